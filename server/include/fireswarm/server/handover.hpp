// Handing a lost drone's lanes to the drones still flying. Pure: waypoints in,
// waypoints out, in the mission area's local frame.
//
// The lost drone's remaining route is cut into its search lanes (a waypoint with
// the lane-start flag and the one after it); the transit legs between them are
// dropped, each taker flies its own. Lanes go out in the lost drone's order, in
// runs: the taker whose route ends nearest takes lanes until its work (its own
// remaining route, the transits and the lanes) reaches an equal share of the
// whole, then the taker nearest to the next lane, and so on (takers already over
// the share take none while another can). Each taker's new route is its own remaining
// waypoints, then its lanes, flown at its own altitude and speed (altitude layers
// keep drones apart). Lanes are flown in the direction nearer to the taker.
// With no-fly zones, every join the hand-over makes (from the taker's route or
// position to a lane, from a lane to the next) goes around them: the transit's
// corners are inserted as plain waypoints. Takers and directions are still chosen
// by straight distances; the work counted is the routed one.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <vector>

#include "fireswarm/common/local_frame.hpp"
#include "fireswarm/planner/transit.hpp"
#include "fireswarm/radio/messages.hpp"

namespace fireswarm::server {

/// A drone that can take lanes.
struct Taker {
  std::uint8_t vehicle = 0;
  /// Where it is now, local (east, north) m.
  Eigen::Vector2d position_en_m = Eigen::Vector2d::Zero();
  /// The waypoints it still has to fly, the one it flies to first. May be empty
  /// (a drone whose lanes are all flown).
  std::vector<radio::Waypoint> remaining;
  /// Altitude and speed of the lanes it takes (its own).
  double altitude_m = 0.0;
  double speed_mps = 0.0;
};

/// What a hand-over gives out.
struct LaneHandOver {
  /// Each taker's new route, for the takers that got at least one lane.
  std::map<std::uint8_t, std::vector<radio::Waypoint>> routes;
  /// Joins that could not be routed around the no-fly zones (an end inside a zone,
  /// or no way around found) and are flown straight. 0 when they all were.
  int straight_joins = 0;
};

/// The lost drone's `orphaned` waypoints (from the one it was flying away from)
/// shared out among `takers` (not empty). A taker's new route is its remaining
/// waypoints, its share of the lanes, then back to where its remaining route
/// ended (the way home, at its return altitude). `around`: the no-fly zones' transit
/// planner (in `frame`'s local metres), or null for straight joins. Routes nothing
/// when `orphaned` has no lane.
LaneHandOver HandOverLanes(const std::vector<radio::Waypoint>& orphaned,
                           const std::vector<Taker>& takers, const common::LocalFrame& frame,
                           const planner::TransitPlanner* around = nullptr);

}  // namespace fireswarm::server
