#include "message_json.hpp"

#include <charconv>
#include <iterator>
#include <string_view>
#include <variant>

namespace fireswarm::app {
namespace {

namespace radio = fireswarm::radio;
using Json = nlohmann::ordered_json;

Json TelemetryFlagNames(std::uint8_t flags) {
  namespace bits = radio::telemetry_flags;
  Json names = Json::array();
  if ((flags & bits::kReportPending) != 0) names.push_back("report_pending");
  if ((flags & bits::kMissionValid) != 0) names.push_back("mission_valid");
  if ((flags & bits::kLowBattery) != 0) names.push_back("low_battery");
  if ((flags & bits::kLinkLost) != 0) names.push_back("link_lost");
  if ((flags & bits::kGpsFix) != 0) names.push_back("gps_fix");
  return names;
}

// A float parameter as the shortest decimal that reads back as the same float
// (0.0125F prints as 0.0125, not 0.012500000186264515).
double FloatForJson(float value) {
  char text[32];
  const auto written = std::to_chars(std::begin(text), std::end(text), value);
  double shortest = static_cast<double>(value);
  std::from_chars(std::begin(text), written.ptr, shortest);
  return shortest;
}

Json Header(const radio::MessageHeader& header) {
  return {{"sender", header.sender}, {"sequence", header.sequence}};
}

Json Fields(const radio::Poll& m) {
  Json j = Header(m.header);
  j["reply"] = radio::ToString(m.reply);
  return j;
}

Json Fields(const radio::SlotSchedule& m) {
  Json j = Header(m.header);
  j["first_slot_delay_us"] = m.first_slot_delay_us;
  j["guard_us"] = m.guard_us;
  j["slots"] = Json::array();
  for (const radio::Slot& slot : m.active()) {
    j["slots"].push_back({{"receiver", slot.receiver},
                          {"reply", radio::ToString(slot.reply)},
                          {"slot_bytes", slot.slot_bytes}});
  }
  return j;
}

Json Fields(const radio::Telemetry& m) {
  Json j = Header(m.header);
  j["time_ms"] = m.time_ms;
  j["lat_deg"] = m.lat_deg;
  j["lon_deg"] = m.lon_deg;
  j["altitude_m"] = m.altitude_m;
  j["velocity_north_mps"] = m.velocity_north_mps;
  j["velocity_east_mps"] = m.velocity_east_mps;
  j["climb_rate_mps"] = m.climb_rate_mps;
  j["roll_deg"] = m.roll_deg;
  j["pitch_deg"] = m.pitch_deg;
  j["heading_deg"] = m.heading_deg;
  j["battery_v"] = m.battery_v;
  j["battery_percent"] = m.battery_percent;
  j["mode"] = radio::ToString(m.mode);
  j["flags"] = m.flags;
  j["flag_names"] = TelemetryFlagNames(m.flags);
  j["pending_reports"] = m.pending_reports;
  j["mission_id"] = m.mission_id;
  j["waypoint_index"] = m.waypoint_index;
  return j;
}

Json Fields(const radio::FireReport& m) {
  Json j = Header(m.header);
  j["report_id"] = m.report_id;
  j["time_ms"] = m.time_ms;
  j["lat_deg"] = m.lat_deg;
  j["lon_deg"] = m.lon_deg;
  j["sigma_north_m"] = m.sigma_north_m;
  j["sigma_east_m"] = m.sigma_east_m;
  j["correlation"] = m.correlation;
  j["observer_lat_deg"] = m.observer_lat_deg;
  j["observer_lon_deg"] = m.observer_lon_deg;
  j["observer_altitude_m"] = m.observer_altitude_m;
  j["pixel_count"] = m.pixel_count;
  j["peak_temperature_c"] = m.peak_temperature_c;
  j["confidence"] = m.confidence;
  return j;
}

Json Fields(const radio::FireReportAck& m) {
  Json j = Header(m.header);
  j["vehicle"] = m.vehicle;
  j["report_id"] = m.report_id;
  return j;
}

Json Fields(const radio::MissionChunk& m) {
  Json j = Header(m.header);
  j["mission_id"] = m.mission_id;
  j["chunk_index"] = m.chunk_index;
  j["chunk_count"] = m.chunk_count;
  j["total_waypoints"] = m.total_waypoints;
  j["first_waypoint"] = m.first_waypoint;
  j["waypoints"] = Json::array();
  for (const radio::Waypoint& w : m.active()) {
    j["waypoints"].push_back({{"lat_deg", w.lat_deg},
                              {"lon_deg", w.lon_deg},
                              {"altitude_m", w.altitude_m},
                              {"speed_mps", w.speed_mps},
                              {"flags", w.flags}});
  }
  return j;
}

Json Fields(const radio::MissionAck& m) {
  Json j = Header(m.header);
  j["mission_id"] = m.mission_id;
  j["chunk_index"] = m.chunk_index;
  j["status"] = radio::ToString(m.status);
  return j;
}

Json Fields(const radio::Command& m) {
  Json j = Header(m.header);
  j["type"] = radio::ToString(m.type);
  j["mission_id"] = m.mission_id;
  j["lat_deg"] = m.lat_deg;
  j["lon_deg"] = m.lon_deg;
  j["altitude_m"] = m.altitude_m;
  j["radius_m"] = m.radius_m;
  j["duration_s"] = m.duration_s;
  return j;
}

Json Fields(const radio::CommandAck& m) {
  Json j = Header(m.header);
  j["acked_sequence"] = m.acked_sequence;
  j["type"] = radio::ToString(m.type);
  j["result"] = radio::ToString(m.result);
  return j;
}

Json Fields(const radio::ParamRead& m) {
  Json j = Header(m.header);
  j["param_id"] = m.param_id;
  return j;
}

Json Fields(const radio::ParamWrite& m) {
  Json j = Header(m.header);
  j["param_id"] = m.param_id;
  j["value"] = FloatForJson(m.value);
  return j;
}

Json Fields(const radio::ParamValue& m) {
  Json j = Header(m.header);
  j["param_id"] = m.param_id;
  j["value"] = FloatForJson(m.value);
  j["status"] = radio::ToString(m.status);
  return j;
}

Json Fields(const radio::Heartbeat& m) {
  Json j = Header(m.header);
  j["time_ms"] = m.time_ms;
  j["mode"] = radio::ToString(m.mode);
  j["flags"] = m.flags;
  return j;
}

}  // namespace

nlohmann::ordered_json MessageToJson(const radio::Message& message) {
  return std::visit([](const auto& m) { return Fields(m); }, message);
}

std::string HexString(std::span<const std::uint8_t> bytes) {
  static constexpr std::string_view kDigits = "0123456789abcdef";
  std::string hex;
  hex.reserve(2 * bytes.size());
  for (const std::uint8_t byte : bytes) {
    hex.push_back(kDigits[byte >> 4]);
    hex.push_back(kDigits[byte & 0x0F]);
  }
  return hex;
}

}  // namespace fireswarm::app
