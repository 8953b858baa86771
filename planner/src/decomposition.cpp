#include "decomposition.hpp"

#include <algorithm>
#include <boost/geometry.hpp>
#include <cmath>
#include <numeric>

#include "lanes.hpp"

namespace fireswarm::planner {
namespace bg = boost::geometry;

namespace {

constexpr double kMinPieceAreaM2 = 1e-6;  // slivers of rounding at nearly equal levels

// Ring vertices that are local extremes in y (plateaus included): only there can
// a horizontal line's number of intervals change.
template <typename Ring>
void AddCriticalLevels(const Ring& ring, std::vector<double>& levels) {
  const std::size_t n = ring.size() > 0 ? ring.size() - 1 : 0;  // closed ring
  for (std::size_t i = 0; i < n; ++i) {
    const double y = ring[i].y();
    std::size_t prev = i, next = i;
    for (std::size_t step = 0; step < n && ring[prev].y() == y; ++step) prev = (prev + n - 1) % n;
    for (std::size_t step = 0; step < n && ring[next].y() == y; ++step) next = (next + 1) % n;
    if ((ring[prev].y() - y) * (ring[next].y() - y) > 0.0) levels.push_back(y);
  }
}

std::vector<double> CriticalLevels(const MultiPolygon& region, double tolerance_m) {
  std::vector<double> levels;
  for (const Polygon& polygon : region) {
    AddCriticalLevels(polygon.outer(), levels);
    for (const auto& ring : polygon.inners()) AddCriticalLevels(ring, levels);
  }
  std::sort(levels.begin(), levels.end());
  std::vector<double> unique;
  for (const double y : levels) {
    if (unique.empty() || y - unique.back() > tolerance_m) unique.push_back(y);
  }
  return unique;
}

struct Piece {
  Polygon polygon;
  std::size_t slab = 0;
  double bottom_lo = 0, bottom_hi = 0;  // x extent where it touches its slab's bottom
  double top_lo = 0, top_hi = 0;
};

// The x extent of `polygon`'s vertices lying on the level y (within tolerance).
std::pair<double, double> ExtentAtLevel(const Polygon& polygon, double y, double tolerance_m) {
  double lo = 1e300, hi = -1e300;
  for (const Point& p : polygon.outer()) {
    if (std::abs(p.y() - y) <= tolerance_m) {
      lo = std::min(lo, p.x());
      hi = std::max(hi, p.x());
    }
  }
  return {lo, hi};
}

// True when every horizontal line through the middle of the slab meets each part once.
bool AllMonotone(const MultiPolygon& parts, double y_mid) {
  return std::all_of(parts.begin(), parts.end(), [y_mid](const Polygon& part) {
    return LineIntervals(part, y_mid).size() <= 1;
  });
}

// Moves vertices lying on y = from onto y = to.
void Snap(MultiPolygon& parts, double from, double to, double tolerance_m) {
  for (Polygon& part : parts) {
    for (Point& p : part.outer()) {
      if (std::abs(p.y() - from) <= tolerance_m) p.y(to);
    }
  }
}

// The region between two levels, one polygon per y-monotone piece. Where a region
// edge lies on the slab's own edge Boost can return two pieces joined along it (a
// zero-width bridge); such a slab is cut again with a box shrunk by a hair and the
// cut vertices snapped back onto the levels.
MultiPolygon Slab(const MultiPolygon& region, double x_lo, double x_hi, double y0, double y1,
                  double tolerance_m) {
  MultiPolygon parts;
  bg::intersection(region, Box{{x_lo, y0}, {x_hi, y1}}, parts);
  const double y_mid = (y0 + y1) / 2;
  if (AllMonotone(parts, y_mid)) return parts;
  const double hair_m = std::min(1e3 * tolerance_m, (y1 - y0) / 4);
  parts.clear();
  bg::intersection(region, Box{{x_lo, y0 + hair_m}, {x_hi, y1 - hair_m}}, parts);
  Snap(parts, y0 + hair_m, y0, hair_m / 2);
  Snap(parts, y1 - hair_m, y1, hair_m / 2);
  return parts;
}

std::vector<Piece> SlabPieces(const MultiPolygon& region, const std::vector<double>& levels,
                              double tolerance_m) {
  Box envelope;
  bg::envelope(region, envelope);
  const double x_lo = envelope.min_corner().x() - 1.0;
  const double x_hi = envelope.max_corner().x() + 1.0;
  std::vector<Piece> pieces;
  for (std::size_t slab = 0; slab + 1 < levels.size(); ++slab) {
    MultiPolygon parts = Slab(region, x_lo, x_hi, levels[slab], levels[slab + 1], tolerance_m);
    for (Polygon& part : parts) {
      if (std::abs(static_cast<double>(bg::area(part))) < kMinPieceAreaM2) continue;
      Piece piece;
      std::tie(piece.bottom_lo, piece.bottom_hi) = ExtentAtLevel(part, levels[slab], tolerance_m);
      std::tie(piece.top_lo, piece.top_hi) = ExtentAtLevel(part, levels[slab + 1], tolerance_m);
      piece.polygon = std::move(part);
      piece.slab = slab;
      pieces.push_back(std::move(piece));
    }
  }
  return pieces;
}

std::size_t Find(std::vector<std::size_t>& parent, std::size_t i) {
  while (parent[i] != i) i = parent[i] = parent[parent[i]];
  return i;
}

// Union-find groups of pieces that meet one-to-one across a level.
std::vector<std::size_t> MergeGroups(const std::vector<Piece>& pieces, double tolerance_m) {
  const std::size_t n = pieces.size();
  std::vector<std::size_t> up_degree(n, 0), down_degree(n, 0);
  std::vector<std::pair<std::size_t, std::size_t>> links;
  for (std::size_t a = 0; a < n; ++a) {
    for (std::size_t b = 0; b < n; ++b) {
      if (pieces[b].slab != pieces[a].slab + 1) continue;
      const double overlap = std::min(pieces[a].top_hi, pieces[b].bottom_hi) -
                             std::max(pieces[a].top_lo, pieces[b].bottom_lo);
      if (overlap <= tolerance_m) continue;
      links.emplace_back(a, b);
      ++up_degree[a];
      ++down_degree[b];
    }
  }
  std::vector<std::size_t> parent(n);
  std::iota(parent.begin(), parent.end(), std::size_t{0});
  for (const auto& [a, b] : links) {
    if (up_degree[a] == 1 && down_degree[b] == 1) parent[Find(parent, b)] = Find(parent, a);
  }
  for (std::size_t i = 0; i < n; ++i) parent[i] = Find(parent, i);
  return parent;
}

}  // namespace

std::vector<Polygon> DecomposeLaneFrame(const MultiPolygon& region_lane) {
  if (region_lane.empty()) return {};
  Box envelope;
  bg::envelope(region_lane, envelope);
  const double extent_m = std::max(envelope.max_corner().x() - envelope.min_corner().x(),
                                   envelope.max_corner().y() - envelope.min_corner().y());
  const double tolerance_m = 1e-9 * std::max(1.0, extent_m);
  const std::vector<double> levels = CriticalLevels(region_lane, tolerance_m);
  const std::vector<Piece> pieces = SlabPieces(region_lane, levels, tolerance_m);
  const std::vector<std::size_t> group = MergeGroups(pieces, tolerance_m);
  std::vector<Polygon> cells;
  // Pieces are in slab order, so each group is merged bottom-up.
  std::vector<std::size_t> cell_of_group(pieces.size(), pieces.size());
  for (std::size_t i = 0; i < pieces.size(); ++i) {
    std::size_t& cell = cell_of_group[group[i]];
    if (cell < cells.size()) {
      MultiPolygon merged;
      bg::union_(cells[cell], pieces[i].polygon, merged);
      if (merged.size() == 1) {
        cells[cell] = std::move(merged.front());
        continue;
      }
    }
    cell = cells.size();  // first piece of its group, or a union that did not join
    cells.push_back(pieces[i].polygon);
  }
  return cells;
}

std::vector<Polygon> Decompose(const MultiPolygon& region, double direction_rad) {
  const LaneFrame frame{direction_rad};
  std::vector<Polygon> cells = DecomposeLaneFrame(frame.ToLane(region));
  for (Polygon& cell : cells) cell = frame.ToLocal(cell);
  return cells;
}

}  // namespace fireswarm::planner
