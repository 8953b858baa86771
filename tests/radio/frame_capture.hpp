// Parsing a whole byte stream into comparable values, for the FrameParser tests.
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <tuple>
#include <vector>

#include "fireswarm/radio/parser.hpp"

namespace fireswarm::radio::testing_frames {

using Bytes = std::vector<std::uint8_t>;

/// A delivered frame, copied out of the parser's buffer.
struct CapturedFrame {
  std::uint64_t offset = 0;
  std::uint8_t receiver = 0;
  std::uint8_t message_id = 0;
  Bytes data;
  friend bool operator==(const CapturedFrame&, const CapturedFrame&) = default;
};

struct ParseResult {
  std::vector<CapturedFrame> frames;
  ParserStats stats;
};

/// ParserStats as a comparable, printable tuple.
inline auto AsTuple(const ParserStats& s) {
  return std::tuple(s.frames, s.bytes, s.skipped_bytes, s.checksum_errors, s.truncated_frames);
}

/// Feeds `stream` in chunks of next_chunk_size() bytes (at least 1), then finishes.
template <typename NextChunkSize>
ParseResult ParseInChunks(const Bytes& stream, ChecksumMode mode, NextChunkSize next_chunk_size) {
  FrameParser parser(mode);
  ParseResult result;
  const auto capture = [&result](const FrameView& f) {
    result.frames.push_back(
        {f.offset, f.receiver, f.message_id, Bytes(f.data.begin(), f.data.end())});
  };
  const std::span<const std::uint8_t> all(stream);
  for (std::size_t at = 0; at < stream.size();) {
    const std::size_t size = std::min<std::size_t>(next_chunk_size(), stream.size() - at);
    parser.Feed(all.subspan(at, size), capture);
    at += size;
  }
  parser.Finish(capture);
  result.stats = parser.stats();
  return result;
}

}  // namespace fireswarm::radio::testing_frames
