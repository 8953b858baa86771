// PlanSearch: validation, the fleet's route, its partition, sorties and figures.
#include "fireswarm/planner/plan.hpp"

#include <algorithm>
#include <array>
#include <boost/geometry.hpp>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <numeric>
#include <set>
#include <stdexcept>
#include <string>

#include "coverage.hpp"
#include "coverage_raster.hpp"
#include "fireswarm/planner/footprint.hpp"
#include "fireswarm/planner/transit.hpp"
#include "fleet_assignment.hpp"
#include "lane_field.hpp"
#include "lanes.hpp"
#include "lower_bound.hpp"
#include "sortie_blocks.hpp"
#include "sortie_flight.hpp"

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

// Every sortie's climb over its site to altitude_m and its descent to land, s.
double VerticalS(const FleetSpec& fleet) {
  return fleet.altitude_m / fleet.climb_mps + fleet.altitude_m / fleet.descent_mps;
}

// What a sortie's endurance leaves at altitude, s.
double LevelFlightS(const FleetSpec& fleet) {
  return fleet.endurance_s - VerticalS(fleet);
}

// Refuses a lane spacing so fine for the area that the lanes would not fit in
// memory or time: estimated before any lane exists.
void CheckLaneCount(const SearchArea& area, const FleetSpec& fleet) {
  if (area.area.empty()) return;  // SearchRegion() names that
  Box box;
  bg::envelope(area.area, box);
  const double diagonal_m = std::hypot(box.max_corner().x() - box.min_corner().x(),
                                       box.max_corner().y() - box.min_corner().y());
  const double spacing_m = SweepWidthM(fleet);
  const double lanes = diagonal_m / spacing_m;
  if (lanes <= kMaxPlanLanes) return;
  throw std::invalid_argument(
      "side_overlap " + std::to_string(fleet.side_overlap) + " at altitude_m " +
      std::to_string(std::lround(fleet.altitude_m)) + " spaces lanes " + std::to_string(spacing_m) +
      " m apart: the area (" + std::to_string(std::lround(diagonal_m)) +
      " m across) would need about " + std::to_string(std::llround(lanes)) +
      " lanes, more than the limit of " + std::to_string(std::lround(kMaxPlanLanes)) +
      "; lower the overlap, fly higher, or split the area");
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
  const auto in_range = [](const char* field, double value, double min, bool min_open, double max) {
    const bool ok = (min_open ? value > min : value >= min) && value <= max;
    Require(ok, std::string(field) + " must be in " + (min_open ? "(" : "[") +
                    std::to_string(std::lround(min)) + ", " + std::to_string(std::lround(max)) +
                    "], got " + std::to_string(value));
  };
  in_range("speed_mps", fleet.speed_mps, 0.0, true, kMaxSpeedMps);
  // Not bounded above here: a long endurance only means fewer sorties (tests and
  // plan_bench use one flight each); the flags and scenario keys bound it.
  Require(fleet.endurance_s > 0.0 && std::isfinite(fleet.endurance_s),
          "endurance_s must be > 0, got " + std::to_string(fleet.endurance_s));
  in_range("swap_s", fleet.swap_s, 0.0, false, kMaxSwapS);
  in_range("climb_mps", fleet.climb_mps, 0.0, true, kMaxVerticalMps);
  in_range("descent_mps", fleet.descent_mps, 0.0, true, kMaxVerticalMps);
  in_range("turn_cost_s", fleet.turn_cost_s, 0.0, false, kMaxTurnCostS);
  in_range("altitude_m", fleet.altitude_m, 0.0, true, kMaxAltitudeM);
  SweepWidthM(fleet);  // throws naming camera, altitude_m, camera_pitch_deg or side_overlap
  Require(VerticalS(fleet) < fleet.endurance_s,
          "endurance_s " + std::to_string(std::lround(fleet.endurance_s)) +
              " s leaves no time at altitude: the climb to altitude_m and the descent take " +
              std::to_string(std::lround(VerticalS(fleet))) + " s");
  CheckLaneCount(area, fleet);
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

}  // namespace

namespace {

constexpr std::size_t kHullDirections = 3;
constexpr double kSameDirectionRad = 5.0 * std::numbers::pi / 180.0;
constexpr int kExtraSortieCounts = 2;  // sorties per drone tried beyond the least

// Sweep directions worth trying: along the convex hull's edges that leave it
// narrowest across (fewest lanes, longest ones), then east and north.
std::vector<double> SweepDirections(const MultiPolygon& region) {
  Polygon hull;
  bg::convex_hull(region, hull);
  std::vector<std::pair<double, double>> by_width;  // (width across, direction)
  const auto& ring = hull.outer();
  for (std::size_t i = 0; i + 1 < ring.size(); ++i) {
    const double dx = ring[i + 1].x() - ring[i].x(), dy = ring[i + 1].y() - ring[i].y();
    const double length = std::hypot(dx, dy);
    if (length <= 0.0) continue;
    double width = 0.0;
    for (const Point& p : ring) {
      width = std::max(width,
                       std::abs((p.x() - ring[i].x()) * dy - (p.y() - ring[i].y()) * dx) / length);
    }
    by_width.emplace_back(width, std::atan2(dy, dx));
  }
  std::sort(by_width.begin(), by_width.end());
  std::vector<double> directions;
  auto add = [&](double direction) {
    direction = std::fmod(direction + 2.0 * std::numbers::pi, std::numbers::pi);
    for (const double d : directions) {
      const double diff = std::abs(d - direction);
      if (std::min(diff, std::numbers::pi - diff) < kSameDirectionRad) return;
    }
    directions.push_back(direction);
  };
  for (const auto& [width, direction] : by_width) {
    if (directions.size() >= kHullDirections) break;
    add(direction);
  }
  add(0.0);
  add(std::numbers::pi / 2.0);
  return directions;
}

// Straight distance, or around the no-fly zones when the segment enters one. The
// detour is planned once per pair of kDetourCellM cells the endpoints fall in
// and kept as a factor on the straight distance: the cutting asks for thousands of
// nearby pairs, and one OMPL query each would take seconds.
class TransitDistance {
 public:
  explicit TransitDistance(const TransitPlanner& transit) : transit_(transit) {}
  double operator()(Point a, Point b) const {
    const double straight_m = bg::distance(a, b);
    if (transit_.NoFly().empty() || straight_m <= 0.0 || IsClear(a, b)) return straight_m;
    const auto cell = [](double v) { return static_cast<long long>(std::floor(v / kDetourCellM)); };
    const auto key = std::make_tuple(cell(a.x()), cell(a.y()), cell(b.x()), cell(b.y()));
    auto it = detour_.find(key);
    if (it == detour_.end()) {
      double factor = 1.0;
      try {
        factor = transit_.DistanceM(a, b) / straight_m;
      } catch (const std::runtime_error&) {
        // A pass's end inside a zone (the band beside it needs the pass, the flight
        // leaves the zone out): the straight distance stands in for the estimate.
      }
      it = detour_.emplace(key, factor).first;
    }
    return straight_m * it->second;
  }

 private:
  // The cutting asks for the same pairs (a site and a block's corners) over and
  // over: each segment is checked against the zones once.
  bool IsClear(Point a, Point b) const {
    const std::array<double, 4> key = {a.x(), a.y(), b.x(), b.y()};
    auto it = clear_.find(key);
    if (it == clear_.end()) it = clear_.emplace(key, transit_.IsClear(a, b)).first;
    return it->second;
  }

  static constexpr double kDetourCellM = 250.0;
  const TransitPlanner& transit_;
  mutable std::map<std::array<double, 4>, bool> clear_;
  mutable std::map<std::tuple<long long, long long, long long, long long>, double> detour_;
};

// Stripe heights worth trying for blocks of `work_s`: square blocks, half as
// high, and two rows (long thin blocks: out along one lane, back along the next).
std::vector<std::size_t> StripeRows(double work_s, double speed_mps, double spacing_m,
                                    std::size_t rows) {
  const double square = std::sqrt(std::max(work_s, 0.0) * speed_mps / spacing_m);
  std::vector<std::size_t> out;
  for (const double k : {square, square / 2.0, 2.0}) {
    auto even = static_cast<std::size_t>(2.0 * std::max(1.0, std::round(k / 2.0)));
    even = std::min(even, std::max<std::size_t>(rows + rows % 2, 2));
    if (std::find(out.begin(), out.end(), even) == out.end()) out.push_back(even);
  }
  return out;
}

struct Candidate {
  std::vector<LaneField> fields;
  std::vector<SortieUnit> units;
  Assignment assignment;
};

double LaneSeconds(const LaneField& field, double speed_mps) {
  double lane_s = 0.0;
  for (const LaneRow& row : field.rows) {
    for (const Span& span : row.spans) lane_s += (span.hi_m - span.lo_m) / speed_mps;
  }
  return lane_s;
}

std::string Where(const SearchArea& area, Point p) {
  const common::LatLon geodetic = area.frame.ToGeodetic({p.x(), p.y()});
  char text[96];
  std::snprintf(text, sizeof text, "(%.6f, %.6f)", geodetic.lat_deg, geodetic.lon_deg);
  return text;
}

// Refuses an area with a point no sortie can reach and return from.
void CheckReach(const SearchArea& area, const MultiPolygon& region, const FleetSpec& fleet,
                double footprint_m) {
  const FarthestPoint far = FarthestFromSites(region, fleet.launch_points);
  const double round_trip_s =
      2.0 * std::max(0.0, far.distance_m - footprint_m / 2.0) / fleet.speed_mps;
  if (round_trip_s < LevelFlightS(fleet)) return;
  throw std::runtime_error(
      "endurance_s " + std::to_string(std::lround(fleet.endurance_s)) +
      " s is too short: the area at " + Where(area, far.point) + " (lat, lon) lies " +
      std::to_string(std::lround(far.distance_m)) +
      " m from the nearest launch site; seeing it and flying back takes more than " +
      std::to_string(std::lround(round_trip_s)) + " s (a range of " +
      std::to_string(std::lround(2.0 * far.distance_m)) + " m out and back, after " +
      std::to_string(std::lround(VerticalS(fleet))) +
      " s of climb and descent): add a launch site nearer to it or a longer endurance");
}

MultiPolygon UnitRegion(const SortieUnit& unit, const LaneField& field) {
  const MultiPolygon& region_lane = field.region_lane;
  MultiPolygon out;
  for (const Block& block : unit.blocks) {
    const double half = field.spacing_m / 2.0;
    const Box box{{block.x_lo_m, field.rows[block.first_row].y_m - half},
                  {block.x_hi_m, field.rows[block.end_row - 1].y_m + half}};
    MultiPolygon piece;
    bg::intersection(region_lane, box, piece);
    for (const Polygon& polygon : piece) out.push_back(field.frame.ToLocal(polygon));
  }
  return out;
}

// The pieces of a sortie's region united where they touch (blocks side by side
// in a stripe, or across a stripe's edge). Boost.Geometry's union can drop a
// piece of a shape that touches itself at a point: then the pieces stay as given.
MultiPolygon Merged(const MultiPolygon& pieces) {
  constexpr double kAreaTolerance = 1e-6;
  MultiPolygon merged;
  for (const Polygon& piece : pieces) {
    MultiPolygon next;
    bg::union_(merged, piece, next);
    merged = std::move(next);
  }
  if (AreaM2(merged) < AreaM2(pieces) * (1.0 - kAreaTolerance)) return pieces;
  return merged;
}

}  // namespace

Plan PlanSearch(const SearchArea& area, const FleetSpec& fleet, PlannerKind kind, unsigned seed) {
  const auto started = std::chrono::steady_clock::now();
  ValidateFleet(area, fleet);
  const MultiPolygon region = SearchRegion(area);
  const std::vector<Point>& sites = fleet.launch_points;
  const std::size_t drones = fleet.receiver_ids.size();
  const double footprint_m =
      FootprintWidthM(*fleet.camera, fleet.altitude_m, fleet.camera_pitch_deg);
  const double sweep_m = SweepWidthM(fleet);
  CheckReach(area, region, fleet, footprint_m);
  const TransitPlanner transit(area.no_fly, TransitBounds(area, sites), seed);
  const TransitDistance distance(transit);
  const TransitFn distance_fn = [&distance](Point a, Point b) { return distance(a, b); };
  // Sorties are cut to the level flight their endurance leaves after the climb and
  // the descent; each costs those on top, like the swap between two.
  const double vertical_s = VerticalS(fleet);
  const SortieSpec spec{fleet.speed_mps, fleet.turn_cost_s, LevelFlightS(fleet)};

  // Lane fields, one per sweep direction over the whole region (a family of
  // fields, so that regions of their own, e.g. per site, can join later), each
  // tried with several sorties per drone and stripe heights, both cuts. The
  // assignment's makespan decides.
  std::vector<std::vector<LaneField>> families;
  for (const double direction : SweepDirections(region)) {
    families.push_back({BuildLaneField(region, direction, sweep_m, 0.0)});
  }
  std::optional<Candidate> best;
  for (std::vector<LaneField>& fields : families) {
    std::vector<double> field_s;
    for (const LaneField& field : fields) field_s.push_back(LaneSeconds(field, fleet.speed_mps));
    const double lane_s = std::accumulate(field_s.begin(), field_s.end(), 0.0);
    if (lane_s <= 0.0) continue;
    const double per_drone_s = lane_s / static_cast<double>(drones);
    const int least = std::max(1, static_cast<int>(std::ceil(per_drone_s / spec.endurance_s)));
    for (int sorties = least; sorties <= least + kExtraSortieCounts; ++sorties) {
      const double target_s = per_drone_s / sorties;
      const double wanted = static_cast<double>(drones) * sorties;
      for (const std::size_t rows : StripeRows(target_s, fleet.speed_mps, fields.front().spacing_m,
                                               fields.front().rows.size())) {
        for (const bool equal_time : {true, false}) {
          std::vector<SortieUnit> units;
          bool cut = true;
          for (std::size_t f = 0; f < fields.size() && cut; ++f) {
            const auto share = static_cast<std::size_t>(std::ceil(wanted * field_s[f] / lane_s));
            std::vector<SortieUnit> part =
                equal_time ? CutSortieUnits(fields[f], rows, std::max<std::size_t>(share, 1), sites,
                                            spec, distance_fn, 2.0 * sweep_m)
                           : CutSortieUnitsByWork(fields[f], rows, target_s, sites, spec,
                                                  distance_fn, 2.0 * sweep_m);
            cut = !part.empty() || field_s[f] <= 0.0;
            for (SortieUnit& unit : part) {
              unit.field = f;
              units.push_back(std::move(unit));
            }
          }
          if (!cut || units.empty()) continue;
          std::vector<std::vector<double>> unit_site_s(units.size());
          for (std::size_t u = 0; u < units.size(); ++u) {
            for (const Point& site : sites) {
              unit_site_s[u].push_back(SortieTimeS(units[u], site, spec, distance_fn));
            }
          }
          std::optional<Assignment> assignment = AssignUnits(
              unit_site_s, drones, fleet.site_drones, spec.endurance_s, fleet.swap_s + vertical_s);
          if (!assignment) continue;
          if (!best || assignment->makespan_s < best->assignment.makespan_s) {
            best = Candidate{fields, std::move(units), std::move(*assignment)};
          }
        }
      }
    }
  }
  if (!best) {
    throw std::runtime_error("endurance_s " + std::to_string(std::lround(fleet.endurance_s)) +
                             " s: no split of the area into sorties fits it from the launch "
                             "sites given (site_drones may leave a needed site without drones)");
  }

  Plan plan;
  plan.sweep_width_m = sweep_m;
  // Receiver IDs in the order of the units' walk: neighbouring units go to drones
  // next to each other in the fleet (the runner layers transit altitudes by fleet
  // order, so drones working side by side differ in altitude where they turn).
  std::vector<std::size_t> slots(drones);
  std::iota(slots.begin(), slots.end(), std::size_t{0});
  const auto first_unit = [&](std::size_t slot) {
    const auto& units = best->assignment.drone_units[slot];
    return units.empty() ? best->units.size() : *std::min_element(units.begin(), units.end());
  };
  std::stable_sort(slots.begin(), slots.end(),
                   [&](std::size_t a, std::size_t b) { return first_unit(a) < first_unit(b); });
  std::vector<Path> paths;
  for (std::size_t d = 0; d < drones; ++d) {
    const std::size_t slot = slots[d];
    DronePlan drone;
    drone.receiver_id = fleet.receiver_ids[d];
    drone.site = best->assignment.drone_site[slot];
    drone.launch = sites[drone.site];
    std::vector<SortieUnit> units;
    for (const std::size_t u : best->assignment.drone_units[slot]) {
      SortieUnit unit = best->units[u];
      OrientUnit(best->fields[unit.field], unit, drone.launch, spec);
      MultiPolygon unit_region = Merged(UnitRegion(unit, best->fields[unit.field]));
      drone.region.insert(drone.region.end(), unit_region.begin(), unit_region.end());
      drone.sortie_regions.push_back(std::move(unit_region));
      units.push_back(std::move(unit));
    }
    Flight flight;
    if (kind == PlannerKind::kOmpl) {
      std::vector<Path> covers;
      for (const SortieUnit& unit : units) {
        covers.push_back(CoverOmpl(UnitRegion(unit, best->fields[unit.field]), sweep_m,
                                   drone.launch, transit, seed));
      }
      flight = FlyPaths(covers, drone.launch, fleet.speed_mps, fleet.turn_cost_s, kOmplTurnAngleRad,
                        transit);
    } else {
      flight = FlySorties(units, drone.launch, fleet.speed_mps, fleet.turn_cost_s, transit);
    }
    Path path;
    for (const FlightPoint& p : flight.points) {
      path.push_back(p.point);
      const common::LatLon geodetic = area.frame.ToGeodetic({p.point.x(), p.point.y()});
      drone.waypoints.push_back({p.point, geodetic, p.is_return, p.starts_lane});
    }
    drone.sorties = std::max(flight.sorties, 1);
    drone.length_m = flight.length_m;
    drone.sweep_s = flight.sweep_s;
    drone.turn_s = flight.turn_s;
    drone.transit_s = flight.transit_s;
    drone.vertical_s = drone.sorties * vertical_s;
    drone.longest_sortie_s = flight.longest_sortie_s + vertical_s;
    drone.ground_s = flight.sorties > 1 ? (flight.sorties - 1) * fleet.swap_s : 0.0;
    drone.time_s = flight.time_s + drone.vertical_s + drone.ground_s;
    plan.makespan_s = std::max(plan.makespan_s, drone.time_s);
    plan.nofly_violation_m += InteriorLengthM(path, area.no_fly);
    paths.push_back(std::move(path));
    plan.drones.push_back(std::move(drone));
  }
  plan.coverage =
      CoverageFraction(region, paths, footprint_m / 2.0, CoverageCellM(AreaM2(region), sweep_m));
  const LowerBound bound = MakespanLowerBound(
      region, sites,
      {drones, sweep_m, footprint_m, fleet.speed_mps, spec.endurance_s, fleet.swap_s, vertical_s});
  plan.lower_bound_s = bound.seconds;
  plan.lower_bound_basis = bound.basis;
  plan.planning_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return plan;
}

}  // namespace fireswarm::planner
