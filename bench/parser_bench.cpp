// FrameParser throughput (bytes/s of stream) in both checksum modes, on a clean
// stream of mixed-size frames and on one with 10 % garbage between frames; the
// garbage case also reports the fraction of intact frames found; and on streams built
// to be slow (issue 19: a preamble every few bytes promising long frames, nested
// false preambles) against random bytes. bytes_per_second is the figure.
//   build/bin/parser_bench [--stream-mib N] [--benchmark_filter=...]
// --stream-mib: the streams' size (default 8 MiB; the smoke test's 1 MiB keeps
// its run short under the sanitizers).
#include <benchmark/benchmark.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <random>
#include <tuple>
#include <vector>

#include "fireswarm/radio/parser.hpp"

namespace {

using fireswarm::radio::AppendFrame;
using fireswarm::radio::ChecksumMode;
using fireswarm::radio::FrameParser;
using fireswarm::radio::FrameView;

std::size_t stream_bytes = std::size_t{8} << 20;  // per pass (--stream-mib)
constexpr std::size_t kReadSize = 4096;           // bytes per Feed(), like a serial read

enum class SizeMix : int {
  kFleet,    // the fleet's traffic: polls, telemetry, fire reports, heartbeats, chunks
  kUniform,  // data sizes uniform in 0..255
};

struct BenchStream {
  std::vector<std::uint8_t> bytes;
  std::vector<std::uint64_t> intact_offsets;  // where each written frame starts
};

std::size_t DataSize(SizeMix mix, std::mt19937_64& rng) {
  const auto uniform = [&rng](int low, int high) {
    return static_cast<std::size_t>(std::uniform_int_distribution(low, high)(rng));
  };
  if (mix == SizeMix::kUniform) return uniform(0, 255);
  // Payload sizes of docs/protocol.md: poll 4, telemetry 41, fire report 38,
  // heartbeat 9, mission chunk 12 + 12 per waypoint.
  const std::size_t kind = uniform(0, 99);
  if (kind < 30) return 4;
  if (kind < 60) return 41;
  if (kind < 75) return 38;
  if (kind < 85) return 9;
  return 12 + 12 * uniform(1, 20);
}

// Frames, with garbage runs (random bytes, a third opening with a false preamble)
// between them making up `garbage_fraction` of the stream on average.
BenchStream MakeStream(ChecksumMode mode, SizeMix mix, double garbage_fraction) {
  std::mt19937_64 rng(42);
  BenchStream stream;
  std::vector<std::uint8_t> data;
  while (stream.bytes.size() < stream_bytes) {
    data.resize(DataSize(mix, rng));
    for (std::uint8_t& byte : data) byte = static_cast<std::uint8_t>(rng());
    const std::size_t before = stream.bytes.size();
    stream.intact_offsets.push_back(before);
    AppendFrame(stream.bytes, static_cast<std::uint8_t>(rng() % 8), 0x10, data, mode);
    if (garbage_fraction <= 0.0) continue;
    const double frame_size = static_cast<double>(stream.bytes.size() - before);
    const double mean = frame_size * garbage_fraction / (1.0 - garbage_fraction);
    auto garbage = static_cast<std::size_t>(std::uniform_real_distribution(0.0, 2.0 * mean)(rng));
    if (garbage >= 6 && rng() % 3 == 0) {
      stream.bytes.insert(stream.bytes.end(), {0x70, 0x96, 0xAC});
      garbage -= 3;
    }
    for (; garbage > 0; --garbage) stream.bytes.push_back(static_cast<std::uint8_t>(rng()));
  }
  return stream;
}

const BenchStream& CachedStream(ChecksumMode mode, SizeMix mix, double garbage_fraction) {
  static std::map<std::tuple<ChecksumMode, SizeMix, double>, BenchStream> cache;
  const auto key = std::tuple(mode, mix, garbage_fraction);
  auto it = cache.find(key);
  if (it == cache.end()) it = cache.emplace(key, MakeStream(mode, mix, garbage_fraction)).first;
  return it->second;
}

void BM_FrameParser(benchmark::State& state, ChecksumMode mode, SizeMix mix,
                    double garbage_fraction) {
  const BenchStream& stream = CachedStream(mode, mix, garbage_fraction);
  const std::span<const std::uint8_t> all(stream.bytes);
  std::uint64_t intact_found = 0;
  std::uint64_t frames = 0;
  for (auto _ : state) {
    FrameParser parser(mode);
    std::size_t next_intact = 0;
    const auto on_frame = [&](const FrameView& frame) {
      // Count a frame as intact only where one was written (coincidental accepts
      // from garbage do not count).
      while (next_intact < stream.intact_offsets.size() &&
             stream.intact_offsets[next_intact] < frame.offset) {
        ++next_intact;
      }
      if (next_intact < stream.intact_offsets.size() &&
          stream.intact_offsets[next_intact] == frame.offset) {
        ++intact_found;
      }
      benchmark::DoNotOptimize(frame.data.data());
    };
    for (std::size_t at = 0; at < all.size(); at += kReadSize) {
      parser.Feed(all.subspan(at, std::min(kReadSize, all.size() - at)), on_frame);
    }
    parser.Finish(on_frame);
    frames += parser.stats().frames;
  }
  const auto passes = static_cast<double>(state.iterations());
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(stream.bytes.size()));
  state.counters["frames_per_pass"] = static_cast<double>(frames) / passes;
  state.counters["intact_found_fraction"] = static_cast<double>(intact_found) / passes /
                                            static_cast<double>(stream.intact_offsets.size());
}

BENCHMARK_CAPTURE(BM_FrameParser, crc16_clean_fleet_mix, ChecksumMode::kCrc16, SizeMix::kFleet,
                  0.0);
BENCHMARK_CAPTURE(BM_FrameParser, crc16_clean_uniform_0_255, ChecksumMode::kCrc16,
                  SizeMix::kUniform, 0.0);
BENCHMARK_CAPTURE(BM_FrameParser, crc16_garbage10_fleet_mix, ChecksumMode::kCrc16, SizeMix::kFleet,
                  0.10);
BENCHMARK_CAPTURE(BM_FrameParser, xor_clean_fleet_mix, ChecksumMode::kXor, SizeMix::kFleet, 0.0);
BENCHMARK_CAPTURE(BM_FrameParser, xor_clean_uniform_0_255, ChecksumMode::kXor, SizeMix::kUniform,
                  0.0);
BENCHMARK_CAPTURE(BM_FrameParser, xor_garbage10_fleet_mix, ChecksumMode::kXor, SizeMix::kFleet,
                  0.10);

// Streams with no intact frame at all, the parser's worst cases and random bytes.
enum class Hostile : int {
  kPreambleEvery3,  // 70 96 AC repeated: a candidate every 3 bytes, length byte 0xAC
  kPreambleFF,      // 70 96 AC FF repeated (the finding): length byte 0x96
  kHeader255,       // 70 96 AC 01 10 FF repeated: full headers with length 255
  kNested,          // false and partial preambles one byte apart
  kRandom,          // uniformly random bytes
};

std::vector<std::uint8_t> MakeHostileStream(Hostile kind) {
  std::vector<std::uint8_t> unit;
  switch (kind) {
    case Hostile::kPreambleEvery3:
      unit = {0x70, 0x96, 0xAC};
      break;
    case Hostile::kPreambleFF:
      unit = {0x70, 0x96, 0xAC, 0xFF};
      break;
    case Hostile::kHeader255:
      unit = {0x70, 0x96, 0xAC, 0x01, 0x10, 0xFF};
      break;
    case Hostile::kNested:
      unit = {0x70, 0x70, 0x96, 0xAC, 0x70, 0x96, 0x70, 0xFF};
      break;
    case Hostile::kRandom: {
      std::mt19937_64 rng(19);
      std::vector<std::uint8_t> bytes(stream_bytes);
      for (std::uint8_t& byte : bytes) byte = static_cast<std::uint8_t>(rng());
      return bytes;
    }
  }
  std::vector<std::uint8_t> bytes;
  bytes.reserve(stream_bytes + unit.size());
  while (bytes.size() < stream_bytes) bytes.insert(bytes.end(), unit.begin(), unit.end());
  return bytes;
}

void BM_FrameParserHostile(benchmark::State& state, ChecksumMode mode, Hostile kind) {
  const std::vector<std::uint8_t> stream = MakeHostileStream(kind);
  const std::span<const std::uint8_t> all(stream);
  std::uint64_t examined = 0;
  for (auto _ : state) {
    FrameParser parser(mode);
    const auto on_frame = [](const FrameView& frame) {
      benchmark::DoNotOptimize(frame.data.data());
    };
    for (std::size_t at = 0; at < all.size(); at += kReadSize) {
      parser.Feed(all.subspan(at, std::min(kReadSize, all.size() - at)), on_frame);
    }
    parser.Finish(on_frame);
    examined += parser.stats().examined_bytes;
  }
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations()) *
                          static_cast<std::int64_t>(stream.size()));
  state.counters["examined_per_byte"] = static_cast<double>(examined) /
                                        static_cast<double>(state.iterations()) /
                                        static_cast<double>(stream.size());
}

BENCHMARK_CAPTURE(BM_FrameParserHostile, crc16_preamble_every_3, ChecksumMode::kCrc16,
                  Hostile::kPreambleEvery3);
BENCHMARK_CAPTURE(BM_FrameParserHostile, crc16_preamble_ff, ChecksumMode::kCrc16,
                  Hostile::kPreambleFF);
BENCHMARK_CAPTURE(BM_FrameParserHostile, crc16_header_255, ChecksumMode::kCrc16,
                  Hostile::kHeader255);
BENCHMARK_CAPTURE(BM_FrameParserHostile, crc16_nested, ChecksumMode::kCrc16, Hostile::kNested);
BENCHMARK_CAPTURE(BM_FrameParserHostile, crc16_random, ChecksumMode::kCrc16, Hostile::kRandom);
BENCHMARK_CAPTURE(BM_FrameParserHostile, xor_preamble_every_3, ChecksumMode::kXor,
                  Hostile::kPreambleEvery3);
BENCHMARK_CAPTURE(BM_FrameParserHostile, xor_header_255, ChecksumMode::kXor, Hostile::kHeader255);
BENCHMARK_CAPTURE(BM_FrameParserHostile, xor_random, ChecksumMode::kXor, Hostile::kRandom);
BENCHMARK_CAPTURE(BM_FrameParserHostile, secure_preamble_every_3, ChecksumMode::kSecure,
                  Hostile::kPreambleEvery3);
BENCHMARK_CAPTURE(BM_FrameParserHostile, secure_header_255, ChecksumMode::kSecure,
                  Hostile::kHeader255);
BENCHMARK_CAPTURE(BM_FrameParserHostile, secure_random, ChecksumMode::kSecure, Hostile::kRandom);

}  // namespace

int main(int argc, char** argv) {
  // --stream-mib N is ours; Google Benchmark is given the other arguments.
  std::vector<char*> args = {argv[0]};
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--stream-mib") == 0 && i + 1 < argc) {
      char* end = nullptr;
      const long mib = std::strtol(argv[++i], &end, 10);
      if (*end != '\0' || mib < 1 || mib > 1024) {
        std::fprintf(stderr, "parser_bench: --stream-mib: an integer in 1..1024, not '%s'\n",
                     argv[i]);
        return 2;
      }
      stream_bytes = static_cast<std::size_t>(mib) << 20;
    } else {
      args.push_back(argv[i]);
    }
  }
  int count = static_cast<int>(args.size());
  benchmark::Initialize(&count, args.data());
  if (benchmark::ReportUnrecognizedArguments(count, args.data())) return 2;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
