// OMPL transit around no-fly zones. The only translation unit that includes OMPL.
//
// Validity is exact, not sampled: OMPL's motion validator is replaced by one that
// asks Boost.Geometry whether the whole segment enters a zone's interior, so every
// edge of the tree, of the solution and of the shortened path is proven clear.
// States additionally keep kClearanceM from the zones (except the query's own
// endpoints, which may lie on a zone's boundary, e.g. a lane ending at it).
#include "fireswarm/planner/transit.hpp"

#include <ompl/base/MotionValidator.h>
#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/base/ProblemDefinition.h>
#include <ompl/base/SpaceInformation.h>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/PathGeometric.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>

#include <algorithm>
#include <boost/geometry.hpp>
#include <boost/geometry/geometries/multi_linestring.hpp>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

namespace fireswarm::planner {
namespace bg = boost::geometry;
namespace ob = ompl::base;
namespace og = ompl::geometric;

namespace {

constexpr double kMinPieceM = 1e-6;              // shorter pieces are rounding at a grazed vertex
constexpr double kClearanceM = 1.0;              // wanted distance of OMPL states from a zone
constexpr double kMaxPlanSeconds = 1.0;          // cap of one OMPL query
constexpr double kTransitBoundsMarginM = 100.0;  // room around the bounds and the endpoints
constexpr double kSameStateM = 1e-9;
constexpr double kCornerOffsetM = 0.01;  // visibility-graph corners this far off a zone

using MultiPath = bg::model::multi_linestring<Path>;

Point ToPoint(const ob::State* state) {
  const auto* values = state->as<ob::RealVectorStateSpace::StateType>()->values;
  return {values[0], values[1]};
}

// A sampler whose generator is seeded by the planner, not by OMPL's global seed
// sequence, so a query gives the same path whatever ran before it.
class SeededSampler : public ob::RealVectorStateSampler {
 public:
  SeededSampler(const ob::StateSpace* space, unsigned seed) : ob::RealVectorStateSampler(space) {
    rng_.setLocalSeed(seed);
  }
};

class SeededRrtConnect : public og::RRTConnect {
 public:
  SeededRrtConnect(const ob::SpaceInformationPtr& si, unsigned seed) : og::RRTConnect(si) {
    rng_.setLocalSeed(seed);
  }
};

class ExactMotionValidator : public ob::MotionValidator {
 public:
  ExactMotionValidator(const ob::SpaceInformationPtr& si, const TransitPlanner& planner)
      : ob::MotionValidator(si), planner_(planner) {}

  bool checkMotion(const ob::State* s1, const ob::State* s2) const override {
    const bool clear = si_->isValid(s2) && planner_.IsClear(ToPoint(s1), ToPoint(s2));
    if (clear) {
      ++valid_;
    } else {
      ++invalid_;
    }
    return clear;
  }

  bool checkMotion(const ob::State* s1, const ob::State* s2,
                   std::pair<ob::State*, double>& last_valid) const override {
    if (checkMotion(s1, s2)) return true;
    // Conservative: report the start of the motion as the last valid state.
    if (last_valid.first != nullptr) si_->copyState(last_valid.first, s1);
    last_valid.second = 0.0;
    return false;
  }

 private:
  const TransitPlanner& planner_;
};

void SilenceOmplOnce() {
  static std::once_flag once;
  std::call_once(once, [] { ompl::msg::setLogLevel(ompl::msg::LOG_WARN); });
}

}  // namespace

double InteriorLengthM(const Path& path, const MultiPolygon& zones) {
  if (zones.empty() || path.size() < 2) return 0.0;
  if (!bg::intersects(path, zones)) return 0.0;
  double inside_m = 0.0;
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    const Path segment{path[i], path[i + 1]};
    if (!bg::intersects(segment, zones)) continue;
    MultiPath pieces;
    bg::intersection(segment, zones, pieces);
    for (const Path& piece : pieces) {
      for (std::size_t k = 0; k + 1 < piece.size(); ++k) {
        const double length_m = bg::distance(piece[k], piece[k + 1]);
        if (length_m < kMinPieceM) continue;
        const Point middle{(piece[k].x() + piece[k + 1].x()) / 2,
                           (piece[k].y() + piece[k + 1].y()) / 2};
        // Strictly inside: a piece along a boundary has its middle on the boundary.
        if (bg::within(middle, zones)) inside_m += length_m;
      }
    }
  }
  return inside_m;
}

struct TransitPlanner::Impl {
  MultiPolygon no_fly;
  Box bounds;
  unsigned seed = 1;
  // Each zone's envelope: a segment is checked only against the zones whose box
  // meets its own (Boost.Geometry sectionalizes every zone it is given, each call).
  std::vector<Box> zone_boxes;
  // The zones' corners and which pairs see each other (the segment between them
  // enters no zone's interior): the visibility graph the shortest path runs on.
  std::vector<Point> corners;
  std::vector<std::vector<std::size_t>> sees;
};

TransitPlanner::TransitPlanner(const MultiPolygon& no_fly, const Box& bounds, unsigned seed)
    : impl_(std::make_unique<Impl>(Impl{no_fly, bounds, seed, {}, {}, {}})) {
  SilenceOmplOnce();
  for (const Polygon& zone : no_fly) impl_->zone_boxes.push_back(bg::return_envelope<Box>(zone));
  // Each corner is moved kCornerOffsetM off the zone along its bisector, so paths
  // between corners run just outside the edges instead of on them (where rounding
  // puts them a hair inside) and still 0 m inside.
  const auto add_ring = [this, &no_fly](const auto& ring) {
    const std::size_t n = ring.size() > 0 ? ring.size() - 1 : 0;  // closed ring
    for (std::size_t i = 0; i < n; ++i) {
      const Point& v = ring[i];
      const Point& prev = ring[(i + n - 1) % n];
      const Point& next = ring[(i + 1) % n];
      const double la = bg::distance(v, prev), lb = bg::distance(v, next);
      if (la <= 0.0 || lb <= 0.0) continue;
      double bx = (v.x() - prev.x()) / la + (v.x() - next.x()) / lb;
      double by = (v.y() - prev.y()) / la + (v.y() - next.y()) / lb;
      double norm = std::hypot(bx, by);
      if (norm < 1e-12) {  // a straight corner: step along the edge's normal
        bx = -(next.y() - prev.y());
        by = next.x() - prev.x();
        norm = std::hypot(bx, by);
      }
      for (const double sign : {1.0, -1.0}) {
        const Point c{v.x() + sign * kCornerOffsetM * bx / norm,
                      v.y() + sign * kCornerOffsetM * by / norm};
        if (!bg::covered_by(c, no_fly)) {
          impl_->corners.push_back(c);
          break;
        }
      }
    }
  };
  for (const Polygon& zone : no_fly) {
    add_ring(zone.outer());
    for (const auto& ring : zone.inners()) add_ring(ring);
  }
  const std::size_t n = impl_->corners.size();
  impl_->sees.assign(n, {});
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      if (IsClear(impl_->corners[i], impl_->corners[j])) {
        impl_->sees[i].push_back(j);
        impl_->sees[j].push_back(i);
      }
    }
  }
}

TransitPlanner::~TransitPlanner() = default;

const MultiPolygon& TransitPlanner::NoFly() const {
  return impl_->no_fly;
}

bool TransitPlanner::IsInside(Point p) const {
  const MultiPolygon& zones = impl_->no_fly;
  if (zones.empty() || !bg::within(p, zones)) return false;
  // Inside: its distance to the zone's boundary (rings read as lines, since a
  // ring is areal to Boost.Geometry) is its depth.
  const auto boundary_m = [p](const auto& ring) {
    return static_cast<double>(bg::distance(p, Path(ring.begin(), ring.end())));
  };
  for (const Polygon& zone : zones) {
    if (!bg::within(p, zone)) continue;
    double depth_m = boundary_m(zone.outer());
    for (const auto& ring : zone.inners()) depth_m = std::min(depth_m, boundary_m(ring));
    return depth_m > kOnBoundaryToleranceM;
  }
  return false;
}

bool TransitPlanner::IsClear(Point from, Point to) const {
  // A zone whose box the segment's box misses holds no point of the segment:
  // leaving it out changes neither the pieces nor what lies inside the zones.
  const Path segment{from, to};
  const Box reach = bg::return_envelope<Box>(segment);
  MultiPolygon near;
  for (std::size_t k = 0; k < impl_->zone_boxes.size(); ++k) {
    if (!bg::disjoint(reach, impl_->zone_boxes[k])) near.push_back(impl_->no_fly[k]);
  }
  return near.empty() || InteriorLengthM(segment, near) == 0.0;
}

bool TransitPlanner::IsCircleClear(Point center, double radius_m) const {
  for (const Polygon& zone : impl_->no_fly) {
    // 0 when `center` is inside the zone; the farthest point is a vertex of its outer ring.
    const auto nearest_m = static_cast<double>(bg::distance(center, zone));
    double farthest_m = 0.0;
    for (const Point& vertex : zone.outer()) {
      farthest_m = std::max(farthest_m, static_cast<double>(bg::distance(center, vertex)));
    }
    if (nearest_m + kOnBoundaryToleranceM < radius_m &&
        radius_m < farthest_m - kOnBoundaryToleranceM) {
      return false;
    }
  }
  return true;
}

double TransitPlanner::DistanceM(Point from, Point to) const {
  if (IsClear(from, to)) return bg::distance(from, to);
  return static_cast<double>(bg::length(Plan(from, to)));
}

namespace {

// Greedy shortcut with exact checks: from each kept vertex jump to the farthest
// later vertex that is in plain sight.
Path Shortcut(const Path& raw, const TransitPlanner& planner) {
  Path out{raw.front()};
  std::size_t i = 0;
  while (i + 1 < raw.size()) {
    std::size_t j = raw.size() - 1;
    while (j > i + 1 && !planner.IsClear(raw[i], raw[j])) --j;
    out.push_back(raw[j]);
    i = j;
  }
  return out;
}

// The shortest path from `from` to `to` around polygonal zones runs straight
// between zone corners (the visibility graph); Dijkstra over the corners that see
// each other, `from` and `to`. Empty when `to` cannot be reached that way.
Path VisibilityPath(Point from, Point to, const std::vector<Point>& corners,
                    const std::vector<std::vector<std::size_t>>& sees,
                    const TransitPlanner& planner) {
  const std::size_t n = corners.size();
  const std::size_t source = n, target = n + 1;  // node ids of the endpoints
  const auto at = [&](std::size_t node) {
    return node == source ? from : node == target ? to : corners[node];
  };
  std::vector<bool> from_sees(n), sees_to(n);
  for (std::size_t i = 0; i < n; ++i) {
    from_sees[i] = planner.IsClear(from, corners[i]);
    sees_to[i] = planner.IsClear(corners[i], to);
  }
  constexpr double kInf = std::numeric_limits<double>::infinity();
  std::vector<double> dist(n + 2, kInf);
  std::vector<std::size_t> previous(n + 2, n + 2);
  std::vector<bool> done(n + 2, false);
  dist[source] = 0.0;
  for (;;) {
    std::size_t u = n + 2;
    for (std::size_t k = 0; k < n + 2; ++k) {
      if (!done[k] && std::isfinite(dist[k]) && (u == n + 2 || dist[k] < dist[u])) u = k;
    }
    if (u == n + 2 || u == target) break;
    done[u] = true;
    const auto relax = [&](std::size_t v) {
      const double d = dist[u] + bg::distance(at(u), at(v));
      if (d < dist[v]) {
        dist[v] = d;
        previous[v] = u;
      }
    };
    if (u == source) {
      for (std::size_t i = 0; i < n; ++i) {
        if (from_sees[i]) relax(i);
      }
      continue;
    }
    for (const std::size_t v : sees[u]) relax(v);
    if (sees_to[u]) relax(target);
  }
  if (!std::isfinite(dist[target])) return {};
  Path reversed;
  for (std::size_t node = target; node != n + 2; node = previous[node]) {
    reversed.push_back(at(node));
    if (node == source) break;
  }
  return Path(reversed.rbegin(), reversed.rend());
}

std::string Describe(Point p) {
  return "(" + std::to_string(p.x()) + ", " + std::to_string(p.y()) + ")";
}

}  // namespace

Path TransitPlanner::Plan(Point from, Point to) const {
  if (IsClear(from, to)) return Path{from, to};
  const MultiPolygon& zones = impl_->no_fly;
  if (IsInside(from) || IsInside(to)) {
    throw std::runtime_error("transit from " + Describe(from) + " to " + Describe(to) +
                             ": an endpoint is inside a no-fly zone");
  }
  // Polygonal zones: the exact shortest path. RRTConnect (below) only finds some
  // path, and on the scenario's power-line corridor it went around the far end,
  // kilometres longer; it stays as the fallback.
  Path shortest = VisibilityPath(from, to, impl_->corners, impl_->sees, *this);
  if (!shortest.empty()) return shortest;
  auto space = std::make_shared<ob::RealVectorStateSpace>(2);
  ob::RealVectorBounds bounds(2);
  bounds.setLow(
      0, std::min({impl_->bounds.min_corner().x(), from.x(), to.x()}) - kTransitBoundsMarginM);
  bounds.setLow(
      1, std::min({impl_->bounds.min_corner().y(), from.y(), to.y()}) - kTransitBoundsMarginM);
  bounds.setHigh(
      0, std::max({impl_->bounds.max_corner().x(), from.x(), to.x()}) + kTransitBoundsMarginM);
  bounds.setHigh(
      1, std::max({impl_->bounds.max_corner().y(), from.y(), to.y()}) + kTransitBoundsMarginM);
  space->setBounds(bounds);
  const unsigned seed = impl_->seed;
  space->setStateSamplerAllocator(
      [seed](const ob::StateSpace* s) { return std::make_shared<SeededSampler>(s, seed); });

  auto si = std::make_shared<ob::SpaceInformation>(space);
  const ob::StateSpace* raw_space = space.get();  // no shared_ptr: it would form a cycle
  si->setStateValidityChecker([&zones, from, to, raw_space](const ob::State* state) {
    if (!raw_space->satisfiesBounds(state)) return false;
    const Point p = ToPoint(state);
    if (bg::distance(p, from) < kSameStateM || bg::distance(p, to) < kSameStateM) return true;
    return bg::distance(p, zones) >= kClearanceM;
  });
  si->setMotionValidator(std::make_shared<ExactMotionValidator>(si, *this));
  si->setup();

  ob::ScopedState<ob::RealVectorStateSpace> start(space), goal(space);
  start[0] = from.x();
  start[1] = from.y();
  goal[0] = to.x();
  goal[1] = to.y();
  auto problem = std::make_shared<ob::ProblemDefinition>(si);
  problem->setStartAndGoalStates(start, goal);

  auto planner = std::make_shared<SeededRrtConnect>(si, seed);
  planner->setProblemDefinition(problem);
  planner->setup();
  const ob::PlannerStatus status =
      planner->solve(ob::timedPlannerTerminationCondition(kMaxPlanSeconds));
  if (status != ob::PlannerStatus::EXACT_SOLUTION) {
    throw std::runtime_error("transit from " + Describe(from) + " to " + Describe(to) +
                             ": no path around the no-fly zones found");
  }
  auto* solution = problem->getSolutionPath()->as<og::PathGeometric>();
  Path raw;
  for (const ob::State* state : solution->getStates()) raw.push_back(ToPoint(state));
  Path path = Shortcut(raw, *this);
  // Every segment was proven clear by the exact validator; keep the invariant visible.
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    if (!IsClear(path[i], path[i + 1])) {
      throw std::runtime_error("transit from " + Describe(from) + " to " + Describe(to) +
                               ": internal error, a segment enters a no-fly zone");
    }
  }
  return path;
}

}  // namespace fireswarm::planner
