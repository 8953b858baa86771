// FrameParser on any byte stream (issue 19). Input: a mode byte (xor, crc16,
// secure), a chunking seed byte, then the stream. Properties: the stream parsed
// whole and cut into seeded chunks gives the same frames and statistics; every
// frame's bytes are the stream's at its offset; the work stays linear.
#include <array>
#include <cstring>
#include <span>
#include <vector>

#include "fireswarm/radio/parser.hpp"
#include "fuzz_check.hpp"

namespace {

using fireswarm::fuzz::Check;
namespace radio = fireswarm::radio;

struct Found {
  std::uint8_t receiver = 0;
  std::uint8_t message_id = 0;
  std::uint64_t offset = 0;
  std::vector<std::uint8_t> data;
  bool operator==(const Found&) const = default;
};

// Frames and statistics of `stream` fed in chunks whose sizes come from `seed` (0:
// the whole stream at once).
std::vector<Found> ParseStream(radio::ChecksumMode mode, std::span<const std::uint8_t> stream,
                               std::uint8_t seed, radio::ParserStats& stats) {
  radio::FrameParser parser(mode);
  std::vector<Found> found;
  const auto on_frame = [&found](const radio::FrameView& frame) {
    found.push_back({frame.receiver, frame.message_id, frame.offset,
                     std::vector<std::uint8_t>(frame.data.begin(), frame.data.end())});
  };
  std::uint32_t state = seed;
  while (!stream.empty()) {
    std::size_t chunk = stream.size();
    if (seed != 0) {
      state = state * 1103515245U + 12345U;  // a small LCG: chunks of 1..300 bytes
      chunk = std::min<std::size_t>(stream.size(), 1 + (state >> 16) % 300);
    }
    parser.Feed(stream.first(chunk), on_frame);
    stream = stream.subspan(chunk);
  }
  parser.Finish(on_frame);
  stats = parser.stats();
  return found;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 2) return 0;
  const auto mode = static_cast<radio::ChecksumMode>(data[0] % 3);
  const std::uint8_t seed = data[1];
  const std::span<const std::uint8_t> stream(data + 2, size - 2);

  radio::ParserStats whole{};
  const std::vector<Found> frames = ParseStream(mode, stream, 0, whole);
  radio::ParserStats chunked{};
  const std::vector<Found> frames_chunked = ParseStream(mode, stream, seed | 1U, chunked);

  Check(frames == frames_chunked, "chunking changes the frames found");
  Check(whole.frames == chunked.frames && whole.bytes == chunked.bytes &&
            whole.skipped_bytes == chunked.skipped_bytes &&
            whole.checksum_errors == chunked.checksum_errors &&
            whole.truncated_frames == chunked.truncated_frames,
        "chunking changes the statistics");
  Check(whole.bytes == stream.size() && whole.frames == frames.size(), "bytes or frames miscounted");
  // Linear work: checksum states once per byte, inner searches about once, plus
  // retries of candidates that waited on a chunk boundary.
  const std::uint64_t bound = 3 * whole.bytes + radio::kMaxFrameSize;
  Check(whole.examined_bytes <= bound && chunked.examined_bytes <= bound,
        "examined bytes beyond a linear bound");

  const std::size_t data_at = radio::kHeaderSize +
                              (mode == radio::ChecksumMode::kSecure ? radio::kSecureHeaderSize : 0);
  for (const Found& frame : frames) {
    Check(frame.offset + radio::FrameSize(frame.data.size(), mode) <= stream.size(),
          "a frame runs past the stream");
    const std::uint8_t* at = stream.data() + frame.offset;
    Check(std::memcmp(at, radio::kPreamble.data(), radio::kPreamble.size()) == 0 &&
              at[3] == frame.receiver && at[4] == frame.message_id && at[5] == frame.data.size() &&
              (frame.data.empty() ||
               std::memcmp(at + data_at, frame.data.data(), frame.data.size()) == 0),
          "a frame's fields are not the stream's bytes at its offset");
  }
  return 0;
}
