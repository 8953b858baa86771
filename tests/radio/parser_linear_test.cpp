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

namespace fireswarm::radio {
namespace {

constexpr std::size_t kStreamBytes = 1 << 20;
// Checksum states computed once per byte, the inner preamble search once per byte,
// and a little slack for candidates waiting on a chunk boundary.
constexpr std::uint64_t kMaxExaminedPerByte = 3;

using Bytes = std::vector<std::uint8_t>;

Bytes Repeat(const Bytes& unit) {
  Bytes stream;
  stream.reserve(kStreamBytes + unit.size());
  while (stream.size() < kStreamBytes) stream.insert(stream.end(), unit.begin(), unit.end());
  return stream;
}

// The worst streams we know of for a parser that rescans candidates.
std::vector<std::pair<std::string, Bytes>> AdversarialStreams() {
  std::vector<std::pair<std::string, Bytes>> streams;
  // A candidate every 3 bytes, its length byte the preamble's 0xAC.
  streams.emplace_back("preamble_every_3", Repeat({0x70, 0x96, 0xAC}));
  // The finding: a preamble every 4 bytes whose length byte (here the
  // next unit's 0x96) promises the longest frame.
  streams.emplace_back("preamble_ff", Repeat({0x70, 0x96, 0xAC, 0xFF}));
  // Full headers with the longest length: receiver, message ID, length 255.
  streams.emplace_back("header_255", Repeat({0x70, 0x96, 0xAC, 0x01, 0x10, 0xFF}));
  // False preambles nested one byte apart from partial ones (70 70 96 ...), and
  // runs of the first preamble byte that memchr stops on.
  streams.emplace_back("nested", Repeat({0x70, 0x70, 0x96, 0xAC, 0x70, 0x96, 0x70, 0xFF}));
  Bytes runs{0x70, 0x96, 0xAC, 0x00, 0x00, 0xFF};
  runs.resize(runs.size() + 256, 0x70);
  streams.emplace_back("first_byte_runs", Repeat(runs));
  std::mt19937_64 rng(19);
  Bytes random(kStreamBytes);
  for (std::uint8_t& byte : random) byte = static_cast<std::uint8_t>(rng());
  streams.emplace_back("random", random);
  return streams;
}

ParserStats ParseInChunks(ChecksumMode mode, const Bytes& stream, std::size_t chunk_size) {
  FrameParser parser(mode);
  for (std::size_t at = 0; at < stream.size(); at += chunk_size) {
    const std::size_t size = std::min(chunk_size, stream.size() - at);
    parser.Feed(std::span<const std::uint8_t>(stream).subspan(at, size), [](const FrameView&) {});
  }
  parser.Finish();
  return parser.stats();
}

TEST(FrameParserLinear, ExaminesABoundedMultipleOfTheBytesFedOnAdversarialStreams) {
  for (const ChecksumMode mode : {ChecksumMode::kXor, ChecksumMode::kCrc16, ChecksumMode::kSecure}) {
    for (const auto& [name, stream] : AdversarialStreams()) {
      for (const std::size_t chunk_size : {std::size_t{1}, std::size_t{7}, std::size_t{4096}}) {
        // One-byte chunks cost call overhead per byte; a 64 KiB slice shows their bound.
        const std::size_t size = chunk_size == 1 ? std::size_t{1} << 16 : stream.size();
        const Bytes slice(stream.begin(), stream.begin() + static_cast<std::ptrdiff_t>(size));
        const ParserStats stats = ParseInChunks(mode, slice, chunk_size);
        EXPECT_EQ(stats.bytes, slice.size());
        EXPECT_LE(stats.examined_bytes, kMaxExaminedPerByte * stats.bytes)
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
    while (stream.size() < kStreamBytes) AppendFrame(stream, 1, 0x10, data, mode);
    const ParserStats stats = ParseInChunks(mode, stream, 4096);
    EXPECT_EQ(stats.checksum_errors, 0U);
    EXPECT_LE(stats.examined_bytes, stats.bytes) << ToString(mode);
  }
}

}  // namespace
}  // namespace fireswarm::radio
