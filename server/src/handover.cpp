#include "fireswarm/server/handover.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>
#include <utility>

#include "local_point.hpp"

namespace fireswarm::server {
namespace {

struct Lane {
  Eigen::Vector2d start_en_m;
  Eigen::Vector2d end_en_m;
};

// How far a taker has to fly, and where its route ends, as lanes are added.
struct Load {
  double work_m = 0.0;
  Eigen::Vector2d end_en_m = Eigen::Vector2d::Zero();
  std::vector<radio::Waypoint> added;
};

Eigen::Vector2d LocalOf(const common::LocalFrame& frame, const radio::Waypoint& waypoint) {
  return LocalM(frame, {waypoint.lat_deg, waypoint.lon_deg});
}

std::vector<Lane> LanesOf(const std::vector<radio::Waypoint>& route,
                          const common::LocalFrame& frame) {
  std::vector<Lane> lanes;
  for (std::size_t i = 0; i + 1 < route.size(); ++i) {
    if ((route[i].flags & radio::Waypoint::kLaneStart) == 0) continue;
    lanes.push_back({LocalOf(frame, route[i]), LocalOf(frame, route[i + 1])});
  }
  return lanes;
}

Load LoadOf(const Taker& taker, const common::LocalFrame& frame) {
  Load load;
  load.end_en_m = taker.position_en_m;
  for (const radio::Waypoint& waypoint : taker.remaining) {
    const Eigen::Vector2d next = LocalOf(frame, waypoint);
    load.work_m += (next - load.end_en_m).norm();
    load.end_en_m = next;
  }
  return load;
}

double Reach(const Load& load, const Lane& lane) {
  return std::min((lane.start_en_m - load.end_en_m).norm(), (lane.end_en_m - load.end_en_m).norm());
}

// The taker nearest to `lane` among those not yet done (none: the least loaded).
std::size_t Nearest(const std::vector<Load>& loads, const std::vector<bool>& done,
                    const Lane& lane) {
  std::size_t best = loads.size();
  double best_reach = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < loads.size(); ++i) {
    if (done[i]) continue;
    const double reach = Reach(loads[i], lane);
    if (reach < best_reach) {
      best_reach = reach;
      best = i;
    }
  }
  if (best < loads.size()) return best;
  best = 0;
  for (std::size_t i = 1; i < loads.size(); ++i) {
    if (loads[i].work_m < loads[best].work_m) best = i;
  }
  return best;
}

radio::Waypoint WaypointAt(const common::LocalFrame& frame, const Eigen::Vector2d& en_m,
                           const Taker& taker, bool lane_start) {
  const common::LatLon p = Geodetic(frame, en_m);
  radio::Waypoint waypoint;
  waypoint.lat_deg = p.lat_deg;
  waypoint.lon_deg = p.lon_deg;
  waypoint.altitude_m = taker.altitude_m;
  waypoint.speed_mps = taker.speed_mps;
  waypoint.flags = lane_start ? radio::Waypoint::kLaneStart : 0;
  return waypoint;
}

// The corners a join from `from` to `to` turns at to keep out of the no-fly
// zones: none when the straight leg is clear. A join that cannot be routed (an
// end inside a zone: a drone that drifted in) stays straight and is counted.
std::vector<Eigen::Vector2d> JoinCorners(const planner::TransitPlanner* around,
                                         const Eigen::Vector2d& from, const Eigen::Vector2d& to,
                                         int& straight_joins) {
  if (around == nullptr || around->IsClear(PlannerPoint(from), PlannerPoint(to))) return {};
  try {
    const planner::Path path = around->Plan(PlannerPoint(from), PlannerPoint(to));
    std::vector<Eigen::Vector2d> corners;
    for (std::size_t i = 1; i + 1 < path.size(); ++i) corners.push_back(FromPlanner(path[i]));
    return corners;
  } catch (const std::runtime_error&) {
    ++straight_joins;
    return {};
  }
}

}  // namespace

LaneHandOver HandOverLanes(const std::vector<radio::Waypoint>& orphaned,
                           const std::vector<Taker>& takers, const common::LocalFrame& frame,
                           const planner::TransitPlanner* around) {
  LaneHandOver result;
  const std::vector<Lane> lanes = LanesOf(orphaned, frame);
  if (lanes.empty() || takers.empty()) return result;
  std::vector<Load> loads;
  double total_m = 0.0;
  for (const Taker& taker : takers) {
    loads.push_back(LoadOf(taker, frame));
    total_m += loads.back().work_m;
  }
  for (const Lane& lane : lanes) total_m += (lane.end_en_m - lane.start_en_m).norm();
  const double share_m = total_m / static_cast<double>(takers.size());

  // Runs of neighbouring lanes: the nearest taker takes lanes until its work
  // reaches the share, then the one nearest to the next lane, and so on.
  std::vector<bool> done(loads.size());
  for (std::size_t i = 0; i < loads.size(); ++i) done[i] = loads[i].work_m >= share_m;
  std::size_t taker = Nearest(loads, done, lanes.front());
  for (const Lane& lane : lanes) {
    if (loads[taker].work_m >= share_m) {
      done[taker] = true;
      // The last taker with work to take takes the rest.
      if (std::ranges::find(done, false) != done.end()) taker = Nearest(loads, done, lane);
    }
    Load& load = loads[taker];
    // Flown from whichever end is nearer.
    Eigen::Vector2d start = lane.start_en_m;
    Eigen::Vector2d end = lane.end_en_m;
    if ((end - load.end_en_m).norm() < (start - load.end_en_m).norm()) std::swap(start, end);
    for (const Eigen::Vector2d& corner :
         JoinCorners(around, load.end_en_m, start, result.straight_joins)) {
      load.added.push_back(WaypointAt(frame, corner, takers[taker], /*lane_start=*/false));
      load.work_m += (corner - load.end_en_m).norm();
      load.end_en_m = corner;
    }
    load.added.push_back(WaypointAt(frame, start, takers[taker], /*lane_start=*/true));
    load.added.push_back(WaypointAt(frame, end, takers[taker], /*lane_start=*/false));
    load.work_m += (start - load.end_en_m).norm() + (end - start).norm();
    load.end_en_m = end;
  }

  for (std::size_t i = 0; i < takers.size(); ++i) {
    Load& load = loads[i];
    if (load.added.empty()) continue;
    std::vector<radio::Waypoint> route = takers[i].remaining;
    // Its own route ended on the way home (the planner's transit, the return
    // altitude); after the extra lanes it goes back there, around the zones,
    // rather than straight home from the last one.
    if (!route.empty()) {
      radio::Waypoint home_leg = route.back();
      home_leg.flags = 0;
      home_leg.speed_mps = takers[i].speed_mps;
      const Eigen::Vector2d to = LocalOf(frame, home_leg);
      for (const Eigen::Vector2d& corner :
           JoinCorners(around, load.end_en_m, to, result.straight_joins)) {
        radio::Waypoint waypoint = WaypointAt(frame, corner, takers[i], /*lane_start=*/false);
        waypoint.altitude_m = home_leg.altitude_m;
        load.added.push_back(waypoint);
      }
      load.added.push_back(home_leg);
    }
    route.insert(route.end(), load.added.begin(), load.added.end());
    result.routes[takers[i].vehicle] = std::move(route);
  }
  return result;
}

}  // namespace fireswarm::server
