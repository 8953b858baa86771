#include "lane_field.hpp"

#include <algorithm>
#include <boost/geometry.hpp>
#include <cmath>

namespace fireswarm::planner {
namespace bg = boost::geometry;

namespace {

struct Edge {
  Point a, b;
};

template <typename Ring>
void AddEdges(const Ring& ring, std::vector<Edge>& edges) {
  for (std::size_t i = 0; i + 1 < ring.size(); ++i) edges.push_back({ring[i], ring[i + 1]});
}

// The x range of edge e where it lies between y_lo and y_hi; false when it does not.
bool ClippedRange(const Edge& e, double y_lo, double y_hi, Span& out) {
  const double e_lo = std::min(e.a.y(), e.b.y()), e_hi = std::max(e.a.y(), e.b.y());
  if (e_hi < y_lo || e_lo > y_hi) return false;
  auto x_at = [&](double y) {
    if (e.b.y() == e.a.y()) return e.a.x();
    const double t = std::clamp((y - e.a.y()) / (e.b.y() - e.a.y()), 0.0, 1.0);
    return e.a.x() + t * (e.b.x() - e.a.x());
  };
  const double x0 = x_at(std::max(e_lo, y_lo)), x1 = x_at(std::min(e_hi, y_hi));
  out = {std::min(x0, x1), std::max(x0, x1)};
  return true;
}

}  // namespace

std::vector<Span> MergedSpans(std::vector<Span> spans, double gap_m) {
  std::sort(spans.begin(), spans.end(),
            [](const Span& a, const Span& b) { return a.lo_m < b.lo_m; });
  std::vector<Span> out;
  for (const Span& s : spans) {
    if (!out.empty() && s.lo_m <= out.back().hi_m + gap_m) {
      out.back().hi_m = std::max(out.back().hi_m, s.hi_m);
    } else {
      out.push_back(s);
    }
  }
  return out;
}

LaneField BuildLaneField(const MultiPolygon& region, double direction_rad, double sweep_width_m,
                         double merge_gap_m) {
  LaneField field;
  field.frame.direction_rad = direction_rad;
  field.region_lane = field.frame.ToLane(region);
  const MultiPolygon& lane_region = field.region_lane;
  Box box;
  bg::envelope(lane_region, box);
  const double height_m = box.max_corner().y() - box.min_corner().y();
  const auto rows = static_cast<std::size_t>(std::max(1.0, std::ceil(height_m / sweep_width_m)));
  field.spacing_m = height_m / static_cast<double>(rows);

  std::vector<Edge> edges;
  for (const Polygon& polygon : lane_region) {
    AddEdges(polygon.outer(), edges);
    for (const auto& ring : polygon.inners()) AddEdges(ring, edges);
  }
  // Edges by their lowest y, so each row looks only at those that can reach it.
  std::sort(edges.begin(), edges.end(), [](const Edge& a, const Edge& b) {
    return std::min(a.a.y(), a.b.y()) < std::min(b.a.y(), b.b.y());
  });
  std::vector<double> edge_top(edges.size());
  for (std::size_t i = 0; i < edges.size(); ++i) {
    edge_top[i] = std::max(edges[i].a.y(), edges[i].b.y());
  }

  for (std::size_t j = 0; j < rows; ++j) {
    LaneRow row;
    row.y_m = box.min_corner().y() + (static_cast<double>(j) + 0.5) * field.spacing_m;
    const double y_lo = row.y_m - field.spacing_m / 2.0, y_hi = row.y_m + field.spacing_m / 2.0;
    // The band's projection: where its edges pass, and where its bottom, middle or
    // top line runs inside (a vertical through the band meets the region exactly
    // when it crosses an edge there or one of those lines is inside).
    std::vector<Span> spans;
    for (const double y : {y_lo, row.y_m, y_hi}) {
      for (const Polygon& polygon : lane_region) {
        for (const auto& [a, b] : LineIntervals(polygon, y)) spans.push_back({a, b});
      }
    }
    for (std::size_t i = 0; i < edges.size(); ++i) {
      if (std::min(edges[i].a.y(), edges[i].b.y()) > y_hi) break;
      if (edge_top[i] < y_lo) continue;
      Span s;
      if (ClippedRange(edges[i], y_lo, y_hi, s)) spans.push_back(s);
    }
    row.spans = MergedSpans(std::move(spans), merge_gap_m);
    field.rows.push_back(std::move(row));
  }
  return field;
}

}  // namespace fireswarm::planner
