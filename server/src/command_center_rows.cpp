// LCM messages -> the command center's JSON rows. Pure.
#include "command_center_rows.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "fireswarm/common/angles.hpp"
#include "fireswarm/common/time.hpp"
#include "fireswarm/operator_command_t.hpp"

namespace fireswarm::server::internal {

namespace {

// Tableau/d3 colours without the fire colours (red, orange), then darker and
// lighter variants of the same hues: 12 that stay apart on a satellite or
// topographic map.
constexpr std::array<std::string_view, 12> kPalette = {"#1f77b4", "#2ca02c", "#9467bd", "#8c564b",
                                                       "#e377c2", "#17becf", "#bcbd22", "#7f7f7f",
                                                       "#393b79", "#637939", "#aec7e8", "#98df8a"};

// The ellipse holding a Gaussian's 2-sigma contour: semi-axes 2 sqrt(eigenvalue).
constexpr double kEllipseSigmas = 2.0;

template <std::size_t N>
std::string_view NameOf(const std::array<std::string_view, N>& names, int value) {
  if (value < 0 || static_cast<std::size_t>(value) >= N) return "unknown";
  return names[static_cast<std::size_t>(value)];
}

// `text` with every invalid UTF-8 sequence replaced by U+FFFD: LCM strings are
// bytes, and nlohmann::json refuses to dump a string that is not UTF-8.
std::string ValidUtf8(const std::string& text) {
  const std::string quoted =
      nlohmann::json(text).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  return nlohmann::json::parse(quoted).get<std::string>();
}

nlohmann::json LatLonOrNull(bool known, double lat_deg, double lon_deg) {
  if (!known || !std::isfinite(lat_deg) || !std::isfinite(lon_deg)) return nullptr;
  return nlohmann::json::array({lat_deg, lon_deg});
}

}  // namespace

double UtimeToSeconds(std::int64_t utime) {
  return static_cast<double>(utime) / common::kMicrosPerSecond;
}

nlohmann::json Number(double value) {
  if (!std::isfinite(value)) return nullptr;
  return value;
}

std::string_view VehicleColour(int receiver_id) {
  const int index =
      ((receiver_id - 1) % static_cast<int>(kPalette.size()) + static_cast<int>(kPalette.size())) %
      static_cast<int>(kPalette.size());
  return kPalette[static_cast<std::size_t>(index)];
}

std::string_view ModeName(int flight_mode) {
  // vehicle_state_t::MODE_* in order.
  static constexpr std::array<std::string_view, 8> kNames = {
      "idle", "takeoff", "search", "investigate", "return", "land", "landed", "hold"};
  return NameOf(kNames, flight_mode);
}

std::string_view LinkName(int link_state) {
  // vehicle_state_t::LINK_* in order.
  static constexpr std::array<std::string_view, 4> kNames = {"never", "ok", "degraded", "lost"};
  return NameOf(kNames, link_state);
}

std::string_view TaskName(int task) {
  // vehicle_state_t::TASK_* in order.
  static constexpr std::array<std::string_view, 9> kNames = {
      "idle",    "uploading", "lane",     "investigating", "returning",
      "landing", "landed",    "given_up", "holding"};
  return NameOf(kNames, task);
}

VehicleFields FieldsOf(const vehicle_state_t& m) {
  const bool heard = m.telemetry_age_s >= 0.0;
  const auto finite = [](double value) -> std::optional<double> {
    if (!std::isfinite(value)) return std::nullopt;
    return value;
  };
  const auto telemetry = [&](double value) { return heard ? finite(value) : std::nullopt; };
  VehicleFields f;
  f.id = m.receiver_id;
  if (heard) f.mode = m.flight_mode;
  if (m.has_position && std::isfinite(m.lat_deg) && std::isfinite(m.lon_deg)) {
    f.lat_deg = m.lat_deg;
    f.lon_deg = m.lon_deg;
  }
  f.altitude_m = telemetry(m.altitude_m);
  f.speed_mps = telemetry(std::hypot(m.velocity_north_mps, m.velocity_east_mps));
  f.heading_deg = telemetry(m.heading_deg);
  f.battery_percent = telemetry(m.battery_percent);
  f.link = m.link_state;
  // Rounded: utime and the age are two numbers whose difference is one instant.
  f.heard_s = telemetry(std::round((UtimeToSeconds(m.utime) - m.telemetry_age_s) * 1e3) / 1e3);
  f.telemetry_hz = finite(m.telemetry_hz);
  f.progress = finite(m.progress_fraction);
  f.task = m.task;
  f.lane_index = m.lane_index;
  f.lane_count = m.lane_count;
  f.track_id = m.task_track_id;
  return f;
}

std::string TaskText(const VehicleFields& f) {
  switch (f.task) {
    case vehicle_state_t::TASK_IDLE:
      return "idle";
    case vehicle_state_t::TASK_UPLOADING:
      return "receiving its mission";
    case vehicle_state_t::TASK_LANE:
      if (f.lane_index <= 0) return "searching";
      if (f.lane_count <= 0) return "lane " + std::to_string(f.lane_index);
      return "lane " + std::to_string(f.lane_index) + " of " + std::to_string(f.lane_count);
    case vehicle_state_t::TASK_INVESTIGATING:
      if (f.track_id > 0) return "investigating fire " + std::to_string(f.track_id);
      return "investigating a point";
    case vehicle_state_t::TASK_RETURNING:
      return "returning";
    case vehicle_state_t::TASK_LANDING:
      return "landing";
    case vehicle_state_t::TASK_LANDED:
      return "landed";
    case vehicle_state_t::TASK_GIVEN_UP:
      return "given up: no answer";
    case vehicle_state_t::TASK_HOLDING:
      return "holding";
    default:
      return "unknown task " + std::to_string(f.task);
  }
}

nlohmann::json VehicleRow(const VehicleFields& f, const VehicleFields* before) {
  const auto number = [](const std::optional<double>& value) {
    return value ? nlohmann::json(*value) : nlohmann::json(nullptr);
  };
  // Whether member `field` goes in: always in a whole row, else when it changed.
  const auto differs = [before, &f](auto VehicleFields::*field) {
    return before == nullptr || f.*field != before->*field;
  };
  nlohmann::json row = {{"id", f.id}};
  if (before == nullptr) row["colour"] = VehicleColour(f.id);
  if (differs(&VehicleFields::mode)) {
    row["mode"] = f.mode ? nlohmann::json(ModeName(*f.mode)) : nlohmann::json(nullptr);
  }
  if (differs(&VehicleFields::lat_deg) || differs(&VehicleFields::lon_deg)) {
    row["position"] = f.lat_deg && f.lon_deg ? nlohmann::json::array({*f.lat_deg, *f.lon_deg})
                                             : nlohmann::json(nullptr);
  }
  for (const auto& [key, field] : {std::pair{"altitude_m", &VehicleFields::altitude_m},
                                   std::pair{"speed_mps", &VehicleFields::speed_mps},
                                   std::pair{"heading_deg", &VehicleFields::heading_deg},
                                   std::pair{"battery_percent", &VehicleFields::battery_percent},
                                   std::pair{"heard_s", &VehicleFields::heard_s},
                                   std::pair{"telemetry_hz", &VehicleFields::telemetry_hz},
                                   std::pair{"progress", &VehicleFields::progress}}) {
    if (differs(field)) row[key] = number(f.*field);
  }
  if (differs(&VehicleFields::link)) row["link"] = LinkName(f.link);
  if (differs(&VehicleFields::task) || differs(&VehicleFields::lane_index) ||
      differs(&VehicleFields::lane_count) || differs(&VehicleFields::track_id)) {
    row["task"] = TaskName(f.task);
    row["task_text"] = TaskText(f);
    row["track_id"] = f.track_id;
  }
  return row;
}

nlohmann::json Ellipse2Sigma(const double (&c)[2][2]) {
  Eigen::Matrix2d covariance_ne;
  // Symmetrised: the off-diagonal entries are the same number in a well-formed message.
  const double off = 0.5 * (c[0][1] + c[1][0]);
  covariance_ne << c[0][0], off, off, c[1][1];
  if (!covariance_ne.allFinite()) return nullptr;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(covariance_ne);
  // Eigenvalues ascending: index 1 is the major axis. A covariance that rounding
  // made slightly indefinite gets a zero axis, not a NaN.
  const double major_m = kEllipseSigmas * std::sqrt(std::max(0.0, solver.eigenvalues()(1)));
  const double minor_m = kEllipseSigmas * std::sqrt(std::max(0.0, solver.eigenvalues()(0)));
  const Eigen::Vector2d axis_ne = solver.eigenvectors().col(1);
  // Clockwise from north: atan2(east, north); an axis has no sign, so [0, 180).
  double bearing_deg = std::atan2(axis_ne(1), axis_ne(0)) * common::kDegPerRad;
  bearing_deg = std::fmod(bearing_deg + 360.0, 180.0);
  return {{"semi_major_m", major_m}, {"semi_minor_m", minor_m}, {"bearing_deg", bearing_deg}};
}

std::string_view TrackStatusName(int status) {
  // fire_track_t::STATUS_* in order.
  static constexpr std::array<std::string_view, 3> kNames = {"tentative", "confirmed", "rejected"};
  return NameOf(kNames, status);
}

nlohmann::json TrackRow(const fire_track_t& t) {
  return {
      {"id", t.track_id},
      {"status", TrackStatusName(t.status)},
      {"position", LatLonOrNull(true, t.lat_deg, t.lon_deg)},
      {"ellipse", Ellipse2Sigma(t.covariance_m2)},
      {"reports", t.report_count},
      {"drones", t.vehicle_ids},
      {"first_seen_s", UtimeToSeconds(t.first_seen_utime)},
      {"last_seen_s", UtimeToSeconds(t.last_seen_utime)},
  };
}

std::string_view MissionStateName(int state) {
  // mission_status_t::STATE_* in order.
  static constexpr std::array<std::string_view, 6> kNames = {"idle",      "uploading", "running",
                                                             "returning", "complete",  "aborted"};
  return NameOf(kNames, state);
}

nlohmann::json MissionJson(const mission_status_t& m) {
  return {
      {"state", MissionStateName(m.state)},      {"mission_id", m.mission_id},
      {"coverage", Number(m.coverage_fraction)}, {"elapsed_s", Number(m.elapsed_s)},
      {"vehicles_active", m.vehicles_active},    {"vehicles_lost", m.vehicles_lost},
      {"fires_tentative", m.fires_tentative},    {"fires_confirmed", m.fires_confirmed},
  };
}

namespace {

// Each radio channel's row and each vehicle's channel (docs/command_center.md).
nlohmann::json ChannelsJson(const radio_stats_t& m) {
  nlohmann::json channels = nlohmann::json::array();
  for (std::size_t k = 0; k < static_cast<std::size_t>(std::max<int>(m.channel_count, 0)); ++k) {
    nlohmann::json vehicles = nlohmann::json::array();
    for (std::size_t i = 0; i < std::min(m.vehicle_ids.size(), m.vehicle_channel.size()); ++i) {
      if (static_cast<std::size_t>(m.vehicle_channel[i]) == k) vehicles.push_back(m.vehicle_ids[i]);
    }
    channels.push_back({{"channel", k},
                        {"busy_fraction", Number(m.channel_busy_fraction.at(k))},
                        {"payload_bytes_per_s", Number(m.channel_payload_bytes_per_s.at(k))},
                        {"frames_sent", m.channel_frames_sent.at(k)},
                        {"frames_received", m.channel_frames_received.at(k)},
                        {"retries", m.channel_retries.at(k)},
                        {"timeouts", m.channel_timeouts.at(k)},
                        {"vehicles", std::move(vehicles)},
                        {"silent", m.channel_silent.at(k) != 0}});
  }
  return channels;
}

}  // namespace

nlohmann::json RadioJson(const radio_stats_t& m) {
  nlohmann::json ages = nlohmann::json::object();
  const std::size_t count = std::min(m.vehicle_ids.size(), m.telemetry_age_s.size());
  for (std::size_t i = 0; i < count; ++i) {
    ages[std::to_string(m.vehicle_ids[i])] = Number(m.telemetry_age_s[i]);
  }
  nlohmann::json auth_failures = nlohmann::json::object();
  nlohmann::json replays = nlohmann::json::object();
  for (std::size_t i = 0; i < m.vehicle_ids.size(); ++i) {
    const std::string id = std::to_string(m.vehicle_ids[i]);
    if (i < m.auth_failures.size()) auth_failures[id] = m.auth_failures[i];
    if (i < m.replays.size()) replays[id] = m.replays[i];
  }
  return {
      {"window_s", Number(m.window_s)},
      {"channels", ChannelsJson(m)},
      {"busy_fraction", Number(m.busy_fraction)},
      {"payload_bytes_per_s", Number(m.payload_bytes_per_s)},
      {"frames_sent", m.frames_sent},
      {"frames_received", m.frames_received},
      {"checksum_errors", m.checksum_errors},
      {"collisions", m.collisions},
      {"retries", m.retries},
      {"timeouts", m.timeouts},
      {"telemetry_age_s", std::move(ages)},
      {"secured", m.secured},
      {"out_of_turn", m.out_of_turn},
      {"auth_failures", std::move(auth_failures)},
      {"replays", std::move(replays)},
  };
}

std::string_view CommandKindName(int command) {
  // operator_command_t's constants, from START = 1; the names are POST /api/command's kinds.
  static constexpr std::array<std::string_view, 12> kNames = {
      "unknown", "start",  "abort",  "return_all", "investigate", "retask",
      "hold",    "resume", "return", "land",       "hold_all",    "resume_all"};
  static_assert(operator_command_t::RESUME_ALL == 11);
  return NameOf(kNames, command);
}

std::string_view CommandStateName(int state) {
  // command_status_t::STATE_* in order.
  static constexpr std::array<std::string_view, 4> kNames = {"queued", "sent", "acknowledged",
                                                             "failed"};
  return NameOf(kNames, state);
}

nlohmann::json CommandRow(const command_status_t& m) {
  nlohmann::json targets = nlohmann::json::array();
  const std::size_t count = std::min(m.target_ids.size(), m.target_states.size());
  bool any_failed = false;
  int least = command_status_t::STATE_ACKNOWLEDGED;
  for (std::size_t i = 0; i < count; ++i) {
    const int state = m.target_states[i];
    targets.push_back({{"vehicle", m.target_ids[i]}, {"state", CommandStateName(state)}});
    if (state == command_status_t::STATE_FAILED) {
      any_failed = true;
    } else {
      least = std::min(least, state);
    }
  }
  return {
      {"id", m.command_id},
      {"kind", CommandKindName(m.command)},
      {"targets", std::move(targets)},
      {"state", CommandStateName(any_failed ? command_status_t::STATE_FAILED : least)},
      {"time_s", UtimeToSeconds(m.issued_utime)},
      {"reason", ValidUtf8(m.reason)},
  };
}

}  // namespace fireswarm::server::internal
