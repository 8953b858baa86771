#include "fireswarm/server/mission_manager.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <variant>

#include "fireswarm/common/time.hpp"
#include "fireswarm/radio/mission_chunks.hpp"

namespace fireswarm::server {

namespace {

// Waypoints this close to the launch site count as the launch site, m.
constexpr double kLaunchSiteM = 1.0;

}  // namespace

std::vector<DroneMission> ToDroneMissions(const planner::Plan& plan, std::uint16_t mission_id,
                                          double altitude_m, double speed_mps) {
  std::vector<DroneMission> missions;
  for (const planner::DronePlan& drone : plan.drones) {
    if (drone.receiver_id < 1 || drone.receiver_id > 254) {
      throw std::invalid_argument("receiver ID " + std::to_string(drone.receiver_id) +
                                  " is outside 1..254");
    }
    if (drone.waypoints.size() > radio::kMaxMissionWaypoints) {
      throw std::invalid_argument("drone " + std::to_string(drone.receiver_id) + " has " +
                                  std::to_string(drone.waypoints.size()) +
                                  " waypoints; a mission holds at most " +
                                  std::to_string(radio::kMaxMissionWaypoints));
    }
    DroneMission mission;
    mission.vehicle = static_cast<std::uint8_t>(drone.receiver_id);
    mission.mission_id = mission_id;
    for (const planner::Waypoint& point : drone.waypoints) {
      radio::Waypoint waypoint;
      waypoint.lat_deg = point.geodetic.lat_deg;
      waypoint.lon_deg = point.geodetic.lon_deg;
      waypoint.altitude_m = altitude_m;
      waypoint.speed_mps = speed_mps;
      waypoint.flags = point.starts_lane ? radio::Waypoint::kLaneStart : std::uint8_t{0};
      mission.waypoints.push_back(waypoint);
    }
    missions.push_back(std::move(mission));
  }
  return missions;
}

std::vector<DroneMission> WithoutLaunchSite(std::vector<DroneMission> missions,
                                            const common::LocalFrame& frame,
                                            common::EastNorth launch) {
  const auto at_launch = [&](const radio::Waypoint& waypoint) {
    const common::EastNorth local = frame.ToLocal({waypoint.lat_deg, waypoint.lon_deg});
    return std::hypot(local.east_m - launch.east_m, local.north_m - launch.north_m) < kLaunchSiteM;
  };
  for (DroneMission& mission : missions) {
    std::vector<radio::Waypoint>& route = mission.waypoints;
    while (route.size() > 1 && at_launch(route.back())) route.pop_back();
    std::size_t first = 0;
    while (first + 1 < route.size() && at_launch(route[first])) ++first;
    route.erase(route.begin(), route.begin() + static_cast<std::ptrdiff_t>(first));
  }
  return missions;
}

const char* ToString(DronePhase phase) {
  switch (phase) {
    case DronePhase::kUploading:
      return "uploading";
    case DronePhase::kStarting:
      return "starting";
    case DronePhase::kFlying:
      return "flying";
    case DronePhase::kDone:
      return "done";
    case DronePhase::kFailed:
      return "failed";
  }
  return "unknown";
}

MissionManager::MissionManager(radio::MasterScheduler& scheduler,
                               std::vector<DroneMission> missions,
                               const MissionManagerConfig& config)
    : scheduler_(scheduler), config_(config) {
  for (DroneMission& mission : missions) {
    const std::uint8_t vehicle = mission.vehicle;
    if (drones_.contains(vehicle)) {
      throw std::invalid_argument("vehicle " + std::to_string(vehicle) +
                                  " has two missions in one plan");
    }
    drones_.emplace(vehicle, DroneFor(std::move(mission)));
  }
}

MissionManager::Drone MissionManager::DroneFor(DroneMission mission) {
  Drone drone;
  drone.chunks = radio::SplitMission(mission.mission_id, mission.waypoints);
  drone.chunk_rounds.assign(drone.chunks.size(), 0);
  drone.progress.chunk_count = drone.chunks.size();
  drone.progress.waypoint_count = mission.waypoints.size();
  drone.mission = std::move(mission);
  return drone;
}

void MissionManager::Replace(DroneMission mission, bool send) {
  const std::uint8_t vehicle = mission.vehicle;
  Drone& drone = Find(vehicle);
  if (mission.mission_id == drone.mission.mission_id) {
    throw std::invalid_argument("vehicle " + std::to_string(vehicle) + " already has mission " +
                                std::to_string(mission.mission_id));
  }
  // Answers to the old mission's requests are no longer this drone's business.
  std::erase_if(pending_, [&](const auto& entry) { return entry.second.vehicle == vehicle; });
  drone = DroneFor(std::move(mission));
  ++missions_version_;
  if (!send) return;
  for (std::size_t i = 0; i < drone.chunks.size(); ++i) SendChunk(drone, i);
}

void MissionManager::MarkLost(std::uint8_t vehicle, std::string why) {
  Drone& drone = Find(vehicle);
  std::erase_if(pending_, [&](const auto& entry) { return entry.second.vehicle == vehicle; });
  Fail(drone, std::move(why));
}

std::vector<radio::Waypoint> MissionManager::Remaining(std::uint8_t vehicle,
                                                       bool from_leg_start) const {
  const Drone& drone = Find(vehicle);
  const std::vector<radio::Waypoint>& route = drone.mission.waypoints;
  std::size_t first = drone.progress.waypoint_index;
  if (from_leg_start && first > 0) --first;
  if (first >= route.size()) return {};
  return {route.begin() + static_cast<std::ptrdiff_t>(first), route.end()};
}

const DroneMission& MissionManager::mission_of(std::uint8_t vehicle) const {
  return Find(vehicle).mission;
}

const MissionManager::Drone& MissionManager::Find(std::uint8_t vehicle) const {
  const auto found = drones_.find(vehicle);
  if (found == drones_.end()) {
    throw std::out_of_range("vehicle " + std::to_string(vehicle) + " has no mission");
  }
  return found->second;
}

MissionManager::Drone& MissionManager::Find(std::uint8_t vehicle) {
  return const_cast<Drone&>(std::as_const(*this).Find(vehicle));
}

void MissionManager::Begin() {
  for (auto& [vehicle, drone] : drones_) {
    if (drone.progress.phase != DronePhase::kUploading) continue;
    for (std::size_t i = 0; i < drone.chunks.size(); ++i) SendChunk(drone, i);
  }
}

void MissionManager::SendChunk(Drone& drone, std::size_t index) {
  ++drone.chunk_rounds[index];
  const radio::RequestId id =
      scheduler_.SendMissionChunk(drone.mission.vehicle, drone.chunks[index]);
  pending_[id] = Pending{drone.mission.vehicle, static_cast<int>(index)};
}

void MissionManager::SendStart(Drone& drone) {
  radio::Command start;
  start.type = radio::CommandType::kStartMission;
  start.mission_id = drone.mission.mission_id;
  drone.progress.phase = DronePhase::kStarting;
  drone.retry_start_at = common::Nanos::max();
  pending_[scheduler_.SendCommand(drone.mission.vehicle, start)] =
      Pending{drone.mission.vehicle, -1};
}

void MissionManager::Fail(Drone& drone, std::string why) {
  drone.progress.phase = DronePhase::kFailed;
  drone.progress.failure = std::move(why);
  drone.retry_start_at = common::Nanos::max();
}

void MissionManager::OnEvent(const radio::SchedulerEvent& event) {
  if (const auto* finished = std::get_if<radio::RequestFinished>(&event)) {
    OnFinished(*finished);
  } else if (const auto* telemetry = std::get_if<radio::TelemetryReceived>(&event)) {
    OnTelemetry(*telemetry);
  }
}

void MissionManager::OnFinished(const radio::RequestFinished& finished) {
  const auto found = pending_.find(finished.id);
  if (found == pending_.end()) return;  // someone else's request
  const Pending pending = found->second;
  pending_.erase(found);
  Drone& drone = drones_.at(pending.vehicle);
  if (drone.progress.phase == DronePhase::kFailed) return;

  if (pending.chunk >= 0) {
    const auto index = static_cast<std::size_t>(pending.chunk);
    if (finished.status == radio::RequestStatus::kFailed) {
      if (drone.chunk_rounds[index] >= config_.chunk_rounds) {
        Fail(drone, "chunk " + std::to_string(index) + " unanswered after " +
                        std::to_string(drone.chunk_rounds[index]) + " rounds of retries");
      } else {
        SendChunk(drone, index);
      }
      return;
    }
    const auto* ack = finished.ack ? std::get_if<radio::MissionAck>(&*finished.ack) : nullptr;
    if (ack == nullptr || ack->status == radio::MissionAckStatus::kRejected) {
      Fail(drone, "the vehicle rejected chunk " + std::to_string(index));
      return;
    }
    ++drone.progress.chunks_acked;
    if (ack->status == radio::MissionAckStatus::kComplete &&
        drone.progress.phase == DronePhase::kUploading) {
      SendStart(drone);
    }
    return;
  }

  // The start command.
  if (finished.status == radio::RequestStatus::kFailed) {
    drone.retry_start_at = finished.finished;  // unanswered: ask again at once
    return;
  }
  const auto* ack = finished.ack ? std::get_if<radio::CommandAck>(&*finished.ack) : nullptr;
  if (ack != nullptr && ack->result == radio::CommandResult::kAccepted) {
    drone.progress.phase = DronePhase::kFlying;
    return;
  }
  ++drone.progress.start_refusals;
  drone.retry_start_at = finished.finished + common::FromSeconds(config_.start_retry_s);
}

void MissionManager::OnTelemetry(const radio::TelemetryReceived& received) {
  const auto found = drones_.find(received.vehicle);
  if (found == drones_.end()) return;
  Drone& drone = found->second;
  const radio::Telemetry& telemetry = received.telemetry;
  if (telemetry.mission_id != drone.mission.mission_id) return;
  if (drone.progress.phase != DronePhase::kFlying) return;
  drone.progress.waypoint_index = std::max(drone.progress.waypoint_index, telemetry.waypoint_index);
  if (telemetry.mode == radio::FlightMode::kLanded) drone.progress.phase = DronePhase::kDone;
}

void MissionManager::Step(common::Nanos now) {
  for (auto& [vehicle, drone] : drones_) {
    if (drone.progress.phase == DronePhase::kStarting && drone.retry_start_at <= now) {
      SendStart(drone);
    }
  }
}

common::Nanos MissionManager::NextWakeup() const {
  common::Nanos next = common::Nanos::max();
  for (const auto& [vehicle, drone] : drones_) next = std::min(next, drone.retry_start_at);
  return next;
}

void MissionManager::RestorePhase(std::uint8_t vehicle, DronePhase phase) {
  Drone& drone = Find(vehicle);
  drone.progress.phase = phase;
  if (phase != DronePhase::kUploading) drone.progress.chunks_acked = drone.chunks.size();
  drone.retry_start_at = phase == DronePhase::kStarting ? common::Nanos{0} : common::Nanos::max();
}

const DroneProgress& MissionManager::progress(std::uint8_t vehicle) const {
  return Find(vehicle).progress;
}

std::vector<std::uint8_t> MissionManager::vehicles() const {
  std::vector<std::uint8_t> ids;
  for (const auto& [vehicle, drone] : drones_) ids.push_back(vehicle);
  return ids;
}

bool MissionManager::AllStarted() const {
  return std::ranges::none_of(drones_, [](const auto& entry) {
    const DronePhase phase = entry.second.progress.phase;
    return phase == DronePhase::kUploading || phase == DronePhase::kStarting;
  });
}

double MissionManager::WaypointFraction(std::uint8_t vehicle) const {
  const DroneProgress& progress = Find(vehicle).progress;
  if (progress.phase == DronePhase::kDone) return 1.0;
  if (progress.waypoint_count == 0) return 0.0;
  return static_cast<double>(
             std::min<std::size_t>(progress.waypoint_index, progress.waypoint_count)) /
         static_cast<double>(progress.waypoint_count);
}

double MissionManager::WaypointFraction() const {
  std::size_t total = 0;
  std::size_t passed = 0;
  for (const auto& [vehicle, drone] : drones_) {
    const DroneProgress& progress = drone.progress;
    total += progress.waypoint_count;
    passed += progress.phase == DronePhase::kDone
                  ? progress.waypoint_count
                  : std::min<std::size_t>(progress.waypoint_index, progress.waypoint_count);
  }
  return total == 0 ? 0.0 : static_cast<double>(passed) / static_cast<double>(total);
}

}  // namespace fireswarm::server
