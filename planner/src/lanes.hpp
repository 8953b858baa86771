// The rotated "lane frame" lanes are computed in (they run along its x axis), and
// where a horizontal line crosses a polygon.
#pragma once

#include <utility>
#include <vector>

#include "fireswarm/planner/geometry.hpp"

namespace fireswarm::planner {

/// Boost.Geometry's length/area return long double for double points; these
/// return plain metres.
double LengthM(const Path& path);
double AreaM2(const MultiPolygon& region);

/// The lane frame: the local frame turned so that lanes heading `direction_rad`
/// (counter-clockwise from east) run along +x.
struct LaneFrame {
  double direction_rad = 0.0;
  Point ToLane(Point local) const;
  Point ToLocal(Point lane) const;
  Polygon ToLane(const Polygon& local) const;
  MultiPolygon ToLane(const MultiPolygon& local) const;
  Polygon ToLocal(const Polygon& lane) const;
};

/// The x intervals where the horizontal line at `y_m` crosses `shape` (even-odd
/// over all rings), sorted. For a y-monotone cell there is one interval.
std::vector<std::pair<double, double>> LineIntervals(const Polygon& shape, double y_m);

}  // namespace fireswarm::planner
