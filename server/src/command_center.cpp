// The command center's model: keeps the latest row of everything the LCM feed
// says and what changed since the last delta.
#include "fireswarm/server/command_center.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "command_center_alerts.hpp"
#include "command_center_coverage.hpp"
#include "command_center_rows.hpp"

namespace fireswarm::server {

namespace {

// A trail point is added once the vehicle is this far from the previous one:
// telemetry noise of a hovering drone draws no scribble.
constexpr double kTrailStepM = 2.0;

nlohmann::json EmptyFeatureCollection() {
  return {{"type", "FeatureCollection"}, {"features", nlohmann::json::array()}};
}

}  // namespace

void CommandCenterConfig::Validate() const {
  const auto fail = [](const std::string& what) { throw std::invalid_argument(what); };
  if (source != "live" && source != "simulated" && source != "replay") {
    fail("source: must be live, simulated or replay, got '" + source + "'");
  }
  if (trail_points < 1) fail("trail_points: must be >= 1, got 0");
  if (alerts_kept < 1) fail("alerts_kept: must be >= 1, got 0");
  if (commands_kept < 1) fail("commands_kept: must be >= 1, got 0");
  if (!(separation_m > 0.0) || !std::isfinite(separation_m)) {
    fail("separation_m: must be a finite number > 0 m, got " + std::to_string(separation_m));
  }
}

CommandCenter::CommandCenter(CommandCenterConfig config)
    : config_((config.Validate(), std::move(config))),
      plan_(EmptyFeatureCollection()),
      plan_info_({{"mission_id", 0}, {"version", 0}}),
      alerts_(std::make_unique<internal::AlertLog>(config_.alerts_kept)),
      separation_(std::make_unique<internal::SeparationWatch>(config_.separation_m)),
      conflicts_(std::make_unique<internal::ConflictWatch>()) {}

CommandCenter::~CommandCenter() = default;
CommandCenter::CommandCenter(CommandCenter&&) noexcept = default;
CommandCenter& CommandCenter::operator=(CommandCenter&&) noexcept = default;

void CommandCenter::UpdateTime(std::int64_t utime) {
  const double time_s = internal::UtimeToSeconds(utime);
  if (!time_known_ || time_s > time_s_) {
    time_s_ = time_s;
    time_known_ = true;
    time_changed_ = true;
  }
}

void CommandCenter::OnPlan(const plan_t& message) {
  UpdateTime(message.utime);
  if (message.geojson == plan_text_) return;
  plan_text_ = message.geojson;
  plan_changed_ = true;
  nlohmann::json plan = nlohmann::json::parse(message.geojson, nullptr, false);
  // Not plan.value("type", ""): it throws when "type" is there but not a string.
  const auto type = plan.is_object() ? plan.find("type") : plan.end();
  if (plan.is_discarded() || !plan.is_object() || type == plan.end() ||
      *type != "FeatureCollection") {
    // Kept off the map: the previous plan (if any) stays, the state says why.
    plan_info_["error"] = "plan of mission " + std::to_string(message.mission_id) +
                          ": not a GeoJSON FeatureCollection";
    return;
  }
  const internal::CoverageRaster* raster_before = coverage_.get();
  try {
    coverage_ = internal::CoverageRaster::FromPlan(plan, std::move(coverage_));
    if (coverage_.get() != raster_before) ++coverage_version_;
  } catch (const std::invalid_argument& error) {
    coverage_.reset();
    ++coverage_version_;
    plan_info_["error"] =
        std::string("plan of mission ") + std::to_string(message.mission_id) + ": " + error.what();
    plan_ = std::move(plan);
    plan_info_["mission_id"] = message.mission_id;
    plan_info_["version"] = ++plan_version_;
    return;
  }
  plan_ = std::move(plan);
  plan_info_ = {{"mission_id", message.mission_id}, {"version", ++plan_version_}};
}

void CommandCenter::OnVehicleState(const vehicle_state_t& message) {
  UpdateTime(message.utime);
  const auto [it, inserted] = vehicles_.try_emplace(message.receiver_id);
  Vehicle& vehicle = it->second;
  internal::RaiseVehicleAlerts(inserted ? nullptr : &vehicle.last, message, *alerts_);
  std::optional<common::EastNorth> local;
  if (message.has_position && common::IsValidLatLon({message.lat_deg, message.lon_deg})) {
    const common::LatLon point{message.lat_deg, message.lon_deg};
    if (!frame_) frame_.emplace(point);
    // Most states repeat the position of the telemetry before.
    const bool same = !inserted && vehicle.local && vehicle.last.lat_deg == point.lat_deg &&
                      vehicle.last.lon_deg == point.lon_deg;
    local = same ? vehicle.local : frame_->ToLocal(point);
  }
  vehicle.last = message;
  vehicle.local = local;
  ExtendTrail(vehicle, message, local);
  WatchSeparation(message, local);
  if (coverage_) {
    const std::size_t seen_before = coverage_->seen_cells();
    coverage_->Mark(message);
    if (coverage_->seen_cells() != seen_before) ++coverage_version_;
  }
}

void CommandCenter::ExtendTrail(Vehicle& vehicle, const vehicle_state_t& message,
                                const std::optional<common::EastNorth>& local) {
  if (!local) return;
  if (vehicle.trail_end_m &&
      std::hypot(local->east_m - vehicle.trail_end_m->east_m,
                 local->north_m - vehicle.trail_end_m->north_m) <= kTrailStepM) {
    return;
  }
  vehicle.trail_end_m = local;
  vehicle.trail.push_back(nlohmann::json::array({message.lat_deg, message.lon_deg}));
  if (vehicle.trail.size() > config_.trail_points) vehicle.trail.pop_front();
  vehicle.trail_unsent = std::min(vehicle.trail_unsent + 1, vehicle.trail.size());
}

void CommandCenter::WatchSeparation(const vehicle_state_t& message,
                                    const std::optional<common::EastNorth>& local) {
  std::optional<Eigen::Vector3d> position_enu_m;
  if (local && internal::IsAirborne(message)) {
    position_enu_m = Eigen::Vector3d(local->east_m, local->north_m, message.altitude_m);
  }
  separation_->Update(message.receiver_id, position_enu_m, internal::UtimeToSeconds(message.utime),
                      *alerts_);
}

void CommandCenter::OnFireTracks(const fire_track_list_t& message) {
  UpdateTime(message.utime);
  const double time_s = internal::UtimeToSeconds(message.utime);
  std::set<int> present;
  for (const fire_track_t& track : message.tracks) {
    present.insert(track.track_id);
    const auto found = tracks_.find(track.track_id);
    internal::RaiseTrackAlerts(
        found == tracks_.end() ? std::nullopt : std::optional<int>(found->second.status), track,
        time_s, *alerts_);
    nlohmann::json row = internal::TrackRow(track);
    if (found == tracks_.end() || found->second.row != row) {
      tracks_[track.track_id] = Track{track.status, std::move(row)};
      changed_tracks_.insert(track.track_id);
      removed_tracks_.erase(track.track_id);
    }
  }
  // The list is every track the server holds: one missing from it is gone.
  for (auto it = tracks_.begin(); it != tracks_.end();) {
    if (present.contains(it->first)) {
      ++it;
      continue;
    }
    removed_tracks_.insert(it->first);
    changed_tracks_.erase(it->first);
    it = tracks_.erase(it);
  }
}

void CommandCenter::OnMissionStatus(const mission_status_t& message) {
  UpdateTime(message.utime);
  nlohmann::json mission = internal::MissionJson(message);
  if (mission != mission_) {
    mission_ = std::move(mission);
    mission_changed_ = true;
  }
}

void CommandCenter::OnRadioStats(const radio_stats_t& message) {
  UpdateTime(message.utime);
  internal::RaiseChannelAlerts(radio_, message, time_s_, *alerts_);
  nlohmann::json radio = internal::RadioJson(message);
  if (radio != radio_) {
    radio_ = std::move(radio);
    radio_changed_ = true;
  }
}

void CommandCenter::OnCommandStatus(const command_status_t& message) {
  UpdateTime(message.utime);
  // A refused command (ID 0, `refusal` says why: docs/lcm.md) has no record to
  // follow; a replayed log's refusals count as the live page's did.
  if (message.command_id == 0 && !message.refusal.empty()) {
    NoteRefused();
    return;
  }
  nlohmann::json row = internal::CommandRow(message);
  auto& kept = commands_[message.command_id];
  if (kept != row) {
    kept = std::move(row);
    changed_commands_.insert(message.command_id);
  }
  while (commands_.size() > config_.commands_kept) {
    changed_commands_.erase(commands_.begin()->first);
    commands_.erase(commands_.begin());
  }
}

void CommandCenter::OnConflict(const conflict_t& message) {
  UpdateTime(message.utime);
  conflicts_->Update(message, *alerts_);
  conflicts_changed_ = true;
}

void CommandCenter::NoteRefused() {
  ++refused_;
  refused_changed_ = true;
}

nlohmann::json CommandCenter::WholeRow(const Vehicle& vehicle) {
  nlohmann::json row = internal::VehicleRow(internal::FieldsOf(vehicle.last));
  row["trail"] = vehicle.trail;
  return row;
}

std::optional<nlohmann::json> CommandCenter::RowChanges(const Vehicle& vehicle) {
  const internal::VehicleFields now = internal::FieldsOf(vehicle.last);
  std::optional<internal::VehicleFields> before;
  if (vehicle.sent) before = internal::FieldsOf(*vehicle.sent);
  if (before && *before == now && vehicle.trail_unsent == 0) return std::nullopt;
  nlohmann::json row = internal::VehicleRow(now, before ? &*before : nullptr);
  if (vehicle.trail_unsent > 0) {
    nlohmann::json& trail = row["trail"] = nlohmann::json::array();
    for (std::size_t i = vehicle.trail.size() - vehicle.trail_unsent; i < vehicle.trail.size();
         ++i) {
      trail.push_back(vehicle.trail[i]);
    }
  }
  return row;
}

nlohmann::json CommandCenter::State() const {
  nlohmann::json vehicles = nlohmann::json::array();
  for (const auto& [id, vehicle] : vehicles_) vehicles.push_back(WholeRow(vehicle));
  nlohmann::json tracks = nlohmann::json::array();
  for (const auto& [id, track] : tracks_) tracks.push_back(track.row);
  nlohmann::json commands = nlohmann::json::array();
  for (const auto& [id, command] : commands_) commands.push_back(command);
  return {
      {"source", config_.source},
      {"read_only", config_.read_only},
      {"time_s", time_known_ ? nlohmann::json(time_s_) : nlohmann::json(nullptr)},
      {"plan", plan_info_},
      {"mission", mission_},
      {"vehicles", std::move(vehicles)},
      {"tracks", std::move(tracks)},
      {"radio", radio_},
      {"alerts", alerts_->All()},
      {"commands", std::move(commands)},
      {"refused", refused_},
      {"conflicts", conflicts_->Counts()},
  };
}

std::optional<nlohmann::json> CommandCenter::TakeDelta() {
  nlohmann::json delta = {{"type", "delta"}};
  bool any = std::exchange(time_changed_, false);
  if (std::exchange(plan_changed_, false)) delta["plan"] = plan_info_;
  if (std::exchange(mission_changed_, false)) delta["mission"] = mission_;
  nlohmann::json vehicles = nlohmann::json::array();
  for (auto& [id, vehicle] : vehicles_) {
    std::optional<nlohmann::json> row = RowChanges(vehicle);
    if (!row) continue;
    vehicles.push_back(std::move(*row));
    vehicle.sent = vehicle.last;
    vehicle.trail_unsent = 0;
  }
  if (!vehicles.empty()) delta["vehicles"] = std::move(vehicles);
  if (!changed_tracks_.empty()) {
    nlohmann::json& tracks = delta["tracks"] = nlohmann::json::array();
    for (const int id : changed_tracks_) tracks.push_back(tracks_.at(id).row);
    changed_tracks_.clear();
  }
  if (!removed_tracks_.empty()) {
    delta["removed_tracks"] = removed_tracks_;
    removed_tracks_.clear();
  }
  if (std::exchange(radio_changed_, false)) delta["radio"] = radio_;
  if (alerts_->has_new()) delta["alerts"] = alerts_->TakeNew();
  if (!changed_commands_.empty()) {
    nlohmann::json& commands = delta["commands"] = nlohmann::json::array();
    for (const int id : changed_commands_) commands.push_back(commands_.at(id));
    changed_commands_.clear();
  }
  if (std::exchange(refused_changed_, false)) delta["refused"] = refused_;
  if (std::exchange(conflicts_changed_, false)) delta["conflicts"] = conflicts_->Counts();
  if (!any && delta.size() == 1) return std::nullopt;
  delta["time_s"] = time_known_ ? nlohmann::json(time_s_) : nlohmann::json(nullptr);
  return delta;
}

nlohmann::json CommandCenter::Coverage() const {
  if (!coverage_) {
    return {{"cell_m", 0},
            {"rows", 0},
            {"cols", 0},
            {"corners", nlohmann::json::array()},
            {"seen", ""}};
  }
  return coverage_->ToJson();
}

}  // namespace fireswarm::server
