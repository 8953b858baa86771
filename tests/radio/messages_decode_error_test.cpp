// Every DecodeError for every message type: bad payloads are values, never
// exceptions, and decoding never reads past the payload (ASan checks the latter).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <string_view>
#include <utility>
#include <vector>

#include "fireswarm/radio/messages.hpp"
#include "radio/sample_messages.hpp"

namespace fireswarm::radio {
namespace {

using Bytes = std::vector<std::uint8_t>;

using testing_samples::Encode;

// Decodes a copy holding exactly `bytes`, so ASan sees any read past the end.
DecodeResult Decode(std::uint8_t id, const Bytes& bytes) {
  const Bytes exact(bytes);
  return DecodePayload(id, exact);
}

TEST(DecodePayload, EveryLengthOfEveryMessageTypeGivesItsError) {
  for (const Message& message : testing_samples::OnePerType()) {
    const auto id = static_cast<std::uint8_t>(IdOf(message));
    const std::string_view name = *MessageName(id);
    Bytes padded = Encode(message);
    const std::size_t valid_size = padded.size();
    const std::size_t min_size = PayloadSize(IdOf(message), 0);
    const bool variable = id == 0x02 || id == 0x20;
    const std::size_t max_size = PayloadSize(
        IdOf(message), id == 0x02 ? kMaxSlots : (id == 0x20 ? kMaxWaypointsPerChunk : 0));
    padded.resize(kMaxDataSize, 0x00);
    for (std::size_t size = 0; size <= kMaxDataSize; ++size) {
      const Bytes payload(padded.begin(), padded.begin() + static_cast<std::ptrdiff_t>(size));
      DecodeError expected = DecodeError::kNone;
      if (size < min_size) {
        expected = DecodeError::kTooShort;
      } else if (size > max_size) {
        expected = DecodeError::kTooLong;
      } else if (size != valid_size) {
        ASSERT_TRUE(variable);
        expected = DecodeError::kBadValue;  // the count disagrees with the length
      }
      const DecodeResult result = Decode(id, payload);
      EXPECT_EQ(result.error, expected) << name << " with " << size << " bytes";
      EXPECT_EQ(result.message.has_value(), expected == DecodeError::kNone) << name;
    }
  }
}

TEST(DecodePayload, TruncatedAndExtendedPayloadsOfFixedSizeTypes) {
  for (const Message& message : testing_samples::OnePerType()) {
    const auto id = static_cast<std::uint8_t>(IdOf(message));
    if (id == 0x02 || id == 0x20) continue;
    Bytes bytes = Encode(message);
    bytes.pop_back();
    EXPECT_EQ(Decode(id, bytes).error, DecodeError::kTooShort) << *MessageName(id);
    bytes.push_back(0);
    bytes.push_back(0);
    EXPECT_EQ(Decode(id, bytes).error, DecodeError::kTooLong) << *MessageName(id);
  }
}

struct BadByte {
  std::uint8_t message_id;
  std::size_t offset;                // into the sample's payload (docs/protocol.md)
  std::vector<std::uint8_t> values;  // each one alone makes the payload invalid
  std::string_view field;
};

TEST(DecodePayload, EnumsOutOfRangeAreBadValues) {
  const std::vector<BadByte> bad_bytes{
      {0x01, 3, {0, 4, 255}, "Poll.reply"},
      {0x02, 9, {0, 4, 255}, "SlotSchedule.slots[0].reply"},
      {0x02, 12, {0, 4, 255}, "SlotSchedule.slots[1].reply"},
      {0x10, 34, {8, 255}, "Telemetry.mode"},
      {0x21, 6, {3, 255}, "MissionAck.status"},
      {0x30, 3, {0, 9, 255}, "Command.type"},
      {0x31, 5, {0, 9, 255}, "CommandAck.type"},
      {0x31, 6, {3, 255}, "CommandAck.result"},
      {0x42, 9, {4, 255}, "ParamValue.status"},
      {0x50, 7, {8, 255}, "Heartbeat.mode"},
      {0x02, 7, {3, 1, 65, 255}, "SlotSchedule.slot_count"},
      {0x20, 11, {3, 1, 21, 255}, "MissionChunk.waypoint_count"},
  };
  const std::vector<Message> samples = testing_samples::OnePerType();
  for (const BadByte& bad : bad_bytes) {
    const auto sample = std::find_if(samples.begin(), samples.end(), [&](const Message& m) {
      return static_cast<std::uint8_t>(IdOf(m)) == bad.message_id;
    });
    ASSERT_NE(sample, samples.end());
    const Bytes valid = Encode(*sample);
    for (const std::uint8_t value : bad.values) {
      Bytes payload = valid;
      payload.at(bad.offset) = value;
      const DecodeResult result = Decode(bad.message_id, payload);
      EXPECT_EQ(result.error, DecodeError::kBadValue) << bad.field << " = " << int{value};
      EXPECT_FALSE(result.message.has_value());
    }
  }
}

TEST(DecodePayload, HeadingAndCorrelationOutsideTheirRangeAreBadValues) {
  Bytes telemetry = Encode(testing_samples::SampleTelemetry());
  telemetry[29] = 0x9F;  // 35,999 centidegrees: the largest heading
  telemetry[30] = 0x8C;
  EXPECT_EQ(Decode(0x10, telemetry).error, DecodeError::kNone);
  telemetry[29] = 0xA0;  // 36,000 = 360.00 deg: the encoder wraps it to 0
  EXPECT_EQ(Decode(0x10, telemetry).error, DecodeError::kBadValue);

  Bytes report = Encode(testing_samples::OnePerType()[3]);
  for (const auto& [correlation, error] :
       std::vector<std::pair<std::int16_t, DecodeError>>{{10'000, DecodeError::kNone},
                                                         {-10'000, DecodeError::kNone},
                                                         {10'001, DecodeError::kBadValue},
                                                         {-10'001, DecodeError::kBadValue}}) {
    const auto wire = static_cast<std::uint16_t>(correlation);
    report[21] = static_cast<std::uint8_t>(wire & 0xFF);
    report[22] = static_cast<std::uint8_t>(wire >> 8);
    EXPECT_EQ(Decode(0x11, report).error, error) << correlation;
  }
}

TEST(DecodePayload, UnknownMessageIds) {
  int unknown = 0;
  for (int id = 0; id < 256; ++id) {
    const auto message_id = static_cast<std::uint8_t>(id);
    if (MessageName(message_id)) continue;
    ++unknown;
    const DecodeResult result = Decode(message_id, Bytes{0x01, 0x02, 0x03});
    EXPECT_EQ(result.error, DecodeError::kUnknownMessageId) << id;
    EXPECT_FALSE(result.message.has_value());
  }
  EXPECT_EQ(unknown, 256 - 13);
}

TEST(DecodePayload, RandomBytesNeverThrowAndDecodeOnlyToReEncodableMessages) {
  std::mt19937_64 rng(31337);
  std::vector<std::size_t> sample_size(256, 0);
  for (const Message& message : testing_samples::OnePerType()) {
    sample_size[static_cast<std::uint8_t>(IdOf(message))] = Encode(message).size();
  }
  int decoded = 0;
  for (int id = 0; id < 256; ++id) {
    for (int trial = 0; trial < 200; ++trial) {
      // Half the known IDs' trials have a valid length, so the field checks run.
      const std::size_t size =
          sample_size[static_cast<std::size_t>(id)] > 0 && trial % 2 == 0
              ? sample_size[static_cast<std::size_t>(id)]
              : std::uniform_int_distribution<std::size_t>(0, kMaxDataSize)(rng);
      Bytes payload(size);
      for (std::uint8_t& byte : payload) byte = static_cast<std::uint8_t>(rng());
      DecodeResult result;
      ASSERT_NO_THROW(result = Decode(static_cast<std::uint8_t>(id), payload));
      if (!result.message) continue;
      ++decoded;
      Bytes again;
      EncodePayload(*result.message, again);
      EXPECT_EQ(again, payload) << "message ID " << id;
    }
  }
  EXPECT_GT(decoded, 200);  // 345 with this seed
}

TEST(ToString, NamesEveryDecodeError) {
  EXPECT_EQ(ToString(DecodeError::kNone), "none");
  EXPECT_EQ(ToString(DecodeError::kUnknownMessageId), "unknown_message_id");
  EXPECT_EQ(ToString(DecodeError::kTooShort), "too_short");
  EXPECT_EQ(ToString(DecodeError::kTooLong), "too_long");
  EXPECT_EQ(ToString(DecodeError::kBadValue), "bad_value");
}

}  // namespace
}  // namespace fireswarm::radio
