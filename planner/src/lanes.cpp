#include "lanes.hpp"

#include <algorithm>
#include <boost/geometry.hpp>
#include <cmath>
#include <limits>

namespace fireswarm::planner {
namespace bg = boost::geometry;

double LengthM(const Path& path) {
  return static_cast<double>(bg::length(path));
}
double AreaM2(const MultiPolygon& region) {
  return static_cast<double>(bg::area(region));
}

Point LaneFrame::ToLane(Point p) const {
  const double c = std::cos(direction_rad), s = std::sin(direction_rad);
  return {p.x() * c + p.y() * s, -p.x() * s + p.y() * c};
}

Point LaneFrame::ToLocal(Point p) const {
  const double c = std::cos(direction_rad), s = std::sin(direction_rad);
  return {p.x() * c - p.y() * s, p.x() * s + p.y() * c};
}

namespace {

template <typename Transform>
Polygon MapPolygon(const Polygon& in, Transform transform) {
  Polygon out;
  for (const Point& p : in.outer()) out.outer().push_back(transform(p));
  for (const auto& ring : in.inners()) {
    out.inners().emplace_back();
    for (const Point& p : ring) out.inners().back().push_back(transform(p));
  }
  return out;  // a rotation keeps orientation and closure
}

}  // namespace

Polygon LaneFrame::ToLane(const Polygon& local) const {
  return MapPolygon(local, [this](Point p) { return ToLane(p); });
}

MultiPolygon LaneFrame::ToLane(const MultiPolygon& local) const {
  MultiPolygon out;
  for (const Polygon& polygon : local) out.push_back(ToLane(polygon));
  return out;
}

Polygon LaneFrame::ToLocal(const Polygon& lane) const {
  return MapPolygon(lane, [this](Point p) { return ToLocal(p); });
}

std::vector<std::pair<double, double>> LineIntervals(const Polygon& shape, double y_m) {
  std::vector<double> crossings;
  auto add_ring = [&](const auto& ring) {
    for (std::size_t i = 0; i + 1 < ring.size(); ++i) {
      const Point& a = ring[i];
      const Point& b = ring[i + 1];
      // Half-open rule: an edge counts when y is in [min, max), so a vertex on
      // the line is counted once and horizontal edges never.
      if ((a.y() <= y_m) == (b.y() <= y_m)) continue;
      const double t = (y_m - a.y()) / (b.y() - a.y());
      crossings.push_back(a.x() + t * (b.x() - a.x()));
    }
  };
  add_ring(shape.outer());
  for (const auto& ring : shape.inners()) add_ring(ring);
  std::sort(crossings.begin(), crossings.end());
  std::vector<std::pair<double, double>> intervals;
  for (std::size_t i = 0; i + 1 < crossings.size(); i += 2) {
    intervals.emplace_back(crossings[i], crossings[i + 1]);
  }
  return intervals;
}

namespace {

// The x extent of the cell between y_lo and y_hi: its chords at both levels and
// every vertex in between (the extent of a polygon slice is reached at one of them).
std::pair<double, double> StripExtent(const Polygon& cell, double y_lo, double y_hi) {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  for (const double y : {y_lo, y_hi}) {
    for (const auto& [a, b] : LineIntervals(cell, y)) {
      lo = std::min(lo, a);
      hi = std::max(hi, b);
    }
  }
  for (const Point& p : cell.outer()) {
    if (p.y() >= y_lo && p.y() <= y_hi) {
      lo = std::min(lo, p.x());
      hi = std::max(hi, p.x());
    }
  }
  return {lo, hi};
}

}  // namespace

std::vector<Lane> CellLanes(const Polygon& cell, double sweep_width_m, double footprint_radius_m) {
  Box envelope;
  bg::envelope(cell, envelope);
  const double y0 = envelope.min_corner().y();
  const double height_m = envelope.max_corner().y() - y0;
  constexpr double kSlack = 1e-6;  // a cell exactly n sweeps tall needs n lanes, not n + 1
  const int count = std::max(1, static_cast<int>(std::ceil(height_m / sweep_width_m - kSlack)));
  const double spacing_m = height_m / count;
  const double half_m = spacing_m / 2.0;
  // How far past a chord's end the footprint still reaches at the strip's edge.
  const double reach_m =
      std::sqrt(std::max(0.0, footprint_radius_m * footprint_radius_m - half_m * half_m));
  std::vector<Lane> lanes;
  for (int k = 0; k < count; ++k) {
    Lane lane;
    lane.y_m = y0 + (k + 0.5) * spacing_m;
    lane.band_lo_m = lane.y_m - half_m;
    lane.band_hi_m = lane.y_m + half_m;
    const auto chords = LineIntervals(cell, lane.y_m);
    if (chords.empty()) continue;  // a sliver thinner than rounding
    const auto [strip_lo, strip_hi] = StripExtent(cell, lane.band_lo_m, lane.band_hi_m);
    lane.chord_min_m = chords.front().first;
    lane.chord_max_m = chords.back().second;
    lane.x_min_m = std::min(chords.front().first, strip_lo + reach_m);
    lane.x_max_m = std::max(chords.back().second, strip_hi - reach_m);
    lanes.push_back(lane);
  }
  return lanes;
}

}  // namespace fireswarm::planner
