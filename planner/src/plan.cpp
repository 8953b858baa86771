// PlanSearch: validation, the fleet's route, its partition, sorties and figures.
#include "fireswarm/planner/plan.hpp"

#include <algorithm>
#include <boost/geometry.hpp>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <set>
#include <stdexcept>
#include <string>

#include "coverage.hpp"
#include "coverage_raster.hpp"
#include "fireswarm/planner/footprint.hpp"
#include "fireswarm/planner/transit.hpp"
#include "lanes.hpp"
#include "partition.hpp"
#include "sorties.hpp"

namespace fireswarm::planner {
namespace bg = boost::geometry;

namespace {

constexpr int kMinReceiverId = 1;
constexpr int kMaxReceiverId = 254;
constexpr double kPlanBoundsMarginM = 500.0;  // room for transits around the area
constexpr double kOmplTurnAngleRad = 0.5;     // heading changes counted as turns on OMPL paths

void Require(bool ok, const std::string& message) {
  if (!ok) throw std::invalid_argument(message);
}

bool PositiveFinite(double value) {
  return value > 0.0 && std::isfinite(value);
}

void ValidateFleet(const SearchArea& area, const FleetSpec& fleet) {
  Require(!fleet.receiver_ids.empty(), "receiver_ids: the fleet has no drones");
  std::set<int> seen;
  for (const int id : fleet.receiver_ids) {
    Require(id >= kMinReceiverId && id <= kMaxReceiverId,
            "receiver_ids: " + std::to_string(id) + " is not in 1..254");
    Require(seen.insert(id).second, "receiver_ids: " + std::to_string(id) + " appears twice");
  }
  const std::size_t n = fleet.receiver_ids.size();
  Require(!fleet.launch_points.empty(), "launch_points: the fleet has no launch site");
  if (!fleet.site_drones.empty()) {
    Require(fleet.site_drones.size() == fleet.launch_points.size(),
            "site_drones: need one count per launch site (" +
                std::to_string(fleet.launch_points.size()) + "), got " +
                std::to_string(fleet.site_drones.size()));
    long long total = 0;
    for (const int count : fleet.site_drones) {
      Require(count >= 0, "site_drones: a count is negative (" + std::to_string(count) + ")");
      total += count;
    }
    Require(total == static_cast<long long>(n), "site_drones: the counts add up to " +
                                                    std::to_string(total) + ", the fleet has " +
                                                    std::to_string(n) + " drones");
  }
  for (const Point& launch : fleet.launch_points) {
    Require(std::isfinite(launch.x()) && std::isfinite(launch.y()), "launch_points: not finite");
    Require(!bg::within(launch, area.no_fly), "launch_points: (" + std::to_string(launch.x()) +
                                                  ", " + std::to_string(launch.y()) +
                                                  ") is inside a no-fly zone");
  }
  Require(PositiveFinite(fleet.speed_mps),
          "speed_mps must be > 0, got " + std::to_string(fleet.speed_mps));
  Require(PositiveFinite(fleet.endurance_s),
          "endurance_s must be > 0, got " + std::to_string(fleet.endurance_s));
  Require(fleet.swap_s >= 0.0 && std::isfinite(fleet.swap_s),
          "swap_s must be >= 0, got " + std::to_string(fleet.swap_s));
  Require(fleet.turn_cost_s >= 0.0 && std::isfinite(fleet.turn_cost_s),
          "turn_cost_s must be >= 0, got " + std::to_string(fleet.turn_cost_s));
  SweepWidthM(fleet);  // throws naming camera, altitude_m, camera_pitch_deg or side_overlap
}

MultiPolygon SearchRegion(const SearchArea& area) {
  Require(!area.area.empty(), "area: no polygon to search");
  MultiPolygon region;
  bg::difference(area.area, area.no_fly, region);
  Require(AreaM2(region) > 0.0, "area: nothing left to search outside the no-fly zones");
  return region;
}

Box TransitBounds(const SearchArea& area, const std::vector<Point>& launches) {
  Box box;
  bg::envelope(area.area, box);
  for (const Point& p : launches) bg::expand(box, p);
  if (!area.no_fly.empty()) {
    Box zones;
    bg::envelope(area.no_fly, zones);
    bg::expand(box, zones);
  }
  return Box{
      {box.min_corner().x() - kPlanBoundsMarginM, box.min_corner().y() - kPlanBoundsMarginM},
      {box.max_corner().x() + kPlanBoundsMarginM, box.max_corner().y() + kPlanBoundsMarginM}};
}

// Each drone's launch site: `site_drones` when given, otherwise the drones spread
// evenly over the sites in order.
std::vector<std::size_t> SitePerDrone(const FleetSpec& fleet) {
  const std::size_t n = fleet.receiver_ids.size(), k = fleet.launch_points.size();
  std::vector<std::size_t> sites;
  for (std::size_t site = 0; site < k; ++site) {
    const std::size_t count = fleet.site_drones.empty()
                                  ? (site + 1) * n / k - site * n / k
                                  : static_cast<std::size_t>(fleet.site_drones[site]);
    sites.insert(sites.end(), count, site);
  }
  return sites;
}

// A route along an OMPL coverage path: a turn wherever the heading changes sharply.
Route RouteAlong(const Path& path, const FleetSpec& fleet) {
  Route route;
  route.speed_mps = fleet.speed_mps;
  for (std::size_t i = 0; i < path.size(); ++i) {
    double turn_s = 0.0;
    if (i >= 2) {
      const double h0 =
          std::atan2(path[i - 1].y() - path[i - 2].y(), path[i - 1].x() - path[i - 2].x());
      const double h1 = std::atan2(path[i].y() - path[i - 1].y(), path[i].x() - path[i - 1].x());
      const double change = std::abs(std::remainder(h1 - h0, 2.0 * std::numbers::pi));
      if (change > kOmplTurnAngleRad) turn_s = fleet.turn_cost_s;
    }
    route.Extend(path[i], -1, turn_s);
  }
  return route;
}

// A lower bound on the makespan (see Plan::lower_bound_s), in three terms:
//  * work: area / (N * sweep * speed), the time to sweep the region if nothing else
//    were flown, the lane spacing taken as the width seen per metre flown;
//  * far area: for every distance r, the part A(r) of the region farther than r
//    from the nearest launch point can only be seen while a drone is farther than
//    r - w/2 (w: footprint width) and each drone needs 2 (r - w/2) / speed to get
//    that far and back, so T >= A(r) / (N * sweep * speed) + 2 (r - w/2) / speed;
//    r = the region's distance from the launches gives "work + the unavoidable
//    round trip", r = its farthest point gives the reach of the farthest point.
//  A(r) is measured on a raster of about 250,000 cells.
double LowerBoundS(const MultiPolygon& region, const std::vector<Point>& launches, double sweep_m,
                   double footprint_m, double speed_mps) {
  constexpr double kBoundCells = 2.5e5;
  const double area_m2 = AreaM2(region);
  const double rate_m2ps = static_cast<double>(launches.size()) * sweep_m * speed_mps;
  double bound_s = area_m2 / rate_m2ps;
  const double cell_m = std::max(std::sqrt(area_m2 / kBoundCells), 0.1);
  const std::vector<double> distances = CellDistancesM(region, launches, cell_m);
  // Cells sorted farthest first: the k + 1 farthest make up A(r) at r = distances[k].
  const double cell_area_m2 =
      area_m2 / static_cast<double>(std::max<std::size_t>(distances.size(), 1));
  for (std::size_t k = 0; k < distances.size(); ++k) {
    const double far_m2 = static_cast<double>(k + 1) * cell_area_m2;
    const double round_trip_s = 2.0 * std::max(0.0, distances[k] - footprint_m / 2.0) / speed_mps;
    bound_s = std::max(bound_s, far_m2 / rate_m2ps + round_trip_s);
  }
  return bound_s;
}

// The partition's transit estimate between a launch point and a point of the
// route: the straight distance when it enters no zone, otherwise the planned
// distance (OMPL, memoised) from the launch to the route vertex nearest the point
// plus the straight piece from there, exact at route vertices. A constant detour
// per drone, measured for one set of cuts, does not follow the cuts as they move:
// a drone charged a long detour for a share behind a zone then inflated every
// other share (a 20-drone plan had one drone sweep 4 times its part).
class TransitEstimate {
 public:
  TransitEstimate(const Route& route, const std::vector<Point>& launches,
                  const TransitPlanner& transit)
      : route_(route), launches_(launches), transit_(transit) {}

  double DistanceM(Point a, Point b) const {
    const double straight_m = bg::distance(a, b);
    if (transit_.NoFly().empty() || transit_.IsClear(a, b)) return straight_m;
    for (std::size_t i = 0; i < launches_.size(); ++i) {
      if (bg::distance(launches_[i], a) == 0.0) return ViaRouteM(i, b);
      if (bg::distance(launches_[i], b) == 0.0) return ViaRouteM(i, a);
    }
    return transit_.DistanceM(a, b);
  }

 private:
  double ViaRouteM(std::size_t launch, Point p) const {
    std::size_t nearest = 0;
    double nearest_m = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < route_.points.size(); ++j) {
      const double d = bg::distance(route_.points[j], p);
      if (d < nearest_m) {
        nearest_m = d;
        nearest = j;
      }
    }
    if (!std::isfinite(nearest_m) || !transit_.IsClear(route_.points[nearest], p)) {
      return transit_.DistanceM(launches_[launch], p);
    }
    std::vector<double>& memo = planned_m_[launch];
    if (memo.empty()) memo.assign(route_.points.size(), -1.0);
    if (memo[nearest] < 0.0)
      memo[nearest] = transit_.DistanceM(launches_[launch], route_.points[nearest]);
    return memo[nearest] + nearest_m;
  }

  const Route& route_;
  const std::vector<Point>& launches_;
  const TransitPlanner& transit_;
  mutable std::map<std::size_t, std::vector<double>> planned_m_;  // per launch, per route vertex
};

std::vector<Share> Partition(const Route& route, const std::vector<Point>& launches,
                             const TransitPlanner& transit) {
  const TransitEstimate estimate(route, launches, transit);
  return PartitionRoute(route, launches,
                        [&estimate](Point a, Point b) { return estimate.DistanceM(a, b); });
}

}  // namespace

Plan PlanSearch(const SearchArea& area, const FleetSpec& fleet, PlannerKind kind, unsigned seed) {
  const auto started = std::chrono::steady_clock::now();
  ValidateFleet(area, fleet);
  const MultiPolygon region = SearchRegion(area);
  const std::vector<std::size_t> sites = SitePerDrone(fleet);
  std::vector<Point> launches;
  for (const std::size_t site : sites) launches.push_back(fleet.launch_points[site]);
  const double footprint_m =
      FootprintWidthM(*fleet.camera, fleet.altitude_m, fleet.camera_pitch_deg);
  const SweepParams params{SweepWidthM(fleet), footprint_m, fleet.speed_mps, fleet.turn_cost_s};
  const TransitPlanner transit(area.no_fly, TransitBounds(area, launches), seed);

  // The sweep direction is chosen by the fleet's estimated makespan (the longest
  // share, transits to and from the launch points included), not by the route's
  // own length and turns alone.
  Route route;
  std::vector<Share> shares;
  double best_s = std::numeric_limits<double>::infinity();
  for (Route& candidate : SweepRoutes(region, params, launches.front(), transit)) {
    std::vector<Share> candidate_shares = Partition(candidate, launches, transit);
    double longest_s = 0.0;
    for (const Share& share : candidate_shares) longest_s = std::max(longest_s, share.time_s);
    if (longest_s < best_s) {
      best_s = longest_s;
      route = std::move(candidate);
      shares = std::move(candidate_shares);
    }
  }

  Plan plan;
  plan.sweep_width_m = params.sweep_width_m;
  std::vector<Path> paths;
  for (std::size_t i = 0; i < launches.size(); ++i) {
    DronePlan drone;
    drone.receiver_id = fleet.receiver_ids[i];
    drone.site = sites[i];
    drone.launch = launches[i];
    drone.region = ShareRegion(route, shares[i]);
    Flight flight;
    if (kind == PlannerKind::kOmpl && !drone.region.empty()) {
      const Route own = RouteAlong(
          CoverOmpl(drone.region, params.sweep_width_m, launches[i], transit, seed), fleet);
      flight =
          FlyShare(own, Share{0.0, own.TotalS(), 0.0}, launches[i], fleet.endurance_s, transit);
    } else {
      flight = FlyShare(route, shares[i], launches[i], fleet.endurance_s, transit);
    }
    Path path;
    for (const FlightPoint& p : flight.points) {
      path.push_back(p.point);
      const common::LatLon geodetic = area.frame.ToGeodetic({p.point.x(), p.point.y()});
      drone.waypoints.push_back({p.point, geodetic, p.is_return, p.starts_lane});
    }
    drone.sorties = flight.sorties;
    drone.length_m = flight.length_m;
    drone.ground_s = flight.sorties > 1 ? (flight.sorties - 1) * fleet.swap_s : 0.0;
    drone.time_s = flight.time_s + drone.ground_s;
    drone.sweep_s = flight.sweep_s;
    drone.turn_s = flight.turn_s;
    drone.transit_s = flight.transit_s;
    plan.makespan_s = std::max(plan.makespan_s, drone.time_s);
    plan.nofly_violation_m += InteriorLengthM(path, area.no_fly);
    paths.push_back(std::move(path));
    plan.drones.push_back(std::move(drone));
  }
  plan.coverage = CoverageFraction(region, paths, footprint_m / 2.0,
                                   CoverageCellM(AreaM2(region), params.sweep_width_m));
  plan.lower_bound_s =
      LowerBoundS(region, launches, params.sweep_width_m, footprint_m, fleet.speed_mps);
  plan.planning_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return plan;
}

}  // namespace fireswarm::planner
