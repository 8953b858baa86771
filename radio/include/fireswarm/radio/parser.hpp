// Streaming parser for APOne frames (seed 5.3.4). Bytes arrive in any chunking;
// the parser finds frames in garbage, survives truncated frames, false preambles
// and bad checksums, and never loses the next valid frame after an error: after a
// failed candidate it rescans from the byte after that candidate's preamble.
// It owns one fixed buffer and allocates nothing while parsing.
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

  ChecksumMode mode_;
  ParserStats stats_;
  std::array<std::uint8_t, kBufferSize> buffer_{};
  std::size_t begin_ = 0;  // first unconsumed byte
  std::size_t end_ = 0;    // one past the last buffered byte
};

}  // namespace fireswarm::radio
