// The LCM adapter: the one place the server core meets lcm::LCM and log files.
#include "fireswarm/server/lcm_bridge.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <deque>
#include <lcm/lcm-cpp.hpp>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <system_error>
#include <type_traits>
#include <utility>
#include <vector>

namespace fireswarm::server {

namespace {

// CSV rows, one function per message type: the header line and the rows of one
// message (a track list gives one row per track).
std::string CsvHeader(const vehicle_state_t&) {
  return "utime,receiver_id,has_position,vehicle_time_ms,lat_deg,lon_deg,altitude_m,velocity_"
         "north_mps,"
         "velocity_east_mps,velocity_up_mps,roll_deg,pitch_deg,heading_deg,battery_v,"
         "battery_percent,flight_mode,flags,pending_reports,mission_id,waypoint_index,"
         "link_state,telemetry_age_s,missed_replies,telemetry_hz,progress_fraction,task,"
         "task_track_id,lane_index,lane_count";
}
void CsvRows(std::ostream& out, const vehicle_state_t& m) {
  out << m.utime << ',' << m.receiver_id << ',' << int{m.has_position} << ',' << m.vehicle_time_ms
      << ',' << m.lat_deg << ',' << m.lon_deg << ',' << m.altitude_m << ',' << m.velocity_north_mps
      << ',' << m.velocity_east_mps << ',' << m.velocity_up_mps << ',' << m.roll_deg << ','
      << m.pitch_deg << ',' << m.heading_deg << ',' << m.battery_v << ',' << m.battery_percent
      << ',' << int{m.flight_mode} << ',' << m.flags << ',' << m.pending_reports << ','
      << m.mission_id << ',' << m.waypoint_index << ',' << int{m.link_state} << ','
      << m.telemetry_age_s << ',' << m.missed_replies << ',' << m.telemetry_hz << ','
      << m.progress_fraction << ',' << int{m.task} << ',' << m.task_track_id << ',' << m.lane_index
      << ',' << m.lane_count << '\n';
}

std::string CsvHeader(const fire_track_list_t&) {
  return "utime,track_id,status,lat_deg,lon_deg,covariance_nn_m2,covariance_ne_m2,"
         "covariance_ee_m2,report_count,vehicle_count,first_seen_utime,last_seen_utime";
}
void CsvRows(std::ostream& out, const fire_track_list_t& list) {
  for (const fire_track_t& m : list.tracks) {
    out << list.utime << ',' << m.track_id << ',' << int{m.status} << ',' << m.lat_deg << ','
        << m.lon_deg << ',' << m.covariance_m2[0][0] << ',' << m.covariance_m2[0][1] << ','
        << m.covariance_m2[1][1] << ',' << m.report_count << ',' << m.vehicle_count << ','
        << m.first_seen_utime << ',' << m.last_seen_utime << '\n';
  }
}

std::string CsvHeader(const mission_status_t&) {
  return "utime,state,mission_id,coverage_fraction,elapsed_s,vehicles_active,vehicles_lost,"
         "fires_tentative,fires_confirmed";
}
void CsvRows(std::ostream& out, const mission_status_t& m) {
  out << m.utime << ',' << int{m.state} << ',' << m.mission_id << ',' << m.coverage_fraction << ','
      << m.elapsed_s << ',' << m.vehicles_active << ',' << m.vehicles_lost << ','
      << m.fires_tentative << ',' << m.fires_confirmed << '\n';
}

std::string CsvHeader(const radio_stats_t&) {
  return "utime,window_s,busy_fraction,payload_bytes_per_s,frames_sent,frames_received,"
         "checksum_errors,collisions,retries,timeouts,secured,out_of_turn";
}
void CsvRows(std::ostream& out, const radio_stats_t& m) {
  out << m.utime << ',' << m.window_s << ',' << m.busy_fraction << ',' << m.payload_bytes_per_s
      << ',' << m.frames_sent << ',' << m.frames_received << ',' << m.checksum_errors << ','
      << m.collisions << ',' << m.retries << ',' << m.timeouts << ',' << (m.secured ? 1 : 0) << ','
      << m.out_of_turn << '\n';
}

// A text field as one CSV cell (RFC 4180: quoted, quotes doubled).
std::string CsvText(const std::string& text) {
  std::string cell = "\"";
  for (const char c : text) cell += c == '"' ? std::string("\"\"") : std::string(1, c);
  return cell + '"';
}

// One row per target.
std::string CsvHeader(const command_status_t&) {
  return "utime,command_id,command,issued_utime,target_id,target_state,reason";
}
void CsvRows(std::ostream& out, const command_status_t& m) {
  for (std::size_t i = 0; i < m.target_ids.size(); ++i) {
    out << m.utime << ',' << m.command_id << ',' << int{m.command} << ',' << m.issued_utime << ','
        << m.target_ids[i] << ',' << int{m.target_states[i]} << ',' << CsvText(m.reason) << '\n';
  }
}

std::string CsvHeader(const conflict_t&) {
  return "utime,conflict_id,vehicle_a,vehicle_b,detected_utime,predicted_separation_m,"
         "time_to_closest_s,resolution,mover,target_altitude_m,order_s,outcome,"
         "observed_min_separation_m,closed_utime";
}
void CsvRows(std::ostream& out, const conflict_t& m) {
  out << m.utime << ',' << m.conflict_id << ',' << m.vehicle_a << ',' << m.vehicle_b << ','
      << m.detected_utime << ',' << m.predicted_separation_m << ',' << m.time_to_closest_s << ','
      << int{m.resolution} << ',' << m.mover << ',' << m.target_altitude_m << ',' << m.order_s
      << ',' << int{m.outcome} << ',' << m.observed_min_separation_m << ',' << m.closed_utime
      << '\n';
}

std::string CsvName(const char* channel) {
  std::string name(channel);
  for (char& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return name + ".csv";
}

// Appends `message` to its channel's CSV file in `dir`, created with its header
// line on first use (kept open in `files`).
template <typename Message>
void AppendCsv(std::map<std::string, std::ofstream>& files, const std::filesystem::path& dir,
               const char* channel, const Message& message) {
  const std::string name = CsvName(channel);
  auto found = files.find(name);
  if (found == files.end()) {
    const std::filesystem::path path = dir / name;
    std::ofstream file(path);
    if (!file) throw std::runtime_error("cannot create " + path.string());
    file.precision(10);
    file << CsvHeader(message) << '\n';
    found = files.emplace(name, std::move(file)).first;
  }
  CsvRows(found->second, message);
}

double PeriodS(double hz) {
  return hz > 0.0 ? 1.0 / hz : std::numeric_limits<double>::infinity();
}

}  // namespace

LcmBridge::LcmBridge(const LcmBridgeConfig& config) : config_(config) {
  config_.rates.Validate();
  if (!config_.url.empty()) {
    lcm_ = std::make_unique<lcm::LCM>(config_.url);
    if (!lcm_->good()) {
      throw std::runtime_error("LCM could not start on '" + config_.url +
                               "' (for udpm:// on one machine, add a multicast route on lo: "
                               "see scripts/install-deps.sh)");
    }
    lcm_->subscribe(kOperatorCommandChannel, &LcmBridge::OnCommandMessage, this);
  }
  if (config_.log_path) {
    log_ = std::make_unique<lcm::LogFile>(config_.log_path->string(), "w");
    if (!log_->good()) {
      throw std::runtime_error("cannot create the LCM log " + config_.log_path->string());
    }
  }
  if (config_.csv_dir) {
    std::error_code error;
    std::filesystem::create_directories(*config_.csv_dir, error);
    if (error) {
      throw std::runtime_error("cannot create the CSV directory " + config_.csv_dir->string() +
                               ": " + error.message());
    }
  }
  for (const char* channel :
       {kVehicleStateChannel, kFireTracksChannel, kMissionStatusChannel, kRadioStatsChannel}) {
    next_s_[channel] = 0.0;
  }
}

LcmBridge::~LcmBridge() = default;

void LcmBridge::OnCommandMessage(const lcm::ReceiveBuffer* buffer, const std::string&) {
  // An LCM callback: never throws. Decoded here, not by LCM's typed subscription,
  // whose generated decode throws on some malformed strings (DecodeOperatorCommand).
  const std::optional<operator_command_t> message = DecodeOperatorCommand(
      {static_cast<const std::uint8_t*>(buffer->data), buffer->data_size});
  if (!message) {
    ++rejected_commands_;
    CommandRefused refusal;
    refusal.why = "malformed: not an operator_command_t";
    commands_.emplace_back(std::move(refusal));
    return;
  }
  std::string why;
  if (const std::optional<OperatorCommand> command = FromLcm(*message, &why)) {
    commands_.emplace_back(SignedCommand{*command, CredentialsFromLcm(*message)});
  } else {
    ++rejected_commands_;
    commands_.emplace_back(CommandRefused{CommandVerdict::kMalformed, message->command,
                                          message->target_vehicle,
                                          message->operator_id.substr(0, kMaxOperatorIdBytes),
                                          message->utime, message->nonce, "malformed: " + why});
  }
}

template <typename Message>
void LcmBridge::Emit(const char* channel, const Message& message, std::int64_t utime) {
  ++published_;
  if (lcm_) lcm_->publish(channel, &message);
  if (log_) {
    std::vector<std::uint8_t> data(static_cast<std::size_t>(message.getEncodedSize()));
    message.encode(data.data(), 0, static_cast<int>(data.size()));
    lcm::LogEvent event{};
    event.timestamp = utime;
    event.channel = channel;
    event.datalen = static_cast<std::int32_t>(data.size());
    event.data = data.data();
    if (log_->writeEvent(&event) != 0) {
      throw std::runtime_error("cannot write the LCM log " + config_.log_path->string());
    }
  }
  // plan_t is one GeoJSON string, no table: it goes to LCM and the log only.
  if constexpr (!std::is_same_v<Message, plan_t>) {
    if (config_.csv_dir) AppendCsv(csv_, *config_.csv_dir, channel, message);
  }
}

void LcmBridge::Publish(const Server& server, double now_s, std::int64_t utime,
                        std::int64_t utime_at_zero) {
  // Command status on change, not at a rate: an operator waits for it.
  if (server.commands_version() > commands_version_) {
    for (const CommandRecord& record : server.commands()) {
      if (record.version <= commands_version_) continue;
      Emit(kCommandStatusChannel, ToCommandStatus(record, utime, utime_at_zero), utime);
    }
    commands_version_ = server.commands_version();
  }
  // Refusals once each, those still kept (Server::kKeptRefusals).
  const std::deque<CommandRefused>& refusals = server.recent_refusals();
  const std::uint64_t first_kept = server.refusal_count() - refusals.size();
  for (std::uint64_t n = std::max(refusals_published_, first_kept); n < server.refusal_count();
       ++n) {
    Emit(kCommandStatusChannel, ToCommandStatus(refusals[n - first_kept], utime), utime);
  }
  refusals_published_ = server.refusal_count();
  // Conflicts on change: an operator must see one before it comes to pass.
  const TrafficControl& traffic = server.traffic();
  if (traffic.version() > traffic_version_) {
    for (const Conflict& conflict : traffic.conflicts()) {
      if (conflict.version <= traffic_version_) continue;
      Emit(kConflictChannel, ToConflict(conflict, utime, utime_at_zero), utime);
    }
    traffic_version_ = traffic.version();
  }
  const LcmRates& rates = config_.rates;
  const auto due = [&](const char* channel, double hz) {
    double& next = next_s_[channel];
    if (hz <= 0.0 || now_s < next) return false;
    // Keep the rate's grid; after a long gap, resume from now.
    next = std::max(next + PeriodS(hz), now_s);
    return true;
  };
  if (due(kVehicleStateChannel, rates.vehicle_state_hz)) {
    for (const std::uint8_t id : server.registry().ids()) {
      Emit(kVehicleStateChannel, ToVehicleState(server, id, now_s, utime), utime);
    }
  }
  if (due(kFireTracksChannel, rates.fire_tracks_hz)) {
    Emit(kFireTracksChannel, ToFireTrackList(server, utime, utime_at_zero), utime);
  }
  if (due(kMissionStatusChannel, rates.mission_status_hz)) {
    Emit(kMissionStatusChannel, ToMissionStatus(server, now_s, utime), utime);
  }
  if (due(kRadioStatsChannel, rates.radio_stats_hz)) {
    const double window_s = now_s - previous_radio_stats_s_;
    previous_radio_stats_s_ = now_s;
    Emit(kRadioStatsChannel, ToRadioStats(server, now_s, utime, window_s, previous_counters_),
         utime);
  }
  // The plan: as soon as a mission is loaded (its timer starts then), then at plan_hz.
  if (server.mission() != nullptr) {
    next_s_.try_emplace(kPlanChannel, now_s);
    if (due(kPlanChannel, rates.plan_hz)) Emit(kPlanChannel, ToPlan(server, utime), utime);
  }
}

std::vector<IncomingCommand> LcmBridge::TakeCommands() {
  if (lcm_) {
    while (lcm_->handleTimeout(0) > 0) {
    }
  }
  return std::exchange(commands_, {});
}

double LcmBridge::NextPublishS() const {
  double next = std::numeric_limits<double>::infinity();
  const LcmRates& rates = config_.rates;
  const std::pair<const char*, double> channels[] = {
      {kVehicleStateChannel, rates.vehicle_state_hz},
      {kFireTracksChannel, rates.fire_tracks_hz},
      {kMissionStatusChannel, rates.mission_status_hz},
      {kRadioStatsChannel, rates.radio_stats_hz},
      {kPlanChannel, rates.plan_hz}};
  for (const auto& [channel, hz] : channels) {
    const auto found = next_s_.find(channel);  // the plan's only once a mission is loaded
    if (hz > 0.0 && found != next_s_.end()) next = std::min(next, found->second);
  }
  return next;
}

}  // namespace fireswarm::server
