// Streaming parser for APOne frames (seed 5.3.4). Bytes arrive in any chunking;
// the parser finds frames in garbage, survives truncated frames, false preambles
// and bad checksums, and never loses the next valid frame after an error: after a
// failed candidate it goes on at the next preamble after that candidate's first byte.
// It owns one fixed buffer and allocates nothing while parsing. Its work is linear in
// the bytes fed on any stream, however many false candidates overlap: each buffered
// byte enters a running checksum once and a candidate's checksum comes from the
// running states at its ends (radio/src/range_checksum.hpp).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>

#include "fireswarm/radio/frame.hpp"

namespace fireswarm::radio {

/// What the parser has seen since construction (or Reset()).
struct ParserStats {
  std::uint64_t frames = 0;            ///< valid frames delivered
  std::uint64_t bytes = 0;             ///< bytes fed
  std::uint64_t skipped_bytes = 0;     ///< bytes that belonged to no valid frame
  std::uint64_t checksum_errors = 0;   ///< complete candidates whose checksum did not match
  std::uint64_t truncated_frames = 0;  ///< candidates cut short: a new preamble inside them, or
                                       ///< the stream ended mid-frame (counted by Finish())
  /// Work done: bytes run through a checksum or searched for a preamble inside a failed
  /// candidate. At most a small multiple of `bytes` on any stream (the parser is linear
  /// in its input; tests/radio/parser_linear_test.cpp bounds it).
  std::uint64_t examined_bytes = 0;
};

class FrameParser {
 public:
  explicit FrameParser(ChecksumMode mode);

  /// Feeds `bytes` and calls `on_frame(const FrameView&)` for every valid frame, in
  /// stream order. The view is valid only during the call.
  template <typename OnFrame>
  void Feed(std::span<const std::uint8_t> bytes, OnFrame&& on_frame) {
    while (!bytes.empty()) {
      const std::size_t taken = Push(bytes);
      bytes = bytes.subspan(taken);
      while (const std::optional<FrameView> frame = Next()) on_frame(*frame);
    }
  }

  /// Lower-level interface behind Feed(): copies as many of `bytes` into the
  /// parser's buffer as fit and returns how many it took. Call Next() until it
  /// returns nullopt before pushing more.
  std::size_t Push(std::span<const std::uint8_t> bytes);
  /// The next valid frame in the buffered bytes, or nullopt when more bytes are
  /// needed. The view is valid until the next Push()/Next()/Finish().
  std::optional<FrameView> Next();

  /// End of stream: a partial frame still buffered counts as truncated, and the
  /// bytes after its first preamble byte are scanned again, so valid frames buffered
  /// behind it (a short frame after a cut-off long one) still reach `on_frame`. Bytes
  /// in no valid frame count as skipped. The parser is then empty and can be fed again.
  template <typename OnFrame>
  void Finish(OnFrame&& on_frame) {
    while (const std::optional<FrameView> frame = Scan(/*end_of_stream=*/true)) on_frame(*frame);
    begin_ = end_ = 0;
    ForgetStates();
  }
  /// Finish() for callers that need no frames any more: frames still found in the
  /// buffered tail are counted in stats() but not delivered.
  void Finish() {
    Finish([](const FrameView&) {});
  }
  /// Forgets buffered bytes and statistics.
  void Reset();

  ChecksumMode mode() const { return mode_; }
  const ParserStats& stats() const { return stats_; }

 private:
  // Room for a maximal frame plus a window of new bytes; see Push().
  static constexpr std::size_t kBufferSize = 4096;

  // Next() and Finish(): at the end of the stream a candidate that cannot complete
  // is truncated instead of waited for.
  std::optional<FrameView> Scan(bool end_of_stream);
  // Checksum of buffer bytes [first, last) from the running states, extending them.
  std::uint16_t RangeChecksum(std::size_t first, std::size_t last);
  // Drops the running states (the bytes they cover are gone).
  void ForgetStates() { states_first_ = kNoStates; }

  static constexpr std::size_t kNoStates = kBufferSize + 1;

  ChecksumMode mode_;
  ParserStats stats_;
  std::array<std::uint8_t, kBufferSize> buffer_{};
  std::size_t begin_ = 0;  // first unconsumed byte
  std::size_t end_ = 0;    // one past the last buffered byte
  // Running checksum state before buffer byte i, for i in [states_first_, states_last_]
  // (none when states_first_ == kNoStates): every candidate's checksum in O(1).
  std::array<std::uint16_t, kBufferSize + 1> states_{};
  std::size_t states_first_ = kNoStates;
  std::size_t states_last_ = 0;
  // The failed candidate whose inner preamble search waits on a partial preamble at
  // the end of the buffer: its stream offset and the bytes after its first byte
  // already searched, so a retry with more bytes does not search them again.
  struct InnerSearchResume {
    std::uint64_t candidate_offset = UINT64_MAX;
    std::size_t searched = 0;
  };
  InnerSearchResume resume_;
};

}  // namespace fireswarm::radio
