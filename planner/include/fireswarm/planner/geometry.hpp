// Planar geometry in the local frame (metres east, north of the area's origin),
// on Boost.Geometry. Every planner stage speaks these types.
#pragma once

#include <boost/geometry/geometries/box.hpp>
#include <boost/geometry/geometries/linestring.hpp>
#include <boost/geometry/geometries/multi_polygon.hpp>
#include <boost/geometry/geometries/point_xy.hpp>
#include <boost/geometry/geometries/polygon.hpp>

namespace fireswarm::planner {

/// x = metres east, y = metres north of the local frame's origin.
using Point = boost::geometry::model::d2::point_xy<double>;
/// Outer ring clockwise, holes counter-clockwise, rings closed (Boost defaults);
/// call boost::geometry::correct() on anything built by hand.
using Polygon = boost::geometry::model::polygon<Point>;
using MultiPolygon = boost::geometry::model::multi_polygon<Polygon>;
using Path = boost::geometry::model::linestring<Point>;
using Box = boost::geometry::model::box<Point>;

}  // namespace fireswarm::planner
