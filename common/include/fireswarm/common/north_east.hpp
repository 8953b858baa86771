// The server works in (east, north) local metres, as common::EastNorth, the
// planner, sim2d and the vehicles' simulator do. A few formats fixed before it
// did keep (north, east) order: fire_track_t's covariance_m2, the journal's
// *_ne_m and covariance_ne_m2 fields, and the run report's covariance_ne_m2.
// Vectors and covariances are put in that order here, and only here.
#pragma once

#include <Eigen/Core>
#include <array>

namespace fireswarm::common {

/// `v` with its two axes exchanged: (east, north) as (north, east), or back.
inline Eigen::Vector2d SwapAxes(const Eigen::Vector2d& v) {
  return {v.y(), v.x()};
}

/// The covariance `m` of a vector whose axes are exchanged (the same matrix in
/// the other axis order): the diagonal exchanged, the off-diagonal kept.
inline Eigen::Matrix2d SwapAxes(const Eigen::Matrix2d& m) {
  Eigen::Matrix2d swapped;
  swapped << m(1, 1), m(1, 0), m(0, 1), m(0, 0);
  return swapped;
}

/// An (east, north) covariance as the north-first formats write it:
/// {north-north, north-east, east-east}, m^2.
inline std::array<double, 3> NorthEastTriangle(const Eigen::Matrix2d& covariance_en_m2) {
  const Eigen::Matrix2d ne = SwapAxes(covariance_en_m2);
  return {ne(0, 0), ne(0, 1), ne(1, 1)};
}

}  // namespace fireswarm::common
