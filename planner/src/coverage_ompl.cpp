// The OMPL-based coverage variant: viewpoints on a grid one sweep width apart,
// a short tour through them (nearest neighbour, then 2-opt on neighbour lists),
// and legs joined by the TransitPlanner, which plans around no-fly zones with OMPL.
// Longer than the lawnmower on open ground, but needs no cell decomposition.
#include <algorithm>
#include <boost/geometry/algorithms/area.hpp>
#include <boost/geometry/algorithms/centroid.hpp>
#include <boost/geometry/algorithms/convert.hpp>
#include <boost/geometry/algorithms/convex_hull.hpp>
#include <boost/geometry/algorithms/distance.hpp>
#include <boost/geometry/algorithms/envelope.hpp>
#include <boost/geometry/algorithms/intersection.hpp>
#include <boost/geometry/algorithms/intersects.hpp>
#include <boost/geometry/algorithms/within.hpp>
#include <boost/geometry/strategies/agnostic/hull_graham_andrew.hpp>
#include <boost/geometry/strategies/cartesian/centroid_bashein_detmer.hpp>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "coverage.hpp"
#include "lanes.hpp"

namespace fireswarm::planner {
namespace {

namespace bg = boost::geometry;

// A boundary cell's piece of region smaller than this fraction of a cell gets no
// viewpoint of its own: the neighbouring footprints (wider than a cell) reach it.
constexpr double kMinPieceFractionOfCell = 0.05;
// Chord-end viewpoints sit this fraction of a cell inside the region's boundary.
constexpr double kChordEndInsetFraction = 0.01;
// Nearest-neighbour tours are tried from this many chord ends nearest the start.
constexpr std::size_t kStartCandidates = 6;
// A cell centre this close (fraction of a cell) to a chord end adds nothing.
constexpr double kMinCentreGapFraction = 0.25;
// A leg into a no-fly zone is charged this many cells extra (its detour).
constexpr double kDetourCells = 4.0;
// See Distance().
constexpr double kRowChangeWeight = 1.5;
// Refuse grids this large: the sweep width is then surely in the wrong unit.
constexpr double kMaxGridCells = 4e6;
// Candidates per viewpoint for 2-opt moves, and a cap on improvement passes.
constexpr std::size_t kNeighbours = 8;
constexpr int kMaxTwoOptPasses = 50;

struct Grid {
  Point origin;  // lower-left corner of cell (0, 0)
  double cell_m = 0.0;
  long columns = 0;
  long rows = 0;
  std::vector<std::vector<std::size_t>> buckets;  // viewpoint ids per cell

  long Column(double x) const {
    return std::clamp(static_cast<long>(std::floor((x - origin.x()) / cell_m)), 0L, columns - 1);
  }
  long Row(double y) const {
    return std::clamp(static_cast<long>(std::floor((y - origin.y()) / cell_m)), 0L, rows - 1);
  }
  std::vector<std::size_t>& Bucket(long column, long row) {
    return buckets[static_cast<std::size_t>(row * columns + column)];
  }
  const std::vector<std::size_t>& Bucket(long column, long row) const {
    return buckets[static_cast<std::size_t>(row * columns + column)];
  }
};

// Row viewpoints: along each grid row's line, both ends of every chord through
// the region (on its boundary, so the footprint reaches the edge) and the cell
// centres in between. Then, for cells the rows miss (their centre outside the
// region, no chord end in them), one point inside each sizeable piece of region.
struct Viewpoints {
  std::vector<Point> points;
  std::vector<std::size_t> row_ends;  // ids of the chord ends: where good tours begin
};

Viewpoints PlaceViewpoints(const MultiPolygon& region, Grid& grid) {
  Viewpoints result;
  std::vector<Point>& points = result.points;
  const auto add = [&](Point p) {
    grid.Bucket(grid.Column(p.x()), grid.Row(p.y())).push_back(points.size());
    points.push_back(p);
  };
  // Chord ends sit a hair inside the region, never on a no-fly zone's boundary.
  const double inset_m = kChordEndInsetFraction * grid.cell_m;
  for (long row = 0; row < grid.rows; ++row) {
    const double y = grid.origin.y() + (static_cast<double>(row) + 0.5) * grid.cell_m;
    for (const Polygon& polygon : region) {
      for (const auto& [x_begin, x_end] : LineIntervals(polygon, y)) {
        if (x_end - x_begin <= 2.0 * inset_m) {
          result.row_ends.push_back(points.size());
          add(Point(0.5 * (x_begin + x_end), y));
          continue;
        }
        result.row_ends.push_back(points.size());
        add(Point(x_begin + inset_m, y));
        for (long column = grid.Column(x_begin); column <= grid.Column(x_end); ++column) {
          const double x = grid.origin.x() + (static_cast<double>(column) + 0.5) * grid.cell_m;
          const double margin = kMinCentreGapFraction * grid.cell_m;
          if (x > x_begin + margin && x < x_end - margin) add(Point(x, y));
        }
        result.row_ends.push_back(points.size());
        add(Point(x_end - inset_m, y));
      }
    }
  }
  const double cell_area_m2 = grid.cell_m * grid.cell_m;
  for (long row = 0; row < grid.rows; ++row) {
    for (long column = 0; column < grid.columns; ++column) {
      if (!grid.Bucket(column, row).empty()) continue;
      const double x0 = grid.origin.x() + static_cast<double>(column) * grid.cell_m;
      const double y0 = grid.origin.y() + static_cast<double>(row) * grid.cell_m;
      Polygon cell;
      bg::convert(Box(Point(x0, y0), Point(x0 + grid.cell_m, y0 + grid.cell_m)), cell);
      if (!bg::intersects(cell, region)) continue;
      MultiPolygon pieces;
      bg::intersection(cell, region, pieces);
      for (const Polygon& piece : pieces) {
        if (bg::area(piece) < kMinPieceFractionOfCell * cell_area_m2) continue;
        Point centroid;
        bg::centroid(piece, centroid);
        if (bg::within(centroid, piece)) {
          add(centroid);
          continue;
        }
        // Otherwise the middle of the longest chord through the centroid's height.
        double longest_m = 0.0;
        for (const auto& [x_begin, x_end] : LineIntervals(piece, centroid.y())) {
          if (x_end - x_begin > longest_m) {
            longest_m = x_end - x_begin;
            centroid = Point(0.5 * (x_begin + x_end), centroid.y());
          }
        }
        if (longest_m > 0.0) add(centroid);
      }
    }
  }
  return result;
}

// Tour distance in the row frame: a step across rows costs kRowChangeWeight times
// its length, so the tour prefers running along rows (as a lawnmower does) over
// zigzags of the same length with more turns. Never below the true distance, so
// the ring search's bound stays valid.
double Distance(const Point& a, const Point& b) {
  return std::hypot(a.x() - b.x(), kRowChangeWeight * (a.y() - b.y()));
}

// The cost of a tour leg between two row-frame points: Distance, plus a detour
// allowance when the straight leg would enter a no-fly zone (so tours cross a
// zone only when going around is worth it).
struct LegCost {
  const LaneFrame& frame;
  const TransitPlanner& transit;
  double detour_m;
  bool Clear(const Point& a, const Point& b) const {
    return transit.IsClear(frame.ToLocal(a), frame.ToLocal(b));
  }
  double operator()(const Point& a, const Point& b) const {
    return Distance(a, b) + (Clear(a, b) ? 0.0 : detour_m);
  }
};

struct ViewpointCandidate {
  double distance_m;
  long column;
  long row;
  std::size_t slot;
  bool operator<(const ViewpointCandidate& o) const { return distance_m < o.distance_m; }
};

// Every viewpoint in the grid rings around `here` out to where none can be nearer
// than `reach_m` beyond the nearest one found.
std::vector<ViewpointCandidate> RingCandidates(const std::vector<Point>& points, const Grid& grid,
                                               Point here, double reach_m) {
  const long column = grid.Column(here.x());
  const long row = grid.Row(here.y());
  const long max_radius = std::max(grid.columns, grid.rows);
  std::vector<ViewpointCandidate> found;
  double nearest_m = std::numeric_limits<double>::infinity();
  for (long radius = 0; radius <= max_radius; ++radius) {
    // Every point in ring `radius` is at least (radius - 1) cells away.
    if (static_cast<double>(radius - 1) * grid.cell_m > nearest_m + reach_m) break;
    for (long r = row - radius; r <= row + radius; ++r) {
      if (r < 0 || r >= grid.rows) continue;
      const bool edge_row = (r == row - radius || r == row + radius);
      for (long c = column - radius; c <= column + radius; c += edge_row ? 1 : 2 * radius) {
        if (c >= 0 && c < grid.columns) {
          const auto& bucket = grid.Bucket(c, r);
          for (std::size_t slot = 0; slot < bucket.size(); ++slot) {
            const double d = Distance(here, points[bucket[slot]]);
            nearest_m = std::min(nearest_m, d);
            found.push_back({d, c, r, slot});
          }
        }
        if (radius == 0) break;
      }
    }
  }
  return found;
}

// Greedy tour from viewpoint `first`: always the cheapest unvisited viewpoint
// (LegCost), found by searching grid rings outwards (buckets lose their visited
// ids as it goes). The nearest one is taken when its leg is clear; otherwise the
// ring search widens by the detour allowance and the cheapest leg wins.
std::vector<std::size_t> NearestNeighbourTour(const std::vector<Point>& points, std::size_t first,
                                              Grid grid, const LegCost& cost) {
  std::vector<std::size_t> tour{first};
  tour.reserve(points.size());
  auto& first_bucket = grid.Bucket(grid.Column(points[first].x()), grid.Row(points[first].y()));
  first_bucket.erase(std::find(first_bucket.begin(), first_bucket.end(), first));
  Point here = points[first];
  while (tour.size() < points.size()) {
    std::vector<ViewpointCandidate> candidates = RingCandidates(points, grid, here, 0.0);
    ViewpointCandidate best = *std::min_element(candidates.begin(), candidates.end());
    const auto& nearest_bucket = grid.Bucket(best.column, best.row);
    if (!cost.Clear(here, points[nearest_bucket[best.slot]])) {
      candidates = RingCandidates(points, grid, here, cost.detour_m);
      std::sort(candidates.begin(), candidates.end());
      double best_cost = std::numeric_limits<double>::infinity();
      for (const ViewpointCandidate& c : candidates) {
        if (c.distance_m >= best_cost) break;
        const double leg = cost(here, points[grid.Bucket(c.column, c.row)[c.slot]]);
        if (leg < best_cost) {
          best_cost = leg;
          best = c;
        }
      }
    }
    auto& bucket = grid.Bucket(best.column, best.row);
    tour.push_back(bucket[best.slot]);
    here = points[bucket[best.slot]];
    bucket[best.slot] = bucket.back();
    bucket.pop_back();
  }
  return tour;
}

double TourLength(const std::vector<Point>& points, Point start,
                  const std::vector<std::size_t>& tour) {
  // Plain distances: the candidates differ in where they begin, not in detours.
  double total = Distance(start, points[tour.front()]);
  for (std::size_t i = 1; i < tour.size(); ++i)
    total += Distance(points[tour[i - 1]], points[tour[i]]);
  return total;
}

// Greedy tours started at the chord ends nearest `start` (a tour started in the
// middle of a row strands the row's other half); the shortest one wins.
std::vector<std::size_t> BestGreedyTour(const Viewpoints& viewpoints, Point start, const Grid& grid,
                                        const LegCost& cost) {
  const std::vector<Point>& points = viewpoints.points;
  std::vector<std::pair<double, std::size_t>> candidates;
  for (std::size_t id : viewpoints.row_ends)
    candidates.emplace_back(Distance(start, points[id]), id);
  if (candidates.empty()) candidates.emplace_back(0.0, 0);
  const std::size_t keep = std::min(kStartCandidates, candidates.size());
  std::partial_sort(candidates.begin(), candidates.begin() + static_cast<std::ptrdiff_t>(keep),
                    candidates.end());
  std::vector<std::size_t> best;
  double best_m = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < keep; ++k) {
    std::vector<std::size_t> tour = NearestNeighbourTour(points, candidates[k].second, grid, cost);
    const double length_m = TourLength(points, start, tour);
    if (length_m < best_m) {
      best_m = length_m;
      best = std::move(tour);
    }
  }
  return best;
}

// The kNeighbours nearest viewpoints of each viewpoint (from the 5 x 5 cells around it).
std::vector<std::vector<std::size_t>> NeighbourLists(const std::vector<Point>& points,
                                                     const Grid& grid) {
  std::vector<std::vector<std::size_t>> lists(points.size());
  for (std::size_t id = 0; id < points.size(); ++id) {
    const long column = grid.Column(points[id].x());
    const long row = grid.Row(points[id].y());
    std::vector<std::pair<double, std::size_t>> near;
    for (long r = std::max(0L, row - 2); r <= std::min(grid.rows - 1, row + 2); ++r) {
      for (long c = std::max(0L, column - 2); c <= std::min(grid.columns - 1, column + 2); ++c) {
        for (std::size_t other : grid.Bucket(c, r)) {
          if (other != id) near.emplace_back(Distance(points[id], points[other]), other);
        }
      }
    }
    const std::size_t keep = std::min(kNeighbours, near.size());
    std::partial_sort(near.begin(), near.begin() + static_cast<std::ptrdiff_t>(keep), near.end());
    for (std::size_t k = 0; k < keep; ++k) lists[id].push_back(near[k].second);
  }
  return lists;
}

// 2-opt on an open path whose first node (the start) stays put: reversing
// tour[lo + 1 .. hi] swaps edges (lo, lo+1), (hi, hi+1) for (lo, hi), (lo+1, hi+1).
void TwoOpt(std::vector<std::size_t>& tour, const std::vector<Point>& nodes,
            const std::vector<std::vector<std::size_t>>& neighbours, const LegCost& cost) {
  const std::size_t n = tour.size();
  std::vector<std::size_t> position(nodes.size());
  const auto reindex = [&](std::size_t from, std::size_t to) {
    for (std::size_t i = from; i <= to; ++i) position[tour[i]] = i;
  };
  reindex(0, n - 1);
  const auto d = [&](std::size_t i, std::size_t j) {
    return Distance(nodes[tour[i]], nodes[tour[j]]);
  };
  const auto c = [&](std::size_t i, std::size_t j) { return cost(nodes[tour[i]], nodes[tour[j]]); };
  constexpr double kMinGainM = 1e-6;
  for (int pass = 0; pass < kMaxTwoOptPasses; ++pass) {
    bool improved = false;
    for (std::size_t i = 0; i + 1 < n; ++i) {
      for (std::size_t other : neighbours[tour[i]]) {
        const std::size_t j = position[other];
        if (j == 0 || j == i || j == i + 1 || j + 1 == i) continue;
        const std::size_t lo = std::min(i, j);
        const std::size_t hi = std::max(i, j);
        double delta = d(lo, hi) - d(lo, lo + 1);
        if (hi + 1 < n) delta += d(lo + 1, hi + 1) - d(hi, hi + 1);
        if (delta >= -kMinGainM) continue;
        // A shorter pair of legs must also stay clear of no-fly zones (or be worth it).
        delta = c(lo, hi) - c(lo, lo + 1);
        if (hi + 1 < n) delta += c(lo + 1, hi + 1) - c(hi, hi + 1);
        if (delta < -kMinGainM) {
          std::reverse(tour.begin() + static_cast<std::ptrdiff_t>(lo + 1),
                       tour.begin() + static_cast<std::ptrdiff_t>(hi + 1));
          reindex(lo + 1, hi);
          improved = true;
          break;
        }
      }
    }
    if (!improved) break;
  }
}

// The direction (radians counter-clockwise from east) in which the region is
// narrowest across: rows along it are the fewest, and so are the turns. Taken
// among the convex hull's edge directions (rotating calipers).
double RowDirection(const MultiPolygon& region) {
  Polygon hull;
  bg::convex_hull(region, hull);
  const auto& ring = hull.outer();
  double best_rad = 0.0;
  double best_width_m = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < ring.size(); ++i) {
    const double dx = ring[i + 1].x() - ring[i].x();
    const double dy = ring[i + 1].y() - ring[i].y();
    const double length_m = std::hypot(dx, dy);
    if (length_m <= 0.0) continue;
    double lo = std::numeric_limits<double>::infinity();
    double hi = -lo;
    for (const Point& p : ring) {
      const double across_m = (-dy * p.x() + dx * p.y()) / length_m;
      lo = std::min(lo, across_m);
      hi = std::max(hi, across_m);
    }
    if (hi - lo < best_width_m - 1e-9) {
      best_width_m = hi - lo;
      best_rad = std::atan2(dy, dx);
    }
  }
  return best_rad;
}

}  // namespace

// `seed` is not needed here: the tour is deterministic by construction, and the
// TransitPlanner (seeded by its owner) is the only randomised step.
Path CoverOmpl(const MultiPolygon& region, double sweep_width_m, Point start,
               const TransitPlanner& transit, unsigned /*seed*/) {
  if (!(sweep_width_m > 0.0) || !std::isfinite(sweep_width_m)) {
    throw std::invalid_argument("CoverOmpl: sweep_width_m must be positive and finite");
  }
  if (bg::area(region) <= 0.0) return {};
  // Work in the row frame: rows along x, in the region's narrowest direction.
  const LaneFrame frame{RowDirection(region)};
  const MultiPolygon rows_region = frame.ToLane(region);
  Box envelope;
  bg::envelope(rows_region, envelope);
  Grid grid;
  grid.origin = envelope.min_corner();
  grid.cell_m = sweep_width_m;
  const double width_m = envelope.max_corner().x() - envelope.min_corner().x();
  const double height_m = envelope.max_corner().y() - envelope.min_corner().y();
  const double columns = std::max(1.0, std::ceil(width_m / sweep_width_m));
  const double rows = std::max(1.0, std::ceil(height_m / sweep_width_m));
  if (columns * rows > kMaxGridCells) {
    throw std::invalid_argument("CoverOmpl: sweep_width_m " + std::to_string(sweep_width_m) +
                                " gives more than 4 million viewpoints over this region");
  }
  grid.columns = static_cast<long>(columns);
  grid.rows = static_cast<long>(rows);
  grid.buckets.resize(static_cast<std::size_t>(grid.columns * grid.rows));

  const Viewpoints viewpoints = PlaceViewpoints(rows_region, grid);
  const std::vector<Point>& points = viewpoints.points;
  if (points.empty()) return {};
  const Point start_in_rows = frame.ToLane(start);
  const LegCost cost{frame, transit, kDetourCells * sweep_width_m};
  const std::vector<std::size_t> order = BestGreedyTour(viewpoints, start_in_rows, grid, cost);

  // 2-opt over [start, viewpoints...]: node ids shifted by one, start is node 0.
  std::vector<Point> nodes{start_in_rows};
  nodes.insert(nodes.end(), points.begin(), points.end());
  std::vector<std::vector<std::size_t>> neighbours{{}};
  for (auto& list : NeighbourLists(points, grid)) {
    for (std::size_t& id : list) ++id;
    neighbours.push_back(std::move(list));
  }
  std::vector<std::size_t> tour{0};
  for (std::size_t id : order) tour.push_back(id + 1);
  neighbours[0].push_back(tour[1]);
  TwoOpt(tour, nodes, neighbours, cost);

  // Join the viewpoints (back in the local frame); a leg that would cross a no-fly
  // zone goes around it.
  Path path{frame.ToLocal(nodes[tour[1]])};
  for (std::size_t i = 2; i < tour.size(); ++i) {
    const Point from = path.back();
    const Point to = frame.ToLocal(nodes[tour[i]]);
    if (transit.IsClear(from, to)) {
      path.push_back(to);
    } else {
      const Path leg = transit.Plan(from, to);
      path.insert(path.end(), leg.begin() + (leg.empty() ? 0 : 1), leg.end());
    }
  }
  return path;
}

}  // namespace fireswarm::planner
