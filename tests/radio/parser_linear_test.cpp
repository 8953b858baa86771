// FrameParser does work linear in its input on any stream (issue 19): on streams
// built to make a rescanning parser slow (a preamble every few bytes, each with the
// longest length byte; false preambles nested inside false candidates) the bytes it
// runs through a checksum or searches again stay a small multiple of the bytes fed.
// Counted with ParserStats::examined_bytes, not timed: speed is bench/parser_bench's.
// The parser that checksummed every candidate in full examined 45-90 bytes per byte
// fed on the first stream below.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "fireswarm/radio/parser.hpp"
#include "radio/frame_capture.hpp"

namespace fireswarm::radio {
namespace {

using testing_frames::AsTuple;
using testing_frames::Bytes;
using testing_frames::ParseInChunks;

constexpr std::size_t kHostileStreamBytes = 1 << 20;
// Checksum states computed once per byte, the inner preamble search once per byte,
// and a little slack for candidates waiting on a chunk boundary.
constexpr std::uint64_t kMaxExaminedPerByteFed = 3;

Bytes RepeatToHostileSize(const Bytes& unit) {
  Bytes stream;
  stream.reserve(kHostileStreamBytes + unit.size());
  while (stream.size() < kHostileStreamBytes) stream.insert(stream.end(), unit.begin(), unit.end());
  return stream;
}

// The worst streams we know of for a parser that rescans candidates.
std::vector<std::pair<std::string, Bytes>> AdversarialStreams() {
  std::vector<std::pair<std::string, Bytes>> streams;
  // A candidate every 3 bytes, its length byte the preamble's 0xAC.
  streams.emplace_back("preamble_every_3", RepeatToHostileSize({0x70, 0x96, 0xAC}));
  // The finding: a preamble every 4 bytes whose length byte (here the
  // next unit's 0x96) promises the longest frame.
  streams.emplace_back("preamble_ff", RepeatToHostileSize({0x70, 0x96, 0xAC, 0xFF}));
  // Full headers with the longest length: receiver, message ID, length 255.
  streams.emplace_back("header_255", RepeatToHostileSize({0x70, 0x96, 0xAC, 0x01, 0x10, 0xFF}));
  // False preambles nested one byte apart from partial ones (70 70 96 ...), and
  // runs of the first preamble byte that memchr stops on.
  streams.emplace_back("nested", RepeatToHostileSize({0x70, 0x70, 0x96, 0xAC, 0x70, 0x96, 0x70, 0xFF}));
  Bytes runs{0x70, 0x96, 0xAC, 0x00, 0x00, 0xFF};
  runs.resize(runs.size() + 256, 0x70);
  streams.emplace_back("first_byte_runs", RepeatToHostileSize(runs));
  std::mt19937_64 rng(19);
  Bytes random(kHostileStreamBytes);
  for (std::uint8_t& byte : random) byte = static_cast<std::uint8_t>(rng());
  streams.emplace_back("random", random);
  return streams;
}

TEST(FrameParserLinear, ExaminesABoundedMultipleOfTheBytesFedOnAdversarialStreams) {
  for (const ChecksumMode mode : {ChecksumMode::kXor, ChecksumMode::kCrc16, ChecksumMode::kSecure}) {
    for (const auto& [name, stream] : AdversarialStreams()) {
      for (const std::size_t chunk_size : {std::size_t{1}, std::size_t{7}, std::size_t{4096}}) {
        // One-byte chunks cost call overhead per byte; a 64 KiB slice shows their bound.
        const std::size_t size = chunk_size == 1 ? std::size_t{1} << 16 : stream.size();
        const Bytes slice(stream.begin(), stream.begin() + static_cast<std::ptrdiff_t>(size));
        const ParserStats stats = ParseInChunks(slice, mode, [&] { return chunk_size; }).stats;
        EXPECT_EQ(stats.bytes, slice.size());
        EXPECT_LE(stats.examined_bytes, kMaxExaminedPerByteFed * stats.bytes)
            << ToString(mode) << " " << name << " in chunks of " << chunk_size << ": "
            << static_cast<double>(stats.examined_bytes) / static_cast<double>(stats.bytes)
            << " bytes examined per byte fed";
      }
    }
  }
}

TEST(FrameParserLinear, CleanFramesAreChecksummedOnce) {
  for (const ChecksumMode mode : {ChecksumMode::kXor, ChecksumMode::kCrc16}) {
    Bytes stream;
    const Bytes data(200, 0x5A);
    while (stream.size() < kHostileStreamBytes) AppendFrame(stream, 1, 0x10, data, mode);
    const ParserStats stats = ParseInChunks(stream, mode, [] { return std::size_t{4096}; }).stats;
    EXPECT_EQ(stats.checksum_errors, 0U);
    EXPECT_LE(stats.examined_bytes, stats.bytes) << ToString(mode);
  }
}

// The skips that make it linear (to where the inner search stopped, past a candidate
// with no preamble inside) keep the parser's results independent of chunking.
TEST(FrameParserLinear, HostileStreamsGiveTheSameResultsInAnyChunking) {
  for (const ChecksumMode mode : {ChecksumMode::kXor, ChecksumMode::kCrc16, ChecksumMode::kSecure}) {
    for (const auto& [name, stream] : AdversarialStreams()) {
      const Bytes slice(stream.begin(), stream.begin() + (1 << 14));
      const auto whole = ParseInChunks(slice, mode, [&] { return slice.size(); });
      std::mt19937_64 rng(7);
      const auto chunked = ParseInChunks(slice, mode, [&] { return 1 + rng() % 300; });
      EXPECT_EQ(chunked.frames, whole.frames) << ToString(mode) << " " << name;
      EXPECT_EQ(AsTuple(chunked.stats), AsTuple(whole.stats)) << ToString(mode) << " " << name;
    }
  }
}

}  // namespace
}  // namespace fireswarm::radio
