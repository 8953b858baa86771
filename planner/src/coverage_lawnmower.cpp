// Boustrophedon lawnmower coverage: direction choice, cells, lanes, cell order.
#include <algorithm>
#include <boost/geometry.hpp>
#include <cmath>
#include <limits>
#include <numbers>

#include "coverage.hpp"
#include "decomposition.hpp"
#include "lanes.hpp"

namespace fireswarm::planner {
namespace bg = boost::geometry;

namespace {

constexpr std::size_t kMaxDirections = 8;
constexpr double kSameDirectionRad = std::numbers::pi / 180.0;
constexpr double kDefaultOverlap = 0.10;

struct DirectionCandidate {
  double direction_rad = 0.0;
  double length_m = 0.0;
};

template <typename Ring>
void AddEdgeDirections(const Ring& ring, std::vector<DirectionCandidate>& out) {
  for (std::size_t i = 0; i + 1 < ring.size(); ++i) {
    const double dx = ring[i + 1].x() - ring[i].x(), dy = ring[i + 1].y() - ring[i].y();
    const double length_m = std::hypot(dx, dy);
    if (length_m <= 0.0) continue;
    double angle = std::atan2(dy, dx);
    if (angle < 0.0) angle += std::numbers::pi;  // lanes are undirected: [0, pi)
    if (angle >= std::numbers::pi) angle -= std::numbers::pi;
    out.push_back({angle, length_m});
  }
}

// The region's (and its hull's) edge directions, longest first, without repeats.
std::vector<double> CandidateDirections(const MultiPolygon& region) {
  std::vector<DirectionCandidate> edges;
  for (const Polygon& polygon : region) {
    AddEdgeDirections(polygon.outer(), edges);
    for (const auto& ring : polygon.inners()) AddEdgeDirections(ring, edges);
  }
  Polygon hull;
  bg::convex_hull(region, hull);
  AddEdgeDirections(hull.outer(), edges);
  std::sort(edges.begin(), edges.end(),
            [](const DirectionCandidate& a, const DirectionCandidate& b) {
              return a.length_m > b.length_m;
            });
  std::vector<double> directions;
  for (const DirectionCandidate& edge : edges) {
    const bool seen = std::any_of(directions.begin(), directions.end(), [&](double d) {
      const double diff = std::abs(d - edge.direction_rad);
      return std::min(diff, std::numbers::pi - diff) < kSameDirectionRad;
    });
    if (!seen) directions.push_back(edge.direction_rad);
    if (directions.size() >= kMaxDirections) break;
  }
  if (directions.empty()) directions.push_back(0.0);
  return directions;
}

struct Sweep {
  std::vector<SweptCell> cells;
  std::vector<std::vector<Lane>> lanes;  // per cell, bottom to top in its frame
  double estimate_s = std::numeric_limits<double>::infinity();
};

// Lane ends lengthened past the cell's chord must not reach into a no-fly zone:
// there the lane keeps to its chord.
void KeepOutOfNoFly(const LaneFrame& frame, Lane& lane, const TransitPlanner& transit) {
  auto local = [&](double x) { return frame.ToLocal(Point{x, lane.y_m}); };
  if (lane.x_min_m < lane.chord_min_m &&
      !transit.IsClear(local(lane.chord_min_m), local(lane.x_min_m))) {
    lane.x_min_m = lane.chord_min_m;
  }
  if (lane.x_max_m > lane.chord_max_m &&
      !transit.IsClear(local(lane.chord_max_m), local(lane.x_max_m))) {
    lane.x_max_m = lane.chord_max_m;
  }
}

// A lane end clipped against the region (the area minus the zones) lies on a
// zone's edge, in rounding a hair inside it; the connection to the next lane along
// that edge would then run inside. Such an end is moved along the lane, away from
// the zone, in growing steps until it is outside (kMaxEndSnapM: far below what the
// footprint notices). An end still inside after that is left to the transit
// planner, which takes points within kOnBoundaryToleranceM as on the boundary.
void SnapEndsOutOfNoFly(const LaneFrame& frame, Lane& lane, const TransitPlanner& transit) {
  constexpr double kFirstStepM = 1e-9;
  constexpr double kMaxEndSnapM = 1e-3;
  auto snap = [&](double& x_m, double inward) {
    const auto inside = [&](double x) {
      const Point p = frame.ToLocal(Point{x, lane.y_m});
      return bg::within(p, transit.NoFly());
    };
    for (double step_m = kFirstStepM; step_m <= kMaxEndSnapM && inside(x_m); step_m *= 2.0) {
      x_m += inward * step_m;
    }
  };
  if (lane.x_max_m - lane.x_min_m <= 2.0 * kMaxEndSnapM) return;
  snap(lane.x_min_m, 1.0);
  snap(lane.x_max_m, -1.0);
}

// Estimated time of sweeping lanes: their length, a connection about one sweep
// long and a turn at each lane end.
double EstimateS(const std::vector<Lane>& lanes, const SweepParams& params) {
  double flight_m = 0.0;
  for (const Lane& lane : lanes) flight_m += lane.x_max_m - lane.x_min_m + params.sweep_width_m;
  return flight_m / params.speed_mps + static_cast<double>(lanes.size()) * params.turn_cost_s;
}

bool IsConvex(const Polygon& polygon) {
  Polygon hull;
  bg::convex_hull(polygon, hull);
  const auto area = static_cast<double>(bg::area(polygon));
  return static_cast<double>(bg::area(hull)) - area <= 1e-6 * area;
}

// The cell's own sweep direction: the decomposition's, or for a convex cell (any
// direction crosses it in one piece) whichever of its edge directions is faster.
void AddCell(Sweep& sweep, const SweptCell& decomposed, const SweepParams& params,
             const TransitPlanner& transit) {
  const Polygon local = decomposed.frame.ToLocal(decomposed.cell);
  std::vector<double> directions{decomposed.frame.direction_rad};
  if (IsConvex(local)) {
    for (const double d : CandidateDirections(MultiPolygon{local})) directions.push_back(d);
  }
  SweptCell best_cell;
  std::vector<Lane> best_lanes;
  double best_s = std::numeric_limits<double>::infinity();
  for (const double direction_rad : directions) {
    const LaneFrame frame{direction_rad};
    SweptCell cell{frame, frame.ToLane(local)};
    std::vector<Lane> lanes =
        CellLanes(cell.cell, params.sweep_width_m, params.footprint_width_m / 2.0);
    for (Lane& lane : lanes) {
      KeepOutOfNoFly(frame, lane, transit);
      SnapEndsOutOfNoFly(frame, lane, transit);
    }
    const double estimate_s = EstimateS(lanes, params);
    if (estimate_s < best_s) {
      best_s = estimate_s;
      best_cell = std::move(cell);
      best_lanes = std::move(lanes);
    }
  }
  sweep.cells.push_back(std::move(best_cell));
  sweep.lanes.push_back(std::move(best_lanes));
  sweep.estimate_s += best_s;
}

Sweep SweepAlong(const MultiPolygon& region, double direction_rad, const SweepParams& params,
                 const TransitPlanner& transit) {
  const LaneFrame frame{direction_rad};
  Sweep sweep;
  sweep.estimate_s = 0.0;
  for (Polygon& cell : DecomposeLaneFrame(frame.ToLane(region))) {
    AddCell(sweep, SweptCell{frame, std::move(cell)}, params, transit);
  }
  return sweep;
}

// A way through one cell: which lane first (bottom or top) and which end.
struct Variant {
  std::size_t cell = 0;
  bool top_first = false;
  bool start_west = false;
};

Point LaneStart(const LaneFrame& frame, const Lane& lane, bool eastward) {
  return frame.ToLocal(Point{eastward ? lane.x_min_m : lane.x_max_m, lane.y_m});
}

Point LaneEnd(const LaneFrame& frame, const Lane& lane, bool eastward) {
  return frame.ToLocal(Point{eastward ? lane.x_max_m : lane.x_min_m, lane.y_m});
}

// The lanes of a variant in flying order, each with its heading (eastward or not).
std::vector<std::pair<const Lane*, bool>> FlyingOrder(const Sweep& sweep, const Variant& v) {
  const std::vector<Lane>& lanes = sweep.lanes[v.cell];
  std::vector<std::pair<const Lane*, bool>> order;
  for (std::size_t k = 0; k < lanes.size(); ++k) {
    const Lane& lane = v.top_first ? lanes[lanes.size() - 1 - k] : lanes[k];
    order.emplace_back(&lane, v.start_west == (k % 2 == 0));
  }
  return order;
}

// Appends a transit (straight or around no-fly zones), the first leg carrying `turn_s`.
void AppendTransit(Route& route, Point to, double turn_s, const TransitPlanner& transit) {
  const Path path = transit.Plan(route.points.back(), to);
  for (std::size_t i = 1; i < path.size(); ++i) route.Extend(path[i], -1, i == 1 ? turn_s : 0.0);
}

void AppendCell(Route& route, const Sweep& sweep, const Variant& v, const SweepParams& params,
                const TransitPlanner& transit) {
  bool first = true;
  for (const auto& [lane, eastward] : FlyingOrder(sweep, v)) {
    const Point start = LaneStart(sweep.cells[v.cell].frame, *lane, eastward);
    if (route.points.empty()) {
      route.Extend(start, -1, 0.0);
    } else {
      // After a lane (or the previous cell's last lane) the drone turns.
      const bool after_lane = !route.segment_lane.empty() && route.segment_lane.back() >= 0;
      AppendTransit(route, start, after_lane || !first ? params.turn_cost_s : 0.0, transit);
    }
    first = false;
    route.lanes.push_back({v.cell, *lane});
    route.Extend(LaneEnd(sweep.cells[v.cell].frame, *lane, eastward),
                 static_cast<int>(route.lanes.size() - 1), 0.0);
  }
}

}  // namespace

namespace {

Route RouteOf(const Sweep& best, const SweepParams& params, Point start,
              const TransitPlanner& transit) {
  Route route;
  route.cells = best.cells;
  route.speed_mps = params.speed_mps;
  std::vector<bool> done(best.cells.size(), false);
  Point here = start;
  for (std::size_t n = 0; n < best.cells.size(); ++n) {
    Variant next;
    double next_m = std::numeric_limits<double>::infinity();
    for (std::size_t c = 0; c < best.cells.size(); ++c) {
      if (done[c] || best.lanes[c].empty()) continue;
      for (int k = 0; k < 4; ++k) {
        const Variant v{c, (k & 1) != 0, (k & 2) != 0};
        const auto order = FlyingOrder(best, v);
        const double d = bg::distance(
            here, LaneStart(best.cells[c].frame, *order.front().first, order.front().second));
        if (d < next_m) {
          next_m = d;
          next = v;
        }
      }
    }
    if (!std::isfinite(next_m)) break;
    done[next.cell] = true;
    AppendCell(route, best, next, params, transit);
    here = route.points.back();
  }
  return route;
}

}  // namespace

std::vector<Route> SweepRoutes(const MultiPolygon& region, const SweepParams& params, Point start,
                               const TransitPlanner& transit) {
  std::vector<Sweep> sweeps;
  for (const double direction_rad : CandidateDirections(region)) {
    sweeps.push_back(SweepAlong(region, direction_rad, params, transit));
  }
  std::stable_sort(sweeps.begin(), sweeps.end(),
                   [](const Sweep& a, const Sweep& b) { return a.estimate_s < b.estimate_s; });
  std::vector<Route> routes;
  for (const Sweep& sweep : sweeps) routes.push_back(RouteOf(sweep, params, start, transit));
  return routes;
}

Route SweepRoute(const MultiPolygon& region, const SweepParams& params, Point start,
                 const TransitPlanner& transit) {
  Sweep best;
  for (const double direction_rad : CandidateDirections(region)) {
    Sweep sweep = SweepAlong(region, direction_rad, params, transit);
    if (sweep.estimate_s < best.estimate_s) best = std::move(sweep);
  }
  return RouteOf(best, params, start, transit);
}

Path CoverLawnmower(const MultiPolygon& region, double sweep_width_m, Point start,
                    const TransitPlanner& transit) {
  const SweepParams params{sweep_width_m, sweep_width_m / (1.0 - kDefaultOverlap), 1.0, 0.0};
  const Route route = SweepRoute(region, params, start, transit);
  return Path(route.points.begin(), route.points.end());
}

}  // namespace fireswarm::planner
