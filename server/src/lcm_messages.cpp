// Server state -> LCM messages, and operator_command_t -> OperatorCommand. Pure.
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "fireswarm/common/north_east.hpp"
#include "fireswarm/common/time.hpp"
#include "fireswarm/server/lcm_bridge.hpp"
#include "fireswarm/server/vehicle_task.hpp"

namespace fireswarm::server {

namespace {

std::int64_t Utime(std::int64_t utime_at_zero, double seconds) {
  return utime_at_zero +
         static_cast<std::int64_t>(std::llround(seconds * common::kMicrosPerSecond));
}

}  // namespace

void LcmRates::Validate() const {
  const auto check = [](double hz, const char* name) {
    if (!(hz >= 0.0) || !std::isfinite(hz)) {
      throw std::invalid_argument(std::string(name) + " must be >= 0 Hz, got " +
                                  std::to_string(hz));
    }
  };
  check(vehicle_state_hz, "vehicle_state_hz");
  check(fire_tracks_hz, "fire_tracks_hz");
  check(mission_status_hz, "mission_status_hz");
  check(radio_stats_hz, "radio_stats_hz");
  check(plan_hz, "plan_hz");
}

vehicle_state_t ToVehicleState(const Server& server, std::uint8_t vehicle, double now_s,
                               std::int64_t utime) {
  const VehicleState& state = server.registry().state(vehicle);
  vehicle_state_t m{};
  m.utime = utime;
  m.receiver_id = vehicle;
  m.link_state = static_cast<std::int8_t>(server.registry().LinkAt(vehicle, now_s));
  m.missed_replies =
      static_cast<std::int32_t>(std::min<std::uint32_t>(state.missed_replies, INT32_MAX));
  m.telemetry_age_s = server.registry().TelemetryAgeS(vehicle, now_s).value_or(-1.0);
  m.telemetry_hz = server.scheduler().TelemetryRateHz(vehicle);
  const TaskView task = TaskOf(server, vehicle, now_s);
  m.progress_fraction = task.progress_fraction;
  m.task = static_cast<std::int8_t>(task.task);
  m.task_track_id = task.track_id;
  m.lane_index = task.lane_index;
  m.lane_count = task.lane_count;
  constexpr double kUnknown = std::numeric_limits<double>::quiet_NaN();
  if (!state.telemetry) {
    // Registered but not heard yet: no position rather than one at (0, 0).
    m.lat_deg = m.lon_deg = m.altitude_m = kUnknown;
    return m;
  }
  const radio::Telemetry& t = *state.telemetry;
  m.vehicle_time_ms = t.time_ms;
  m.lat_deg = t.lat_deg;
  m.lon_deg = t.lon_deg;
  m.altitude_m = t.altitude_m;
  m.velocity_north_mps = t.velocity_north_mps;
  m.velocity_east_mps = t.velocity_east_mps;
  m.velocity_up_mps = t.climb_rate_mps;
  m.roll_deg = t.roll_deg;
  m.pitch_deg = t.pitch_deg;
  m.heading_deg = t.heading_deg;
  m.battery_v = t.battery_v;
  m.battery_percent = t.battery_percent;
  m.flight_mode = static_cast<std::int8_t>(t.mode);
  m.flags = t.flags;
  m.pending_reports = t.pending_reports;
  m.mission_id = t.mission_id;
  m.waypoint_index = t.waypoint_index;
  // Without a GPS fix the vehicle sends (0, 0): it knows no position.
  m.has_position = (t.flags & radio::telemetry_flags::kGpsFix) != 0;
  if (!m.has_position) m.lat_deg = m.lon_deg = kUnknown;
  return m;
}

fire_track_list_t ToFireTrackList(const Server& server, std::int64_t utime,
                                  std::int64_t utime_at_zero) {
  fire_track_list_t list{};
  list.utime = utime;
  for (const FireTrack& track : server.fusion().tracks()) {
    fire_track_t m{};
    m.utime = utime;
    m.track_id = track.track_id;
    m.status = static_cast<std::int8_t>(track.status);
    const common::LatLon where =
        server.frame().ToGeodetic({track.position_en_m.x(), track.position_en_m.y()});
    m.lat_deg = where.lat_deg;
    m.lon_deg = where.lon_deg;
    // fire_track_t's covariance is (north, east).
    const Eigen::Matrix2d covariance_ne_m2 = common::SwapAxes(track.covariance_en_m2);
    for (int r = 0; r < 2; ++r) {
      for (int c = 0; c < 2; ++c) m.covariance_m2[r][c] = covariance_ne_m2(r, c);
    }
    m.report_count = track.report_count;
    m.vehicle_count = static_cast<std::int16_t>(track.vehicle_ids.size());
    for (const std::uint8_t id : track.vehicle_ids) m.vehicle_ids.push_back(id);
    m.first_seen_utime = Utime(utime_at_zero, track.first_seen_s);
    m.last_seen_utime = Utime(utime_at_zero, track.last_seen_s);
    list.tracks.push_back(std::move(m));
  }
  list.track_count = static_cast<std::int32_t>(list.tracks.size());
  return list;
}

mission_status_t ToMissionStatus(const Server& server, double now_s, std::int64_t utime) {
  mission_status_t m{};
  m.utime = utime;
  m.state = static_cast<std::int8_t>(server.state());
  const MissionManager* mission = server.mission();
  m.mission_id = 0;
  if (mission != nullptr && !mission->vehicles().empty()) m.mission_id = 1;
  // The ground the cameras saw by telemetry, the report's measure; without an
  // area configured, the share of the planned waypoints passed.
  if (const planner::CoverageGrid* coverage = server.coverage()) {
    m.coverage_fraction = coverage->Fraction();
  } else {
    m.coverage_fraction = mission != nullptr ? mission->WaypointFraction() : 0.0;
  }
  m.elapsed_s = server.state() == MissionState::kIdle ? 0.0 : now_s - server.mission_started_s();
  m.vehicles_lost = static_cast<std::int16_t>(server.registry().LostAt(now_s).size());
  m.vehicles_active = static_cast<std::int16_t>(server.registry().ActiveAt(now_s).size());
  for (const FireTrack& track : server.fusion().tracks()) {
    if (track.status == FireTrackStatus::kTentative) ++m.fires_tentative;
    if (track.status == FireTrackStatus::kConfirmed) ++m.fires_confirmed;
  }
  return m;
}

namespace {

// One channel's fields of radio_stats_t over the window since `previous`.
void AddChannelStats(const radio::ChannelRouter& router, std::size_t k, double window_s,
                     const radio::SchedulerStats& previous_stats,
                     const radio::ChannelBytes& previous_bytes, radio_stats_t& m) {
  const radio::MasterScheduler& channel = router.channel(k);
  const radio::SchedulerStats& stats = channel.stats();
  const radio::ChannelBytes& bytes = router.bytes(k);
  double busy = 0.0;
  double payload = 0.0;
  if (window_s > 0.0) {
    payload = static_cast<double>(stats.payload_bytes - previous_stats.payload_bytes) / window_s;
    // What the server hears plus what it sends: both occupy the channel.
    // Turnarounds and idle slots are not counted, so this is a lower bound.
    const double airtime_s = common::ToSeconds(channel.config().timing.AirtimeOf(
        (bytes.sent - previous_bytes.sent) + (bytes.received - previous_bytes.received)));
    busy = std::clamp(airtime_s / window_s, 0.0, 1.0);
  }
  m.channel_busy_fraction.push_back(busy);
  m.channel_payload_bytes_per_s.push_back(payload);
  m.channel_frames_sent.push_back(static_cast<std::int64_t>(
      stats.polls + stats.schedules + stats.requests_sent + stats.report_acks_sent));
  m.channel_frames_received.push_back(static_cast<std::int64_t>(channel.parser_stats().frames));
  m.channel_retries.push_back(static_cast<std::int64_t>(stats.retries));
  m.channel_timeouts.push_back(static_cast<std::int64_t>(stats.missed_replies));
  m.channel_vehicles.push_back(static_cast<std::int16_t>(router.VehiclesOn(k).size()));
  m.channel_silent.push_back(router.health(k).silent);
}

}  // namespace

radio_stats_t ToRadioStats(const Server& server, double now_s, std::int64_t utime, double window_s,
                           RadioCounters& previous) {
  const radio::ChannelRouter& router = server.scheduler();
  const radio::SchedulerStats stats = router.stats();
  const radio::ParserStats parser = router.parser_stats();
  radio_stats_t m{};
  m.utime = utime;
  m.window_s = window_s;
  const std::size_t channels = router.channel_count();
  previous.stats.resize(channels);
  previous.bytes.resize(channels);
  for (std::size_t k = 0; k < channels; ++k) {
    AddChannelStats(router, k, window_s, previous.stats[k], previous.bytes[k], m);
    previous.stats[k] = router.channel(k).stats();
    previous.bytes[k] = router.bytes(k);
  }
  m.channel_count = static_cast<std::int16_t>(channels);
  m.busy_fraction = std::ranges::max(m.channel_busy_fraction);
  for (const double rate : m.channel_payload_bytes_per_s) m.payload_bytes_per_s += rate;
  m.frames_sent = static_cast<std::int64_t>(stats.polls + stats.schedules + stats.requests_sent +
                                            stats.report_acks_sent);
  m.frames_received = static_cast<std::int64_t>(parser.frames);
  m.checksum_errors = static_cast<std::int64_t>(parser.checksum_errors);
  m.collisions = 0;  // a receiver cannot tell a collision from a loss
  m.retries = static_cast<std::int64_t>(stats.retries);
  m.timeouts = static_cast<std::int64_t>(stats.missed_replies);
  const auto refused = [&](CommandVerdict verdict) {
    return static_cast<std::int64_t>(
        server.command_refusals().at(static_cast<std::size_t>(verdict)));
  };
  m.commands_malformed = refused(CommandVerdict::kMalformed);
  m.commands_unknown_operator = refused(CommandVerdict::kUnknownOperator);
  m.commands_bad_mac = refused(CommandVerdict::kBadMac);
  m.commands_stale = refused(CommandVerdict::kStale);
  m.commands_replayed = refused(CommandVerdict::kReplayed);
  const radio::FrameSecurity* security = router.config().security.get();
  m.secured = security != nullptr;
  m.out_of_turn = static_cast<std::int64_t>(stats.out_of_turn);
  for (const std::uint8_t id : server.registry().ids()) {
    m.vehicle_ids.push_back(id);
    m.telemetry_age_s.push_back(server.registry().TelemetryAgeS(id, now_s).value_or(-1.0));
    m.vehicle_channel.push_back(static_cast<std::int16_t>(router.ChannelOf(id)));
    radio::KeySecurityStats key;
    if (security != nullptr) {
      if (const auto found = security->stats().find(id); found != security->stats().end()) {
        key = found->second;
      }
    }
    m.auth_failures.push_back(static_cast<std::int64_t>(key.auth_failures));
    m.replays.push_back(static_cast<std::int64_t>(key.replays));
  }
  m.vehicle_count = static_cast<std::int16_t>(m.vehicle_ids.size());
  return m;
}

bool LcmStringsFit(std::span<const std::uint8_t> bytes, std::size_t at, int count) {
  for (int i = 0; i < count; ++i) {
    if (bytes.size() < at || bytes.size() - at < 4) return false;
    const std::uint32_t length = std::uint32_t{bytes[at]} << 24 |
                                 std::uint32_t{bytes[at + 1]} << 16 |
                                 std::uint32_t{bytes[at + 2]} << 8 | std::uint32_t{bytes[at + 3]};
    at += 4;
    // As unsigned, a negative length is over 2^31 and fails the second test.
    if (length == 0 || length > bytes.size() - at) return false;
    at += length;
  }
  return true;
}

std::optional<operator_command_t> DecodeOperatorCommand(std::span<const std::uint8_t> bytes) {
  if (!LcmStringsFit(bytes, kOperatorCommandStringsAt, 2)) return std::nullopt;
  operator_command_t message;
  try {
    if (message.decode(bytes.data(), 0, static_cast<int>(bytes.size())) < 0) return std::nullopt;
  } catch (const std::exception&) {
    return std::nullopt;  // none expected once the strings fit; never out of a callback
  }
  return message;
}

std::optional<OperatorCommand> FromLcm(const operator_command_t& message, std::string* why) {
  const auto refuse = [&](std::string reason) -> std::optional<OperatorCommand> {
    if (why != nullptr) *why = std::move(reason);
    return std::nullopt;
  };
  OperatorCommand command;
  switch (message.command) {
    case operator_command_t::START:
      command.kind = OperatorCommand::Kind::kStart;
      break;
    case operator_command_t::ABORT:
      command.kind = OperatorCommand::Kind::kAbort;
      break;
    case operator_command_t::RETURN_ALL:
      command.kind = OperatorCommand::Kind::kReturnAll;
      break;
    case operator_command_t::INVESTIGATE_POINT:
      command.kind = OperatorCommand::Kind::kInvestigatePoint;
      break;
    case operator_command_t::RETASK_VEHICLE:
      command.kind = OperatorCommand::Kind::kRetaskVehicle;
      break;
    case operator_command_t::HOLD:
      command.kind = OperatorCommand::Kind::kHold;
      break;
    case operator_command_t::RESUME:
      command.kind = OperatorCommand::Kind::kResume;
      break;
    case operator_command_t::RETURN_VEHICLE:
      command.kind = OperatorCommand::Kind::kReturnVehicle;
      break;
    case operator_command_t::LAND:
      command.kind = OperatorCommand::Kind::kLand;
      break;
    case operator_command_t::HOLD_ALL:
      command.kind = OperatorCommand::Kind::kHoldAll;
      break;
    case operator_command_t::RESUME_ALL:
      command.kind = OperatorCommand::Kind::kResumeAll;
      break;
    default:
      return refuse("unknown command " + std::to_string(message.command));
  }
  if (message.target_vehicle < 0 || message.target_vehicle > kLastVehicleId) {
    return refuse("target_vehicle " + std::to_string(message.target_vehicle) +
                  " is outside 0..254");
  }
  if (!(message.radius_m >= 0.0) || !std::isfinite(message.radius_m)) {
    return refuse("radius_m must be >= 0");
  }
  command.vehicle = static_cast<std::uint8_t>(message.target_vehicle);
  command.point = {message.lat_deg, message.lon_deg};
  command.radius_m = message.radius_m;
  command.reason = message.reason;
  return command;
}

command_status_t ToCommandStatus(const CommandRecord& record, std::int64_t utime,
                                 std::int64_t utime_at_zero) {
  command_status_t m{};
  m.utime = utime;
  m.command_id = record.id;
  m.command = static_cast<std::int8_t>(record.kind);
  m.issued_utime = Utime(utime_at_zero, record.issued_s);
  m.reason = record.reason;
  for (const CommandTarget& target : record.targets) {
    m.target_ids.push_back(target.vehicle);
    m.target_states.push_back(static_cast<std::int8_t>(target.state));
  }
  m.target_count = static_cast<std::int16_t>(m.target_ids.size());
  m.operator_id = record.operator_id;
  m.nonce = record.nonce;
  return m;
}

command_status_t ToCommandStatus(const CommandRefused& refusal, std::int64_t utime) {
  command_status_t m{};
  m.utime = utime;
  m.command_id = 0;
  m.command = static_cast<std::int8_t>(refusal.command);
  m.issued_utime = utime;
  m.target_count = 0;
  m.operator_id = refusal.operator_id;
  m.nonce = refusal.nonce;
  m.refusal = refusal.why;
  return m;
}

conflict_t ToConflict(const Conflict& conflict, std::int64_t utime, std::int64_t utime_at_zero) {
  conflict_t m{};
  m.utime = utime;
  m.conflict_id = conflict.id;
  m.vehicle_a = static_cast<std::int16_t>(conflict.vehicle_a);
  m.vehicle_b = static_cast<std::int16_t>(conflict.vehicle_b);
  m.detected_utime = Utime(utime_at_zero, conflict.detected_s);
  m.predicted_separation_m = conflict.predicted_separation_m;
  m.time_to_closest_s = conflict.time_to_closest_s;
  m.resolution = static_cast<std::int8_t>(conflict.resolution);
  m.mover = static_cast<std::int16_t>(conflict.mover);
  m.target_altitude_m = conflict.target_altitude_m;
  m.order_s = conflict.order_s;
  m.outcome = static_cast<std::int8_t>(conflict.outcome);
  m.observed_min_separation_m = conflict.observed_min_separation_m;
  m.closed_utime =
      conflict.outcome == ConflictOutcome::kOpen ? 0 : Utime(utime_at_zero, conflict.closed_s);
  return m;
}

CommandCredentials CredentialsFromLcm(const operator_command_t& message) {
  CommandCredentials credentials{message.operator_id, message.utime, message.nonce, {}};
  std::copy(std::begin(message.mac), std::end(message.mac), credentials.mac.begin());
  return credentials;
}

operator_command_t ToLcm(const SignedCommand& command) {
  operator_command_t m{};
  m.utime = command.credentials.utime;
  m.command = static_cast<std::int8_t>(command.command.kind);
  m.target_vehicle = command.command.vehicle;
  m.lat_deg = command.command.point.lat_deg;
  m.lon_deg = command.command.point.lon_deg;
  m.radius_m = command.command.radius_m;
  m.reason = command.command.reason;
  m.operator_id = command.credentials.operator_id;
  m.nonce = command.credentials.nonce;
  std::copy(command.credentials.mac.begin(), command.credentials.mac.end(), std::begin(m.mac));
  return m;
}

}  // namespace fireswarm::server
