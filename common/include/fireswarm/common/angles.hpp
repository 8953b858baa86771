// Angles, one way for the whole tree: radians inside, degrees only at the edges
// (GeoJSON, scenario files, the seed's navigation). Headings clockwise from north.
#pragma once

#include <cmath>
#include <numbers>

namespace fireswarm::common {

inline constexpr double kRadPerDeg = std::numbers::pi / 180.0;
inline constexpr double kDegPerRad = 180.0 / std::numbers::pi;

/// `degrees` in radians, as degrees * pi / 180 (multiplied before dividing: the
/// camera models, wind and fire spread have always converted this way, and the
/// last bit of a wind direction changes a whole simulated mission).
constexpr double DegToRad(double degrees) {
  return degrees * std::numbers::pi / 180.0;
}

/// `angle_rad` wrapped into [-pi, pi] (IEEE remainder by a full turn).
inline double WrapPi(double angle_rad) {
  return std::remainder(angle_rad, 2.0 * std::numbers::pi);
}

}  // namespace fireswarm::common
