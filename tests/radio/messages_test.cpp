// Message payload codec: round trips, pinned wire bytes, rounding and clamping.
// Decode errors are in messages_decode_error_test.cpp.
#include "fireswarm/radio/messages.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <stdexcept>
#include <vector>

#include "fireswarm/radio/parser.hpp"
#include "radio/sample_messages.hpp"

namespace fireswarm::radio {
namespace {

using Bytes = std::vector<std::uint8_t>;

using testing_samples::Encode;

template <typename M>
M RoundTrip(const M& message) {
  const Bytes bytes = Encode(message);
  const DecodeResult result = DecodePayload(static_cast<std::uint8_t>(IdOf(message)), bytes);
  EXPECT_EQ(result.error, DecodeError::kNone);
  return std::get<M>(result.message.value());
}

TEST(EncodePayload, DecodeOfEncodeGivesEveryMessageTypeBack) {
  const std::vector<Message> samples = testing_samples::OnePerType();
  ASSERT_EQ(samples.size(), std::variant_size_v<Message>);
  for (const Message& message : samples) {
    const Bytes bytes = Encode(message);
    const DecodeResult result = DecodePayload(static_cast<std::uint8_t>(IdOf(message)), bytes);
    const std::string_view name = *MessageName(static_cast<std::uint8_t>(IdOf(message)));
    ASSERT_EQ(result.error, DecodeError::kNone) << name;
    // The samples lie on the wire grid, so nothing is lost to quantisation.
    EXPECT_EQ(result.message, message) << name;
    EXPECT_EQ(Encode(*result.message), bytes);
  }
}

TEST(EncodePayload, RandomMessagesRoundTripAfterQuantisation) {
  std::mt19937_64 rng(2024);
  for (int i = 0; i < 20'000; ++i) {
    const Message message = testing_samples::Random(rng);
    const auto id = static_cast<std::uint8_t>(IdOf(message));
    const Bytes bytes = Encode(message);
    ASSERT_EQ(bytes.size(), testing_samples::ExpectedPayloadSize(message));
    const DecodeResult decoded = DecodePayload(id, bytes);
    ASSERT_EQ(decoded.error, DecodeError::kNone) << *MessageName(id);
    // encode(decode(bytes)) == bytes, and the quantised message is a fixed point.
    ASSERT_EQ(Encode(*decoded.message), bytes) << *MessageName(id);
    ASSERT_EQ(DecodePayload(id, bytes).message, decoded.message) << *MessageName(id);
  }
}

TEST(EncodePayload, PollFrameBytesArePinned) {
  const Poll poll{.header = {.sender = 0, .sequence = 0x1234}, .reply = ReplyKind::kFireReport};
  Bytes xor_frame;
  AppendMessageFrame(xor_frame, 5, poll, ChecksumMode::kXor);
  // preamble | receiver 5 | ID 0x01 | length 4 | sender 0, sequence 34 12, reply 2 | XOR
  // 05 ^ 01 ^ 04 ^ 00 ^ 34 ^ 12 ^ 02 = 0x24.
  EXPECT_EQ(xor_frame, (Bytes{0x70, 0x96, 0xAC, 0x05, 0x01, 0x04, 0x00, 0x34, 0x12, 0x02, 0x24}));
  Bytes crc_frame;
  AppendMessageFrame(crc_frame, 5, poll, ChecksumMode::kCrc16);
  // CRC-16/CCITT-FALSE of 05 01 04 00 34 12 02 is 0x18F9, sent F9 18.
  EXPECT_EQ(crc_frame,
            (Bytes{0x70, 0x96, 0xAC, 0x05, 0x01, 0x04, 0x00, 0x34, 0x12, 0x02, 0xF9, 0x18}));
}

TEST(EncodePayload, TelemetryBytesArePinned) {
  const Bytes expected{
      0x03, 0x01, 0x02,        // sender 3, sequence 513
      0x40, 0xE2, 0x01, 0x00,  // time 123,456 ms
      0x4B, 0x52, 0x40, 0x1C,  // lat 47.3977419 deg = 473,977,419 x 1e-7
      0x42, 0xF4, 0x17, 0x05,  // lon 8.5455938 deg = 85,455,938 x 1e-7
      0x75, 0x14, 0x00, 0x00,  // altitude 52.37 m = 5,237 cm
      0x41, 0x01,              // north 3.21 m/s = 321 cm/s
      0x6A, 0xFF,              // east -1.5 m/s = -150 cm/s
      0x19, 0x00,              // climb 0.25 m/s = 25 cm/s
      0x2E, 0xFB,              // roll -12.34 deg = -1,234 x 0.01 deg
      0x37, 0x02,              // pitch 5.67 deg = 567
      0xE1, 0x69,              // heading 271.05 deg = 27,105
      0x13, 0x3B,              // battery 15.123 V = 15,123 mV
      0x57,                    // 87 %
      0x02,                    // mode search
      0x12,                    // flags mission valid | GPS fix
      0x02,                    // 2 reports pending
      0x09, 0x00,              // mission 9
      0x0E, 0x00,              // waypoint 14
  };
  EXPECT_EQ(Encode(testing_samples::SampleTelemetry()), expected);
}

TEST(EncodePayload, SlotScheduleAndMissionChunkBytesArePinned) {
  const SlotSchedule schedule = testing_samples::SampleSlotSchedule();
  EXPECT_EQ(Encode(schedule), (Bytes{0x00, 0x2A, 0x00,     // sender 0, sequence 42
                                     0xDC, 0x05,           // first slot after 1,500 us
                                     0xD0, 0x07,           // guard 2,000 us
                                     0x02,                 // 2 slots
                                     0x01, 0x01, 0x31,     // vehicle 1, telemetry, 49 bytes
                                     0x02, 0x02, 0x2E}));  // vehicle 2, fire report, 46 bytes
  MissionChunk chunk = testing_samples::SampleMissionChunk();
  chunk.waypoint_count = 1;
  EXPECT_EQ(Encode(chunk), (Bytes{0x00, 0x2C, 0x01,        // sender 0, sequence 300
                                  0x09, 0x00, 0x01, 0x03,  // mission 9, chunk 1 of 3
                                  0x2D, 0x00, 0x14, 0x00,  // 45 waypoints, this one is #20
                                  0x01,                    // 1 waypoint:
                                  0x4B, 0x52, 0x40, 0x1C,  //   lat 47.3977419 deg
                                  0x42, 0xF4, 0x17, 0x05,  //   lon 8.5455938 deg
                                  0x90, 0x01,              //   40.0 m = 400 dm
                                  0x37,                    //   5.5 m/s = 55 x 0.1 m/s
                                  0x01}));                 //   flags: lane start
}

TEST(EncodePayload, RoundsToNearestAndClampsToTheWireRange) {
  Telemetry t;
  t.lat_deg = std::numeric_limits<double>::quiet_NaN();
  t.lon_deg = -1e300;
  t.altitude_m = std::numeric_limits<double>::infinity();
  t.velocity_north_mps = 0.006;  // 0.6 cm/s -> 1 cm/s
  t.velocity_east_mps = -0.004;  // -0.4 cm/s -> 0
  t.climb_rate_mps = 1e9;
  t.roll_deg = -1e9;
  t.battery_v = -3.0;
  const Telemetry q = RoundTrip(t);
  EXPECT_EQ(q.lat_deg, 0.0);  // NaN encodes as 0
  EXPECT_EQ(q.lon_deg, std::numeric_limits<std::int32_t>::min() / 1e7);
  EXPECT_EQ(q.altitude_m, std::numeric_limits<std::int32_t>::max() / 100.0);
  EXPECT_EQ(q.velocity_north_mps, 0.01);
  EXPECT_EQ(q.velocity_east_mps, 0.0);
  EXPECT_EQ(q.climb_rate_mps, 327.67);
  EXPECT_EQ(q.roll_deg, -327.68);
  EXPECT_EQ(q.battery_v, 0.0);

  FireReport report;
  report.correlation = 1.5;
  report.confidence = 2.0;
  report.sigma_north_m = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(RoundTrip(report).correlation, 1.0);
  EXPECT_EQ(RoundTrip(report).confidence, 1.0);
  EXPECT_EQ(RoundTrip(report).sigma_north_m, 0.0);
  report.correlation = -7.0;
  EXPECT_EQ(RoundTrip(report).correlation, -1.0);

  SlotSchedule schedule;
  schedule.first_slot_delay_us = 70'000;
  EXPECT_EQ(RoundTrip(schedule).first_slot_delay_us, 65'535U);
}

TEST(EncodePayload, WrapsHeadingIntoZeroTo360) {
  const auto heading = [](double heading_deg) {
    Telemetry t;
    t.heading_deg = heading_deg;
    return RoundTrip(t).heading_deg;
  };
  EXPECT_EQ(heading(-90.0), 270.0);
  EXPECT_EQ(heading(720.25), 0.25);
  EXPECT_EQ(heading(359.996), 0.0);  // rounds up to 360.00, which is 0
  EXPECT_EQ(heading(-0.004), 0.0);
  EXPECT_EQ(heading(-0.006), 359.99);
  EXPECT_EQ(heading(1e300), heading(std::fmod(1e300, 360.0)));
  EXPECT_EQ(heading(std::numeric_limits<double>::quiet_NaN()), 0.0);
  EXPECT_EQ(heading(-std::numeric_limits<double>::infinity()), 0.0);
}

TEST(EncodePayload, ThrowsWhenACountExceedsTheCapacityAndLeavesOutputAlone) {
  SlotSchedule schedule;
  schedule.slot_count = kMaxSlots + 1;
  Bytes out{0xAA};
  EXPECT_THROW(EncodePayload(schedule, out), std::invalid_argument);
  EXPECT_EQ(out, Bytes{0xAA});
  MissionChunk chunk;
  chunk.waypoint_count = kMaxWaypointsPerChunk + 1;
  EXPECT_THROW(AppendMessageFrame(out, 1, chunk, ChecksumMode::kCrc16), std::invalid_argument);
  EXPECT_EQ(out, Bytes{0xAA});
}

TEST(PayloadSize, MatchesDocsProtocolMd) {
  EXPECT_EQ(PayloadSize(MessageId::kPoll), 4U);
  EXPECT_EQ(PayloadSize(MessageId::kSlotSchedule, 0), 8U);
  EXPECT_EQ(PayloadSize(MessageId::kSlotSchedule, kMaxSlots), 8U + 3U * 64U);
  EXPECT_EQ(PayloadSize(MessageId::kTelemetry), 41U);
  EXPECT_EQ(PayloadSize(MessageId::kFireReport), 38U);
  EXPECT_EQ(PayloadSize(MessageId::kFireReportAck), 6U);
  EXPECT_EQ(PayloadSize(MessageId::kMissionChunk, 0), 12U);
  EXPECT_EQ(PayloadSize(MessageId::kMissionChunk, kMaxWaypointsPerChunk), 12U + 12U * 20U);
  EXPECT_EQ(PayloadSize(MessageId::kMissionAck), 7U);
  EXPECT_EQ(PayloadSize(MessageId::kCommand), 20U);
  EXPECT_EQ(PayloadSize(MessageId::kCommandAck), 7U);
  EXPECT_EQ(PayloadSize(MessageId::kParamRead), 5U);
  EXPECT_EQ(PayloadSize(MessageId::kParamWrite), 9U);
  EXPECT_EQ(PayloadSize(MessageId::kParamValue), 10U);
  EXPECT_EQ(PayloadSize(MessageId::kHeartbeat), 9U);
  EXPECT_THROW(PayloadSize(static_cast<MessageId>(0x99)), std::invalid_argument);
}

TEST(MessageName, NamesEveryKnownIdAndNoOther) {
  int known = 0;
  for (int id = 0; id < 256; ++id) known += MessageName(static_cast<std::uint8_t>(id)) ? 1 : 0;
  EXPECT_EQ(known, 13);
  EXPECT_EQ(MessageName(0x10), "telemetry");
  EXPECT_EQ(MessageName(0x02), "slot_schedule");
  EXPECT_EQ(MessageName(0x42), "param_value");
  EXPECT_FALSE(MessageName(0x00).has_value());
}

TEST(IdOf, AndHeaderOfReadTheVariant) {
  for (const Message& message : testing_samples::OnePerType()) {
    const auto id = static_cast<std::uint8_t>(IdOf(message));
    EXPECT_EQ(DecodePayload(id, Encode(message)).message->index(), message.index());
    EXPECT_EQ(HeaderOf(message), std::visit([](const auto& m) { return m.header; }, message));
  }
  EXPECT_EQ(IdOf(Heartbeat{}), MessageId::kHeartbeat);
}

TEST(AppendMessageFrame, FramesEveryTypeForTheParser) {
  Bytes stream;
  const std::vector<Message> samples = testing_samples::OnePerType();
  for (const Message& message : samples)
    AppendMessageFrame(stream, 7, message, ChecksumMode::kCrc16);
  FrameParser parser(ChecksumMode::kCrc16);
  std::vector<Message> decoded;
  parser.Feed(stream, [&decoded](const FrameView& frame) {
    EXPECT_EQ(frame.receiver, 7);
    decoded.push_back(DecodePayload(frame.message_id, frame.data).message.value());
  });
  EXPECT_EQ(decoded, samples);
}

}  // namespace
}  // namespace fireswarm::radio
