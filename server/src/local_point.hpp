// Local positions in the server core: Eigen (east, north) metres of the mission
// area's frame, the order of common::EastNorth and of the planner's geometry (x
// east, y north). Both are adapted to Eigen here only; the projection itself is
// common::LocalFrame's.
#pragma once

#include <Eigen/Core>

#include "fireswarm/common/local_frame.hpp"
#include "fireswarm/planner/geometry.hpp"

namespace fireswarm::server {

/// `point` in `frame`'s local (east, north) metres.
inline Eigen::Vector2d LocalM(const common::LocalFrame& frame, common::LatLon point) {
  const common::EastNorth local = frame.ToLocal(point);
  return {local.east_m, local.north_m};
}

/// Local (east, north) metres of `frame` as a geodetic point.
inline common::LatLon Geodetic(const common::LocalFrame& frame, const Eigen::Vector2d& en_m) {
  return frame.ToGeodetic({en_m.x(), en_m.y()});
}

/// A planner point (x east, y north) as local (east, north) metres.
inline Eigen::Vector2d FromPlanner(const planner::Point& point) {
  return {point.x(), point.y()};
}

/// Local (east, north) metres as a planner point (x east, y north).
inline planner::Point PlannerPoint(const Eigen::Vector2d& en_m) {
  return {en_m.x(), en_m.y()};
}

}  // namespace fireswarm::server
