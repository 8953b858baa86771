// One LCM message -> its row of the command center's JSON (docs/command_center.md
// "The state"). Pure functions; CommandCenter keeps the rows and what changed.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>

#include "fireswarm/command_status_t.hpp"
#include "fireswarm/fire_track_t.hpp"
#include "fireswarm/mission_status_t.hpp"
#include "fireswarm/radio_stats_t.hpp"
#include "fireswarm/vehicle_state_t.hpp"

namespace fireswarm::server::internal {

/// Seconds of the publisher's clock from an LCM utime (microseconds).
double UtimeToSeconds(std::int64_t utime);

/// `value` as a JSON number, or null when it is NaN or infinite (JSON has no NaN,
/// and a NaN would never compare equal to itself when rows are diffed).
nlohmann::json Number(double value);

/// The vehicle's colour on the page, "#rrggbb": a fixed palette of 12 colours
/// indexed by (receiver ID - 1) mod 12, so a drone keeps its colour across
/// restarts and replays. Red and orange are left out: they are the fires'.
std::string_view VehicleColour(int receiver_id);

/// Lower-case names of vehicle_state_t's constants ("unknown" for a value the
/// .lcm does not define).
std::string_view ModeName(int flight_mode);
std::string_view LinkName(int link_state);
std::string_view TaskName(int task);

/// What a vehicle's row says (docs/command_center.md "The state"), compared
/// before its JSON is built: states come at the web rate (5 Hz), telemetry at
/// 1-2 Hz, so most states change nothing. A number that is not finite, or a
/// telemetry field before the first telemetry, is nullopt (null in the JSON).
struct VehicleFields {
  int id = 0;
  std::optional<int> mode;  ///< nullopt before the first telemetry
  std::optional<double> lat_deg;
  std::optional<double> lon_deg;  ///< both or neither
  std::optional<double> altitude_m;
  std::optional<double> speed_mps;  ///< horizontal, from the velocity
  std::optional<double> heading_deg;
  std::optional<double> battery_percent;
  int link = 0;
  /// When the latest telemetry came, s of the publisher's clock (utime - telemetry
  /// age), to the millisecond: the page shows its age against the state's time_s.
  std::optional<double> heard_s;
  std::optional<double> telemetry_hz;
  std::optional<double> progress;
  int task = 0;
  int lane_index = 0;
  int lane_count = 0;
  int track_id = 0;
  bool operator==(const VehicleFields&) const = default;
};
VehicleFields FieldsOf(const vehicle_state_t& message);

/// What the vehicle is doing, for a human: "lane 4 of 12", "investigating fire 2",
/// "investigating a point", "returning", ...
std::string TaskText(const VehicleFields& fields);

/// The vehicle's row without "trail": id, colour, mode, position ([lat, lon] or
/// null without a fix), altitude_m, speed_mps, heading_deg, battery_percent,
/// link, heard_s, telemetry_hz, progress, task, task_text, track_id. With
/// `before` (the row a client has), only id and the fields that differ from it
/// (task, task_text and track_id go together).
nlohmann::json VehicleRow(const VehicleFields& fields, const VehicleFields* before = nullptr);

/// The 2-sigma ellipse of a north/east covariance (fire_track_t.covariance_m2,
/// index 0 = north, 1 = east), m^2: {"semi_major_m", "semi_minor_m",
/// "bearing_deg"}, the bearing of the major axis clockwise from north in [0, 180).
/// Null when the covariance is not finite.
nlohmann::json Ellipse2Sigma(const double (&covariance_ne_m2)[2][2]);

std::string_view TrackStatusName(int status);
/// id, status, position, ellipse, reports, drones, first_seen_s, last_seen_s.
nlohmann::json TrackRow(const fire_track_t& track);

std::string_view MissionStateName(int state);
/// state, mission_id, coverage, elapsed_s, vehicles_active, vehicles_lost,
/// fires_tentative, fires_confirmed.
nlohmann::json MissionJson(const mission_status_t& message);

/// busy_fraction, payload_bytes_per_s, the counters, telemetry_age_s by ID ("3": 0.4).
nlohmann::json RadioJson(const radio_stats_t& message);

/// The command kinds of POST /api/command, by operator_command_t constant.
std::string_view CommandKindName(int command);
std::string_view CommandStateName(int state);
/// id, kind, targets [{vehicle, state}], state (failed when any target failed,
/// else the least advanced target's; acknowledged without targets), time_s, reason.
nlohmann::json CommandRow(const command_status_t& message);

}  // namespace fireswarm::server::internal
