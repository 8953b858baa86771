#include "fire_spread.hpp"

#include <algorithm>
#include <cmath>

namespace fireswarm::sim2d {
namespace {
constexpr double kMphPerMps = 2.2369362920544;
}  // namespace

double HeadRosMpm(const FuelBehaviour& fuel, double wind_mps, double wind_exponent) {
  const double wind_ratio = std::max(wind_mps, 0.0) / kReferenceWindMps;
  return fuel.no_wind_ros_mpm +
         (fuel.head_ros_ref_mpm - fuel.no_wind_ros_mpm) * std::pow(wind_ratio, wind_exponent);
}

double LengthToBreadth(double wind_mps) {
  // Anderson (1983), midflame wind in mi/h; equals 1.0 at zero wind.
  const double wind_mph = std::max(wind_mps, 0.0) * kMphPerMps;
  const double lb =
      0.936 * std::exp(0.2566 * wind_mph) + 0.461 * std::exp(-0.1548 * wind_mph) - 0.397;
  return std::max(lb, 1.0);
}

double RosInDirectionMpm(double head_ros_mpm, double lb, double cos_from_head) {
  const double e = std::sqrt(std::max(lb * lb - 1.0, 0.0)) / lb;
  return head_ros_mpm * (1.0 - e) / (1.0 - e * cos_from_head);
}

}  // namespace fireswarm::sim2d
