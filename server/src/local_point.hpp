// Local positions in the server core: Eigen (north, east) metres of the mission
// area's frame, while the planner's geometry is (x east, y north). Converted here
// only, so the order is written once.
#pragma once

#include <Eigen/Core>

#include "fireswarm/common/local_frame.hpp"
#include "fireswarm/planner/geometry.hpp"

namespace fireswarm::server {

/// `point` in `frame`'s local (north, east) metres.
inline Eigen::Vector2d NorthEast(const common::LocalFrame& frame, common::LatLon point) {
  const common::EastNorth local = frame.ToLocal(point);
  return {local.north_m, local.east_m};
}

/// A planner point (x east, y north) as local (north, east) metres.
inline Eigen::Vector2d NorthEast(const planner::Point& point) {
  return {point.y(), point.x()};
}

/// Local (north, east) metres as a planner point (x east, y north).
inline planner::Point PlannerPoint(const Eigen::Vector2d& ne_m) {
  return {ne_m.y(), ne_m.x()};
}

}  // namespace fireswarm::server
