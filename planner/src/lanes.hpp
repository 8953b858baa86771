// Sweep lanes: the straight passes of a boustrophedon over one cell, and the
// rotated "lane frame" they are computed in (lanes run along its x axis).
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

/// One pass over a cell, in the lane frame.
struct Lane {
  double y_m = 0.0;          ///< the lane's line
  double x_min_m = 0.0;      ///< where the flown segment begins (western end)
  double x_max_m = 0.0;      ///< and ends
  double chord_min_m = 0.0;  ///< the cell's chord at y_m (x_min_m <= chord_min_m)
  double chord_max_m = 0.0;
  double band_lo_m = 0.0;  ///< the strip of the cell this lane is responsible for
  double band_hi_m = 0.0;
};

/// Lanes over a y-monotone `cell` (lane frame): n = ceil(height / sweep) lanes
/// spaced height / n <= sweep_width_m apart, the first and last half a spacing
/// inside the cell's bottom and top. Each lane spans the cell's chord at its y
/// (endpoints on the boundary), lengthened where the cell's strip reaches further
/// than a footprint of radius `footprint_radius_m` centred on the chord's end
/// would see (slanted boundaries), so the footprints cover the strip to its edge.
/// Precondition: footprint_radius_m > sweep_width_m / 2.
std::vector<Lane> CellLanes(const Polygon& cell, double sweep_width_m, double footprint_radius_m);

}  // namespace fireswarm::planner
