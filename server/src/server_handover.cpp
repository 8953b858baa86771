// The server's side of a lost drone: when a flying drone (or one on the ground
// between sorties) has not been heard for the registry's lost time, it is given
// up and the lanes it had still to fly, its later sorties' included, go to the
// drones still searching or waiting for their pack with sorties to fly
// (handover.hpp says how they are shared out), each as a new mission uploaded
// and started like the first (after the swap for a drone on the ground), its
// joins to the new lanes routed around the no-fly zones. If it is heard again,
// it is sent home.
#include <string>

#include "fireswarm/server/handover.hpp"
#include "fireswarm/server/server.hpp"
#include "local_point.hpp"

namespace fireswarm::server {

void Server::HandOverLostDrones(double now_s) {
  if (!mission_ || !config_.hand_over_lost_lanes || state_ != MissionState::kRunning) return;
  for (const std::uint8_t id : mission_->vehicles()) {
    // Flying, or on the ground between sorties with more to fly.
    const DronePhase phase = mission_->progress(id).phase;
    if (phase != DronePhase::kFlying && phase != DronePhase::kSwapping) continue;
    if (registry_.LinkAt(id, now_s) != LinkState::kLost) continue;
    HandOver(id, now_s);
  }
}

std::vector<Taker> Server::TakersFor(std::uint8_t lost, double now_s) const {
  std::vector<Taker> takers;
  for (const std::uint8_t id : mission_->vehicles()) {
    if (id == lost || registry_.LinkAt(id, now_s) != LinkState::kOk) continue;
    const std::optional<radio::Telemetry>& telemetry = registry_.state(id).telemetry;
    if (!telemetry) continue;
    // Searching, or on the ground for its pack with sorties still to fly (the
    // lanes end its last one; the swap clears a low battery).
    const DronePhase phase = mission_->progress(id).phase;
    if (phase == DronePhase::kSwapping) {
      if (mission_->Remaining(id, /*from_leg_start=*/false).empty()) continue;
    } else if (phase != DronePhase::kFlying ||
               (telemetry->flags & radio::telemetry_flags::kLowBattery) != 0 ||
               (telemetry->mode != radio::FlightMode::kSearch &&
                telemetry->mode != radio::FlightMode::kInvestigate)) {
      continue;  // returning, landing: its flight is over
    }
    Taker taker;
    taker.vehicle = id;
    taker.position_en_m = LocalM(frame_, {telemetry->lat_deg, telemetry->lon_deg});
    // Its later sorties too: the lanes it gets are added to its last one.
    taker.remaining = mission_->Remaining(id, /*from_leg_start=*/false);
    const std::vector<radio::Waypoint>& own = mission_->mission_of(id).waypoints;
    taker.altitude_m = own.empty() ? telemetry->altitude_m : own.front().altitude_m;
    // Its search layer (the first waypoint is its climb-out's transit layer).
    if (airspace_) {
      for (const DroneLayers& layers : airspace_->drones) {
        if (layers.vehicle == id) taker.altitude_m = layers.search_altitude_m;
      }
    }
    taker.speed_mps = own.empty() ? 0.0 : own.front().speed_mps;
    takers.push_back(std::move(taker));
  }
  return takers;
}

void Server::HandOver(std::uint8_t lost, double now_s) {
  const std::vector<radio::Waypoint> orphaned = mission_->Remaining(lost, /*from_leg_start=*/true);
  const std::string why =
      "lost: not heard for " + std::to_string(static_cast<int>(config_.link.lost_after_s)) + " s";
  mission_->MarkLost(lost, why);
  handed_over_[lost] = false;
  // New mission IDs above every one in use (every sortie's), so no vehicle takes
  // one for another.
  std::uint16_t next_id = mission_->LastMissionId();
  LaneHandOver handed = HandOverLanes(orphaned, TakersFor(lost, now_s), frame_, transit_.get());
  LanesHandedOver record{lost, why, {}, handed.straight_joins};
  for (auto& [vehicle, route] : handed.routes) {
    DroneMission mission;
    mission.vehicle = vehicle;
    mission.waypoints = std::move(route);
    // The taker's own later sorties keep their places at the head of its new
    // route (HandOverLanes keeps its remaining waypoints first); the lanes it
    // takes end its last sortie, and a low battery on them makes their rest a
    // sortie of its own (mission_manager.hpp).
    mission_->Remaining(vehicle, /*from_leg_start=*/false, &mission.sortie_starts);
    mission.mission_id = next_id + 1;
    next_id = static_cast<std::uint16_t>(next_id + SortieCount(mission));
    record.drones.push_back(mission);
    mission_->Replace(std::move(mission));
  }
  Record(now_s, std::move(record));
}

// A drone given up as lost may only have been out of reach. Its lanes are
// someone else's now, and the taker may fly them on the same layer: when it is
// heard again still flying its mission, it is ordered home, once (the
// scheduler retries the command until the vehicle acknowledges it).
void Server::RecallHandedOverDrones(double now_s) {
  for (auto& [id, recalled] : handed_over_) {
    if (recalled || registry_.LinkAt(id, now_s) != LinkState::kOk) continue;
    const std::optional<radio::Telemetry>& telemetry = registry_.state(id).telemetry;
    if (!telemetry) continue;
    const radio::FlightMode mode = telemetry->mode;
    if (mode != radio::FlightMode::kSearch && mode != radio::FlightMode::kInvestigate &&
        mode != radio::FlightMode::kTakeoff && mode != radio::FlightMode::kHold) {
      continue;  // on its way home or down already
    }
    radio::Command command;
    command.type = radio::CommandType::kReturnToLaunch;
    scheduler_->SendCommand(id, command);
    recalled = true;
    Record(now_s, DroneRecalled{id, "heard again after its lanes were handed over"});
  }
}

}  // namespace fireswarm::server
