// Messages for the codec tests: one sample of every type, on the wire grid (so a
// round trip returns it exactly), and random messages spanning each field's range.
#pragma once

#include <cstdint>
#include <limits>
#include <random>
#include <vector>

#include "fireswarm/radio/messages.hpp"

namespace fireswarm::radio::testing_samples {

inline Telemetry SampleTelemetry() {
  return {.header = {.sender = 3, .sequence = 513},
          .time_ms = 123'456,
          .lat_deg = 47.3977419,
          .lon_deg = 8.5455938,
          .altitude_m = 52.37,
          .velocity_north_mps = 3.21,
          .velocity_east_mps = -1.5,
          .climb_rate_mps = 0.25,
          .roll_deg = -12.34,
          .pitch_deg = 5.67,
          .heading_deg = 271.05,
          .battery_v = 15.123,
          .battery_percent = 87,
          .mode = FlightMode::kSearch,
          .flags = telemetry_flags::kMissionValid | telemetry_flags::kGpsFix,
          .pending_reports = 2,
          .mission_id = 9,
          .waypoint_index = 14};
}

inline SlotSchedule SampleSlotSchedule() {
  SlotSchedule schedule{.header = {.sender = kServerId, .sequence = 42},
                        .first_slot_delay_us = 1'500,
                        .guard_us = 2'000,
                        .slot_count = 2};
  schedule.slots[0] = {.receiver = 1, .reply = ReplyKind::kTelemetry, .slot_bytes = 49};
  schedule.slots[1] = {.receiver = 2, .reply = ReplyKind::kFireReport, .slot_bytes = 46};
  return schedule;
}

inline MissionChunk SampleMissionChunk() {
  MissionChunk chunk{.header = {.sender = kServerId, .sequence = 300},
                     .mission_id = 9,
                     .chunk_index = 1,
                     .chunk_count = 3,
                     .total_waypoints = 45,
                     .first_waypoint = 20,
                     .waypoint_count = 2};
  chunk.waypoints[0] = {47.3977419, 8.5455938, 40.0, 5.5, 1};
  chunk.waypoints[1] = {47.3981, 8.5461, 40.5, 6.0, 0};
  return chunk;
}

/// One message of every type, in the order of the Message variant.
inline std::vector<Message> OnePerType() {
  return {
      Poll{{7, 0x1234}, ReplyKind::kFireReport},
      SampleSlotSchedule(),
      SampleTelemetry(),
      FireReport{{4, 77},
                 5,
                 99'000,
                 -33.8567844,
                 151.2152967,
                 3.5,
                 2.25,
                 -0.1234,
                 -33.8571,
                 151.2149,
                 120.5,
                 37,
                 412.3,
                 0.8},
      FireReportAck{{kServerId, 78}, 4, 5},
      SampleMissionChunk(),
      MissionAck{{2, 301}, 9, 1, MissionAckStatus::kComplete},
      Command{{kServerId, 302},
              CommandType::kInvestigate,
              0,
              -33.8567844,
              151.2152967,
              35.5,
              25.0,
              120},
      CommandAck{{2, 303}, 302, CommandType::kInvestigate, CommandResult::kAccepted},
      ParamRead{{kServerId, 304}, 17},
      ParamWrite{{kServerId, 305}, 17, 0.0125F},
      ParamValue{{2, 306}, 17, 0.0125F, ParamStatus::kOk},
      Heartbeat{{2, 307}, 5'000, FlightMode::kHold, 0x11},
  };
}

/// Random field values, reaching past each wire range so clamping is exercised.
class RandomFields {
 public:
  explicit RandomFields(std::mt19937_64& rng) : rng_(rng) {}
  double Real(double limit) { return std::uniform_real_distribution(-limit, limit)(rng_); }
  template <typename Int>
  Int Integer() {
    return static_cast<Int>(std::uniform_int_distribution<std::uint64_t>(
        0, std::numeric_limits<std::make_unsigned_t<Int>>::max())(rng_));
  }
  template <typename Enum>
  Enum EnumIn(int first, int last) {
    return static_cast<Enum>(std::uniform_int_distribution(first, last)(rng_));
  }
  MessageHeader Header() { return {Integer<std::uint8_t>(), Integer<std::uint16_t>()}; }

 private:
  std::mt19937_64& rng_;
};

/// A random message of a random type.
inline Message Random(std::mt19937_64& rng) {
  RandomFields r(rng);
  switch (std::uniform_int_distribution(0, 12)(rng)) {
    case 0:
      return Poll{r.Header(), r.EnumIn<ReplyKind>(1, 3)};
    case 1: {
      SlotSchedule s{r.Header(), static_cast<std::uint32_t>(r.Integer<std::uint32_t>() >> 15),
                     r.Integer<std::uint16_t>(),
                     static_cast<std::uint8_t>(r.Integer<std::uint8_t>() % 65)};
      for (Slot& slot : s.slots)
        slot = {r.Integer<std::uint8_t>(), r.EnumIn<ReplyKind>(1, 3), r.Integer<std::uint8_t>()};
      return s;
    }
    case 2:
      return Telemetry{r.Header(),
                       r.Integer<std::uint32_t>(),
                       r.Real(250),
                       r.Real(250),
                       r.Real(3e7),
                       r.Real(400),
                       r.Real(400),
                       r.Real(400),
                       r.Real(400),
                       r.Real(400),
                       r.Real(1e4),
                       r.Real(80),
                       r.Integer<std::uint8_t>(),
                       r.EnumIn<FlightMode>(0, 7),
                       r.Integer<std::uint8_t>(),
                       r.Integer<std::uint8_t>(),
                       r.Integer<std::uint16_t>(),
                       r.Integer<std::uint16_t>()};
    case 3:
      return FireReport{r.Header(),
                        r.Integer<std::uint16_t>(),
                        r.Integer<std::uint32_t>(),
                        r.Real(250),
                        r.Real(250),
                        r.Real(800),
                        r.Real(800),
                        r.Real(1.2),
                        r.Real(250),
                        r.Real(250),
                        r.Real(4000),
                        r.Integer<std::uint16_t>(),
                        r.Real(4000),
                        r.Real(1.2)};
    case 4:
      return FireReportAck{r.Header(), r.Integer<std::uint8_t>(), r.Integer<std::uint16_t>()};
    case 5: {
      MissionChunk c{r.Header(),
                     r.Integer<std::uint16_t>(),
                     r.Integer<std::uint8_t>(),
                     r.Integer<std::uint8_t>(),
                     r.Integer<std::uint16_t>(),
                     r.Integer<std::uint16_t>(),
                     static_cast<std::uint8_t>(r.Integer<std::uint8_t>() % 21)};
      for (Waypoint& w : c.waypoints)
        w = {r.Real(250), r.Real(250), r.Real(7000), r.Real(30), r.Integer<std::uint8_t>()};
      return c;
    }
    case 6:
      return MissionAck{r.Header(), r.Integer<std::uint16_t>(), r.Integer<std::uint8_t>(),
                        r.EnumIn<MissionAckStatus>(0, 2)};
    case 7:
      return Command{r.Header(),
                     r.EnumIn<CommandType>(1, 7),
                     r.Integer<std::uint16_t>(),
                     r.Real(250),
                     r.Real(250),
                     r.Real(7000),
                     r.Real(7000),
                     r.Integer<std::uint16_t>()};
    case 8:
      return CommandAck{r.Header(), r.Integer<std::uint16_t>(), r.EnumIn<CommandType>(1, 7),
                        r.EnumIn<CommandResult>(0, 2)};
    case 9:
      return ParamRead{r.Header(), r.Integer<std::uint16_t>()};
    case 10:
      return ParamWrite{r.Header(), r.Integer<std::uint16_t>(), static_cast<float>(r.Real(1e6))};
    case 11:
      return ParamValue{r.Header(), r.Integer<std::uint16_t>(), static_cast<float>(r.Real(1e-3)),
                        r.EnumIn<ParamStatus>(0, 3)};
    default:
      return Heartbeat{r.Header(), r.Integer<std::uint32_t>(), r.EnumIn<FlightMode>(0, 7),
                       r.Integer<std::uint8_t>()};
  }
}

/// The payload bytes of `message`.
inline std::vector<std::uint8_t> Encode(const Message& message) {
  std::vector<std::uint8_t> out;
  EncodePayload(message, out);
  return out;
}

/// Payload bytes of `message` from its count fields and PayloadSize().
inline std::size_t ExpectedPayloadSize(const Message& message) {
  std::size_t entries = 0;
  if (const auto* s = std::get_if<SlotSchedule>(&message)) entries = s->slot_count;
  if (const auto* c = std::get_if<MissionChunk>(&message)) entries = c->waypoint_count;
  return PayloadSize(IdOf(message), entries);
}

}  // namespace fireswarm::radio::testing_samples
