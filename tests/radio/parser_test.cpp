#include "fireswarm/radio/parser.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include "radio/frame_capture.hpp"

namespace fireswarm::radio {
namespace {

using testing_frames::AsTuple;
using testing_frames::Bytes;
using testing_frames::CapturedFrame;
using testing_frames::ParseResult;

// Feeds `stream` in chunks of `chunk_size` bytes (0: all at once), then finishes.
ParseResult Parse(const Bytes& stream, ChecksumMode mode, std::size_t chunk_size = 0) {
  return testing_frames::ParseInChunks(stream, mode, [&] {
    return chunk_size == 0 ? std::max<std::size_t>(stream.size(), 1) : chunk_size;
  });
}

Bytes Frame(std::uint8_t receiver, std::uint8_t message_id, const Bytes& data,
            ChecksumMode mode = ChecksumMode::kCrc16) {
  Bytes out;
  AppendFrame(out, receiver, message_id, data, mode);
  return out;
}

Bytes Concat(std::initializer_list<Bytes> parts) {
  Bytes out;
  for (const Bytes& part : parts) out.insert(out.end(), part.begin(), part.end());
  return out;
}

const Bytes kDataA{1, 2, 3, 4, 5};
const Bytes kDataB{0x70, 0x96, 0xAC, 9, 8};  // a false preamble inside data

TEST(FrameParser, DeliversOneFrameWithItsFieldsAndOffset) {
  const Bytes stream = Frame(7, 0x10, kDataA);
  const ParseResult result = Parse(stream, ChecksumMode::kCrc16);
  ASSERT_EQ(result.frames.size(), 1U);
  EXPECT_EQ(result.frames[0], (CapturedFrame{0, 7, 0x10, kDataA}));
  EXPECT_EQ(AsTuple(result.stats), AsTuple({.frames = 1, .bytes = stream.size()}));
}

TEST(FrameParser, FindsFramesInGarbageBeforeBetweenAndAfter) {
  const Bytes garbage1{0x00, 0x70, 0x11, 0x70, 0x96, 0x00};  // includes a broken preamble
  const Bytes garbage2{0xFF, 0xAC, 0x96};
  const Bytes garbage3{0x70, 0x96};  // a preamble start that never completes
  const Bytes frame_a = Frame(1, 0x10, kDataA);
  const Bytes frame_b = Frame(2, 0x11, {});
  const Bytes stream = Concat({garbage1, frame_a, garbage2, frame_b, garbage3});
  const ParseResult result = Parse(stream, ChecksumMode::kCrc16);
  ASSERT_EQ(result.frames.size(), 2U);
  EXPECT_EQ(result.frames[0], (CapturedFrame{garbage1.size(), 1, 0x10, kDataA}));
  EXPECT_EQ(result.frames[1].offset, garbage1.size() + frame_a.size() + garbage2.size());
  EXPECT_EQ(result.stats.skipped_bytes, garbage1.size() + garbage2.size() + garbage3.size());
  EXPECT_EQ(result.stats.checksum_errors, 0U);
  EXPECT_EQ(result.stats.truncated_frames, 0U);
}

TEST(FrameParser, FalsePreambleInsideDataIsNotAFrame) {
  const Bytes stream = Concat({Frame(3, 0x20, kDataB), Frame(4, 0x21, kDataA)});
  const ParseResult result = Parse(stream, ChecksumMode::kCrc16);
  ASSERT_EQ(result.frames.size(), 2U);
  EXPECT_EQ(result.frames[0].data, kDataB);
  EXPECT_EQ(result.stats.skipped_bytes, 0U);
  EXPECT_EQ(result.stats.checksum_errors + result.stats.truncated_frames, 0U);
}

TEST(FrameParser, TruncatedFrameFollowedByValidFrameLosesNothing) {
  const Bytes cut = Frame(5, 0x10, Bytes(40, 0x33));
  const Bytes truncated(cut.begin(), cut.begin() + 20);  // the sender stopped mid-frame
  const Bytes valid = Frame(6, 0x11, kDataA);
  const ParseResult result = Parse(Concat({truncated, valid}), ChecksumMode::kCrc16);
  ASSERT_EQ(result.frames.size(), 1U);
  EXPECT_EQ(result.frames[0], (CapturedFrame{truncated.size(), 6, 0x11, kDataA}));
  EXPECT_EQ(result.stats.truncated_frames, 1U);
  EXPECT_EQ(result.stats.checksum_errors, 0U);
  EXPECT_EQ(result.stats.skipped_bytes, truncated.size());
}

TEST(FrameParser, BadChecksumThenValidFrame) {
  Bytes corrupted = Frame(5, 0x10, kDataA);
  corrupted[8] ^= 0x01;
  const Bytes valid = Frame(6, 0x11, kDataA);
  const ParseResult result = Parse(Concat({corrupted, valid}), ChecksumMode::kCrc16);
  ASSERT_EQ(result.frames.size(), 1U);
  EXPECT_EQ(result.frames[0].offset, corrupted.size());
  EXPECT_EQ(result.stats.checksum_errors, 1U);
  EXPECT_EQ(result.stats.truncated_frames, 0U);
  EXPECT_EQ(result.stats.skipped_bytes, corrupted.size());
}

TEST(FrameParser, FalsePreambleWithLongLengthDoesNotHideTheFramesAfterIt) {
  // 70 96 AC, receiver, ID, length 250: a candidate spanning both valid frames.
  const Bytes false_start{0x70, 0x96, 0xAC, 0x01, 0x10, 250};
  const Bytes stream =
      Concat({false_start, Frame(1, 0x10, kDataA), Frame(2, 0x10, kDataB), Bytes(250, 0x00)});
  const ParseResult result = Parse(stream, ChecksumMode::kCrc16);
  ASSERT_EQ(result.frames.size(), 2U);
  EXPECT_EQ(result.frames[0].offset, false_start.size());
  EXPECT_EQ(result.stats.truncated_frames, 1U);  // a preamble starts inside the candidate
}

TEST(FrameParser, FinishDeliversFramesBufferedBehindACutOffCandidate) {
  const Bytes false_start{0x70, 0x96, 0xAC, 0x01, 0x10, 250};
  const Bytes valid = Frame(9, 0x50, kDataA);
  FrameParser parser(ChecksumMode::kCrc16);
  std::vector<std::uint64_t> offsets;
  const auto on_frame = [&offsets](const FrameView& frame) { offsets.push_back(frame.offset); };
  parser.Feed(Concat({false_start, valid}), on_frame);
  EXPECT_TRUE(offsets.empty());  // still waiting for the 250-byte candidate
  parser.Finish(on_frame);
  EXPECT_EQ(offsets, std::vector<std::uint64_t>{false_start.size()});
  EXPECT_EQ(parser.stats().truncated_frames, 1U);
  EXPECT_EQ(parser.stats().skipped_bytes, false_start.size());
}

TEST(FrameParser, KeepsAPartialPreambleAcrossChunks) {
  const Bytes frame = Frame(1, 0x01, kDataA);
  FrameParser parser(ChecksumMode::kCrc16);
  int frames = 0;
  const auto on_frame = [&frames](const FrameView&) { ++frames; };
  parser.Feed(Concat({Bytes{0x55, 0x55}, Bytes(frame.begin(), frame.begin() + 2)}), on_frame);
  EXPECT_EQ(parser.stats().skipped_bytes, 2U);  // 0x70 0x96 wait for the rest
  parser.Feed(Bytes(frame.begin() + 2, frame.end()), on_frame);
  EXPECT_EQ(frames, 1);
  EXPECT_EQ(parser.stats().skipped_bytes, 2U);
}

TEST(FrameParser, OneByteChunksEqualTheWholeBuffer) {
  Bytes corrupted = Frame(5, 0x10, kDataB);
  corrupted[7] ^= 0x40;
  const Bytes cut = Frame(8, 0x20, Bytes(30, 0x70));
  const Bytes stream =
      Concat({Bytes{0x70, 0x96, 0x01}, Frame(1, 0x10, kDataB), corrupted,
              Bytes(cut.begin(), cut.begin() + 12), Frame(2, 0x11, {}), Bytes{0x70, 0x96, 0xAC},
              Frame(3, 0x12, Bytes(255, 0xAC)), Bytes(cut.begin(), cut.end() - 1)});
  for (const ChecksumMode mode : {ChecksumMode::kCrc16, ChecksumMode::kXor}) {
    const ParseResult whole = Parse(stream, mode);
    for (const std::size_t chunk : {1U, 2U, 3U, 7U, 64U}) {
      const ParseResult chunked = Parse(stream, mode, chunk);
      EXPECT_EQ(chunked.frames, whole.frames) << "chunk " << chunk;
      EXPECT_EQ(AsTuple(chunked.stats), AsTuple(whole.stats)) << "chunk " << chunk;
    }
  }
  const ParseResult whole = Parse(stream, ChecksumMode::kCrc16);
  EXPECT_EQ(whole.frames.size(), 3U);
  EXPECT_EQ(whole.stats.checksum_errors, 1U);
}

TEST(FrameParser, EveryByteIsInAFrameOrSkipped) {
  const Bytes stream = Concat({Bytes{0x70, 0x96, 0xAC, 0x00}, Frame(1, 0x10, kDataA),
                               Bytes{0x70, 0x96, 0xAC, 0x01, 0x02, 0x09, 0x70}});
  const ParseResult result = Parse(stream, ChecksumMode::kCrc16);
  std::uint64_t frame_bytes = 0;
  for (const CapturedFrame& frame : result.frames) {
    frame_bytes += FrameSize(frame.data.size(), ChecksumMode::kCrc16);
  }
  EXPECT_EQ(frame_bytes + result.stats.skipped_bytes, result.stats.bytes);
  EXPECT_EQ(result.stats.bytes, stream.size());
  EXPECT_EQ(result.stats.truncated_frames, 2U);  // both candidates run past the end
}

TEST(FrameParser, SeedXorModeParsesSeedFrames) {
  const Bytes stream = Concat({Frame(3, 0x1D, kDataA, ChecksumMode::kXor), Bytes{0x00}});
  const ParseResult result = Parse(stream, ChecksumMode::kXor);
  ASSERT_EQ(result.frames.size(), 1U);
  EXPECT_EQ(result.frames[0], (CapturedFrame{0, 3, 0x1D, kDataA}));
  // The same bytes are no CRC-16 frame.
  EXPECT_TRUE(Parse(stream, ChecksumMode::kCrc16).frames.empty());
}

TEST(FrameParser, XorModeAcceptsSwappedDataBytesCrc16ModeRejectsThem) {
  const Bytes data{0x10, 0x20, 0x30, 0x40};
  for (const ChecksumMode mode : {ChecksumMode::kXor, ChecksumMode::kCrc16}) {
    Bytes frame = Frame(1, 0x10, data, mode);
    std::swap(frame[kHeaderSize], frame[kHeaderSize + 3]);
    const ParseResult result = Parse(frame, mode);
    if (mode == ChecksumMode::kXor) {
      ASSERT_EQ(result.frames.size(), 1U);  // XOR's blind spot: wrong data delivered
      EXPECT_NE(result.frames[0].data, data);
    } else {
      EXPECT_TRUE(result.frames.empty());
      EXPECT_EQ(result.stats.checksum_errors, 1U);
    }
  }
}

TEST(FrameParser, PushTakesWhatFitsAndNextDrainsIt) {
  Bytes stream;
  for (int i = 0; i < 100; ++i)
    AppendFrame(stream, 1, 0x10, Bytes(100, 0x5A), ChecksumMode::kCrc16);
  FrameParser parser(ChecksumMode::kCrc16);
  std::span<const std::uint8_t> rest(stream);
  int frames = 0;
  while (!rest.empty()) {
    const std::size_t taken = parser.Push(rest);
    ASSERT_GT(taken, 0U);
    EXPECT_LT(taken, stream.size());
    rest = rest.subspan(taken);
    while (parser.Next()) ++frames;
  }
  EXPECT_EQ(frames, 100);
}

TEST(FrameParser, ResetForgetsBufferedBytesStatisticsAndOffsets) {
  FrameParser parser(ChecksumMode::kCrc16);
  const Bytes frame = Frame(1, 0x10, kDataA);
  parser.Feed(Bytes(frame.begin(), frame.begin() + 5), [](const FrameView&) {});
  parser.Reset();
  EXPECT_EQ(AsTuple(parser.stats()), AsTuple(ParserStats{}));
  std::vector<std::uint64_t> offsets;
  parser.Feed(frame, [&offsets](const FrameView& view) { offsets.push_back(view.offset); });
  EXPECT_EQ(offsets, std::vector<std::uint64_t>{0});
}

}  // namespace
}  // namespace fireswarm::radio
