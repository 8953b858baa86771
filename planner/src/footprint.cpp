#include "fireswarm/planner/footprint.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "fireswarm/planner/plan.hpp"

namespace fireswarm::planner {
namespace {

double Radians(double degrees) {
  return degrees * std::numbers::pi / 180.0;
}

}  // namespace

double FootprintWidthM(const common::CameraModel& camera, double altitude_m, double pitch_deg) {
  if (!(altitude_m > 0.0) || !std::isfinite(altitude_m)) {
    throw std::invalid_argument("altitude_m must be > 0, got " + std::to_string(altitude_m));
  }
  if (!(pitch_deg >= -90.0 && pitch_deg < 0.0)) {
    throw std::invalid_argument(
        "camera_pitch_deg must be in [-90, 0) (down from the horizon), got " +
        std::to_string(pitch_deg));
  }
  const double depression_rad = Radians(-pitch_deg);
  const double tan_half_h = std::tan(Radians(camera.hfov_deg) / 2.0);
  const double tan_half_v = std::tan(Radians(camera.vfov_deg) / 2.0);
  // A ray through image row b (b = tan of its angle above the axis) meets the
  // ground at range h / (sin d - b cos d) along the axis; the near edge is b = -tan(vfov/2).
  const double near_edge_denominator =
      std::sin(depression_rad) + tan_half_v * std::cos(depression_rad);
  return 2.0 * altitude_m * tan_half_h / near_edge_denominator;
}

double SweepWidthM(const FleetSpec& fleet) {
  if (fleet.camera == nullptr) throw std::invalid_argument("camera: no camera model given");
  if (!(fleet.side_overlap >= 0.0 && fleet.side_overlap < 1.0)) {
    throw std::invalid_argument("side_overlap must be in [0, 1), got " +
                                std::to_string(fleet.side_overlap));
  }
  return FootprintWidthM(*fleet.camera, fleet.altitude_m, fleet.camera_pitch_deg) *
         (1.0 - fleet.side_overlap);
}

}  // namespace fireswarm::planner
