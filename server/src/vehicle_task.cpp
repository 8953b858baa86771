#include "fireswarm/server/vehicle_task.hpp"

#include <algorithm>
#include <optional>

#include "fireswarm/server/server.hpp"

namespace fireswarm::server {

namespace {

// The task its telemetry's mode alone tells; nullopt for modes that need the
// server's view (idle, take-off, search).
std::optional<VehicleTask> TaskOfMode(radio::FlightMode mode) {
  switch (mode) {
    case radio::FlightMode::kLanded:
      return VehicleTask::kLanded;
    case radio::FlightMode::kLand:
      return VehicleTask::kLanding;
    case radio::FlightMode::kReturnToLaunch:
      return VehicleTask::kReturning;
    case radio::FlightMode::kHold:
      return VehicleTask::kHolding;
    case radio::FlightMode::kInvestigate:
      return VehicleTask::kInvestigating;
    case radio::FlightMode::kIdle:
    case radio::FlightMode::kTakeoff:
    case radio::FlightMode::kSearch:
      break;
  }
  return std::nullopt;
}

bool HasMission(const MissionManager* mission, std::uint8_t vehicle) {
  return mission != nullptr && std::ranges::binary_search(mission->vehicles(), vehicle);
}

}  // namespace

const char* ToString(VehicleTask task) {
  switch (task) {
    case VehicleTask::kIdle:
      return "idle";
    case VehicleTask::kUploading:
      return "uploading";
    case VehicleTask::kLane:
      return "lane";
    case VehicleTask::kInvestigating:
      return "investigating";
    case VehicleTask::kReturning:
      return "returning";
    case VehicleTask::kLanding:
      return "landing";
    case VehicleTask::kLanded:
      return "landed";
    case VehicleTask::kGivenUp:
      return "given_up";
    case VehicleTask::kHolding:
      return "holding";
  }
  return "unknown";
}

LanePosition LaneOf(const std::vector<radio::Waypoint>& route, std::size_t flying_to) {
  LanePosition lanes;
  for (std::size_t i = 0; i + 1 < route.size(); ++i) {
    if ((route[i].flags & radio::Waypoint::kLaneStart) == 0) continue;
    ++lanes.count;
    // Lane `count` ends at waypoint i + 1: it is flown or still ahead while the
    // drone flies to that waypoint or an earlier one.
    if (lanes.index == 0 && i + 1 >= flying_to) lanes.index = lanes.count;
  }
  return lanes;
}

TaskView TaskOf(const Server& server, std::uint8_t vehicle, double now_s) {
  TaskView view;
  const MissionManager* mission = server.mission();
  const bool has_mission = HasMission(mission, vehicle);
  std::optional<DronePhase> phase;
  LanePosition lanes;
  if (has_mission) {
    const DroneProgress& progress = mission->progress(vehicle);
    phase = progress.phase;
    lanes = LaneOf(mission->mission_of(vehicle).waypoints, progress.waypoint_index);
    view.lane_count = lanes.count;
    view.progress_fraction = mission->WaypointFraction(vehicle);
    view.sorties_flown = static_cast<int>(progress.sorties_flown);
    view.sortie_count = static_cast<int>(progress.sorties_flown + progress.sortie_count -
                                         std::min(progress.sortie, progress.sortie_count));
    if (progress.phase != DronePhase::kDone && progress.phase != DronePhase::kFailed &&
        progress.phase != DronePhase::kSwapping) {
      view.sortie = static_cast<int>(progress.sorties_flown) + 1;
    }
  }
  // Its latest investigation: the one it flies, or flew last.
  const Investigation* investigation = nullptr;
  for (const Investigation& i : server.investigations()) {
    if (i.vehicle == vehicle) investigation = &i;
  }
  const auto investigating = [&] {
    view.task = VehicleTask::kInvestigating;
    view.track_id = investigation != nullptr ? investigation->track_id : 0;
    return view;
  };

  const auto handed = server.handed_over().find(vehicle);
  const bool handed_over = handed != server.handed_over().end();
  const bool heard_since = handed_over && handed->second;
  if ((handed_over && !heard_since) || (!handed_over && phase == DronePhase::kFailed)) {
    view.task = VehicleTask::kGivenUp;
    return view;
  }
  const std::optional<radio::Telemetry>& telemetry = server.registry().state(vehicle).telemetry;
  if (telemetry) {
    if (const std::optional<VehicleTask> task = TaskOfMode(telemetry->mode)) {
      if (*task == VehicleTask::kInvestigating) return investigating();
      view.task = *task;
      return view;
    }
  }
  if (investigation != nullptr && !investigation->judged && investigation->until_s > now_s) {
    return investigating();
  }
  if (!phase) return view;
  switch (*phase) {
    case DronePhase::kUploading:
    case DronePhase::kStarting:
      // A mission loaded but not started is not going up yet.
      if (server.state() != MissionState::kIdle) view.task = VehicleTask::kUploading;
      break;
    case DronePhase::kFlying:
      view.task = VehicleTask::kLane;
      view.lane_index = lanes.index;
      break;
    case DronePhase::kDone:
    case DronePhase::kSwapping:
      view.task = VehicleTask::kLanded;
      break;
    case DronePhase::kFailed:
      view.task = VehicleTask::kGivenUp;
      break;
  }
  return view;
}

}  // namespace fireswarm::server
