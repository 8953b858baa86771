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

}  // namespace fireswarm::planner
