// LCM messages as the server publishes them, for the command center's tests.
#pragma once

#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "fireswarm/common/local_frame.hpp"
#include "fireswarm/fire_track_list_t.hpp"
#include "fireswarm/operator_command_t.hpp"
#include "fireswarm/vehicle_state_t.hpp"

namespace fireswarm::server::test {

inline constexpr common::LatLon kOrigin{46.5, 6.6};

/// A drone heard 0.2 s ago with a fix, searching `offset_m` from kOrigin at `altitude_m`.
inline vehicle_state_t Flying(int id, common::EastNorth offset_m, double altitude_m,
                              std::int64_t utime) {
  const common::LatLon point = common::LocalFrame(kOrigin).ToGeodetic(offset_m);
  vehicle_state_t m{};
  m.utime = utime;
  m.receiver_id = static_cast<std::int16_t>(id);
  m.vehicle_time_ms = utime / 1000;  // a new telemetry sample at every call
  m.has_position = true;
  m.lat_deg = point.lat_deg;
  m.lon_deg = point.lon_deg;
  m.altitude_m = altitude_m;
  m.battery_percent = 80.0;
  m.flight_mode = vehicle_state_t::MODE_SEARCH;
  m.flags = vehicle_state_t::FLAG_GPS_FIX | vehicle_state_t::FLAG_MISSION_VALID;
  m.link_state = vehicle_state_t::LINK_OK;
  m.telemetry_age_s = 0.2;
  m.telemetry_hz = 2.0;
  m.task = vehicle_state_t::TASK_LANE;
  m.lane_index = 1;
  m.lane_count = 3;
  return m;
}

/// A registered vehicle the server never heard: everything unknown.
inline vehicle_state_t NeverHeard(int id, std::int64_t utime) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  vehicle_state_t m{};
  m.utime = utime;
  m.receiver_id = static_cast<std::int16_t>(id);
  m.has_position = false;
  m.lat_deg = kNaN;
  m.lon_deg = kNaN;
  m.altitude_m = kNaN;
  m.link_state = vehicle_state_t::LINK_NEVER_HEARD;
  m.telemetry_age_s = -1.0;
  return m;
}

/// A track at kOrigin, covariance 4 m^2 north, 1 m^2 east, 3 reports, first seen at 40.2 s.
inline fire_track_t Track(int id, std::int8_t status, std::vector<std::int16_t> drones) {
  fire_track_t t{};
  t.utime = 50'000'000;
  t.track_id = id;
  t.status = status;
  t.lat_deg = kOrigin.lat_deg;
  t.lon_deg = kOrigin.lon_deg;
  t.covariance_m2[0][0] = 4.0;
  t.covariance_m2[1][1] = 1.0;
  t.report_count = 3;
  t.vehicle_ids = std::move(drones);
  t.vehicle_count = static_cast<std::int16_t>(t.vehicle_ids.size());
  t.first_seen_utime = 40'200'000;
  t.last_seen_utime = 49'000'000;
  return t;
}

inline fire_track_list_t Tracks(std::int64_t utime, std::vector<fire_track_t> tracks) {
  fire_track_list_t list;
  list.utime = utime;
  list.tracks = std::move(tracks);
  list.track_count = static_cast<std::int32_t>(list.tracks.size());
  return list;
}

}  // namespace fireswarm::server::test
