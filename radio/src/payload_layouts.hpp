// The wire layout of every message payload, field by field, in wire order (private
// to the radio module; docs/protocol.md is the byte-by-byte description). Each
// Layout() is walked by a PayloadSizeCounter, PayloadWriter or PayloadReader
// (payload_io.hpp): `m` is const when encoding or counting, mutable when decoding.
// Every payload starts with the 3-byte MessageHeader: sender u8, sequence u16.
#pragma once

#include <concepts>
#include <type_traits>

#include "fireswarm/radio/messages.hpp"
#include "fixed_point.hpp"

namespace fireswarm::radio::detail {

/// `M` is the message struct `T`, const or not.
template <typename M, typename T>
concept MessageOf = std::same_as<std::remove_const_t<M>, T>;

template <typename Io>
constexpr void Layout(Io& io, MessageOf<Poll> auto& m) {
  io.Header(m.header);
  io.EnumValue(m.reply, ReplyKind::kTelemetry, ReplyKind::kAck);
}

template <typename Io>
constexpr void Layout(Io& io, MessageOf<SlotSchedule> auto& m) {
  io.Header(m.header);
  io.ClampedU16(m.first_slot_delay_us);
  io.ClampedU16(m.guard_us);
  io.Count(m.slot_count, kMaxSlots, "SlotSchedule.slot_count");
  for (std::size_t i = 0; i < m.slot_count; ++i) {  // 3 bytes per slot
    io.Integer(m.slots[i].receiver);
    io.EnumValue(m.slots[i].reply, ReplyKind::kTelemetry, ReplyKind::kAck);
    io.Integer(m.slots[i].slot_bytes);
  }
}

template <typename Io>
constexpr void Layout(Io& io, MessageOf<Telemetry> auto& m) {
  io.Header(m.header);
  io.Integer(m.time_ms);
  io.Fixed(m.lat_deg, kE7PerDegree, kI32);
  io.Fixed(m.lon_deg, kE7PerDegree, kI32);
  io.Fixed(m.altitude_m, kCentiPerUnit, kI32);
  io.Fixed(m.velocity_north_mps, kCentiPerUnit, kI16);
  io.Fixed(m.velocity_east_mps, kCentiPerUnit, kI16);
  io.Fixed(m.climb_rate_mps, kCentiPerUnit, kI16);
  io.Fixed(m.roll_deg, kCentiPerUnit, kI16);
  io.Fixed(m.pitch_deg, kCentiPerUnit, kI16);
  io.Heading(m.heading_deg);
  io.Fixed(m.battery_v, kMilliPerUnit, kU16);
  io.Integer(m.battery_percent);
  io.EnumValue(m.mode, FlightMode::kIdle, FlightMode::kHold);
  io.Integer(m.flags);
  io.Integer(m.pending_reports);
  io.Integer(m.mission_id);
  io.Integer(m.waypoint_index);
}

/// Correlation travels in 1e-4 steps and must lie in [-1, 1].
inline constexpr WireRange<std::int16_t> kCorrelationRange{.min = -10'000, .max = 10'000};

template <typename Io>
constexpr void Layout(Io& io, MessageOf<FireReport> auto& m) {
  io.Header(m.header);
  io.Integer(m.report_id);
  io.Integer(m.time_ms);
  io.Fixed(m.lat_deg, kE7PerDegree, kI32);
  io.Fixed(m.lon_deg, kE7PerDegree, kI32);
  io.Fixed(m.sigma_north_m, kCentiPerUnit, kU16);
  io.Fixed(m.sigma_east_m, kCentiPerUnit, kU16);
  io.Fixed(m.correlation, kCorrelationSteps, kCorrelationRange);
  io.Fixed(m.observer_lat_deg, kE7PerDegree, kI32);
  io.Fixed(m.observer_lon_deg, kE7PerDegree, kI32);
  io.Fixed(m.observer_altitude_m, kDeciPerUnit, kI16);
  io.Integer(m.pixel_count);
  io.Fixed(m.peak_temperature_c, kDeciPerUnit, kI16);
  io.Fixed(m.confidence, kConfidenceSteps, kU8);
}

template <typename Io>
constexpr void Layout(Io& io, MessageOf<FireReportAck> auto& m) {
  io.Header(m.header);
  io.Integer(m.vehicle);
  io.Integer(m.report_id);
}

template <typename Io>
constexpr void Layout(Io& io, MessageOf<MissionChunk> auto& m) {
  io.Header(m.header);
  io.Integer(m.mission_id);
  io.Integer(m.chunk_index);
  io.Integer(m.chunk_count);
  io.Integer(m.total_waypoints);
  io.Integer(m.first_waypoint);
  io.Count(m.waypoint_count, kMaxWaypointsPerChunk, "MissionChunk.waypoint_count");
  for (std::size_t i = 0; i < m.waypoint_count; ++i) {  // 12 bytes per waypoint
    auto& waypoint = m.waypoints[i];
    io.Fixed(waypoint.lat_deg, kE7PerDegree, kI32);
    io.Fixed(waypoint.lon_deg, kE7PerDegree, kI32);
    io.Fixed(waypoint.altitude_m, kDeciPerUnit, kU16);
    io.Fixed(waypoint.speed_mps, kDeciPerUnit, kU8);
    io.Integer(waypoint.flags);
  }
}

template <typename Io>
constexpr void Layout(Io& io, MessageOf<MissionAck> auto& m) {
  io.Header(m.header);
  io.Integer(m.mission_id);
  io.Integer(m.chunk_index);
  io.EnumValue(m.status, MissionAckStatus::kAccepted, MissionAckStatus::kRejected);
}

template <typename Io>
constexpr void Layout(Io& io, MessageOf<Command> auto& m) {
  io.Header(m.header);
  io.EnumValue(m.type, CommandType::kStartMission, CommandType::kAvoid);
  io.Integer(m.mission_id);
  io.Fixed(m.lat_deg, kE7PerDegree, kI32);
  io.Fixed(m.lon_deg, kE7PerDegree, kI32);
  io.Fixed(m.altitude_m, kDeciPerUnit, kU16);
  io.Fixed(m.radius_m, kDeciPerUnit, kU16);
  io.Integer(m.duration_s);
}

template <typename Io>
constexpr void Layout(Io& io, MessageOf<CommandAck> auto& m) {
  io.Header(m.header);
  io.Integer(m.acked_sequence);
  io.EnumValue(m.type, CommandType::kStartMission, CommandType::kAvoid);
  io.EnumValue(m.result, CommandResult::kAccepted, CommandResult::kUnsupported);
}

template <typename Io>
constexpr void Layout(Io& io, MessageOf<ParamRead> auto& m) {
  io.Header(m.header);
  io.Integer(m.param_id);
}

template <typename Io>
constexpr void Layout(Io& io, MessageOf<ParamWrite> auto& m) {
  io.Header(m.header);
  io.Integer(m.param_id);
  io.Float32(m.value);
}

template <typename Io>
constexpr void Layout(Io& io, MessageOf<ParamValue> auto& m) {
  io.Header(m.header);
  io.Integer(m.param_id);
  io.Float32(m.value);
  io.EnumValue(m.status, ParamStatus::kOk, ParamStatus::kOutOfRange);
}

template <typename Io>
constexpr void Layout(Io& io, MessageOf<Heartbeat> auto& m) {
  io.Header(m.header);
  io.Integer(m.time_ms);
  io.EnumValue(m.mode, FlightMode::kIdle, FlightMode::kHold);
  io.Integer(m.flags);
}

}  // namespace fireswarm::radio::detail
