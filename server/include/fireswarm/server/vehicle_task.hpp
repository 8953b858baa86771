// What the server has each vehicle doing, as the operator's displays show it
// (vehicle_state_t's task, lane and progress fields): worked out from what the
// server knows, its mission manager's phases, its investigations, its hand-overs
// of lost drones and the vehicle's latest telemetry. Pure.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "fireswarm/radio/messages.hpp"

namespace fireswarm::server {

class Server;

/// vehicle_state_t's TASK_* values.
enum class VehicleTask : std::int8_t {
  kIdle = 0,           ///< no mission, or not started
  kUploading = 1,      ///< its mission is going up, or its start is asked
  kLane = 2,           ///< flying its mission's route (lanes and the transits between)
  kInvestigating = 3,  ///< sent to look at a fire track or an operator's point
  kReturning = 4,      ///< flying home (telemetry: return to launch)
  kLanding = 5,        ///< telemetry: land
  kLanded = 6,         ///< telemetry: landed, or its mission is done
  kGivenUp = 7,        ///< lost and its lanes handed over, or its upload failed
  kHolding = 8,        ///< telemetry: hold
};
/// "idle", "uploading", "lane", "investigating", "returning", "landing", "landed",
/// "given_up", "holding"; "unknown" outside the enum.
const char* ToString(VehicleTask task);

/// Where a route's search lanes are. A lane is a waypoint flagged as a lane start
/// (radio::Waypoint::flags bit 0, the planner's starts_lane) and the waypoint
/// after it; the legs between lanes are transits.
struct LanePosition {
  /// The lane being flown, or between lanes the next one, from 1; 0 when no lane
  /// is left (on the way home) or the route has none.
  int index = 0;
  int count = 0;  ///< lanes in the route
};
/// The lane of a drone flying to waypoint `flying_to` (telemetry's waypoint_index)
/// of `route`.
LanePosition LaneOf(const std::vector<radio::Waypoint>& route, std::size_t flying_to);

/// One vehicle's task as the server sees it.
struct TaskView {
  VehicleTask task = VehicleTask::kIdle;
  /// kInvestigating: the fire track it looks at; 0: an operator's point (or none).
  std::int32_t track_id = 0;
  int lane_index = 0;  ///< LanePosition::index while kLane, 0 otherwise
  int lane_count = 0;  ///< lanes in its mission; 0 without one
  /// Share of its mission's waypoints passed, [0, 1]; 0 without a mission.
  double progress_fraction = 0.0;
  /// Sorties: the one going up or flown now, from 1 (0 while on the ground
  /// between sorties, done or without a mission); flown so far; in all (flown
  /// plus those still to fly, a handed-over mission's included).
  int sortie = 0;
  int sorties_flown = 0;
  int sortie_count = 0;
};

/// What `vehicle` (registered) does at `now_s` (mission seconds). In order: a drone
/// given up (handed over and not heard since, or its upload failed) is kGivenUp;
/// then its telemetry's mode says landed, landing, returning, holding or
/// investigating; then an investigation the server ordered and that still runs;
/// then its mission phase once the mission started (uploading or starting:
/// kUploading, flying: kLane, done: kLanded); else kIdle.
TaskView TaskOf(const Server& server, std::uint8_t vehicle, double now_s);

}  // namespace fireswarm::server
