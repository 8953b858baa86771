#include "fireswarm/sim2d/thermal_camera.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string_view>

#include "fireswarm/common/angles.hpp"

namespace fireswarm::sim2d {
namespace {

[[noreturn]] void Reject(std::string_view field, double value, std::string_view rule) {
  std::ostringstream message;
  message << "thermal camera: " << field << " = " << value << " " << rule;
  throw std::invalid_argument(message.str());
}

void ValidateOptions(const ThermalCameraOptions& options, double saturation_c) {
  if (!std::isfinite(options.fixed_min_c)) {
    Reject("fixed_min_c", options.fixed_min_c, "must be finite");
  }
  const double max_c = std::isnan(options.fixed_max_c) ? saturation_c : options.fixed_max_c;
  if (!std::isfinite(max_c) || max_c <= options.fixed_min_c) {
    Reject("fixed_max_c", max_c, "must be finite and above fixed_min_c");
  }
  if (!(options.agc_min_span_k > 0.0) || !std::isfinite(options.agc_min_span_k)) {
    Reject("agc_min_span_k", options.agc_min_span_k, "must be a finite number > 0");
  }
  if (!(options.max_range_m > 0.0) || !std::isfinite(options.max_range_m)) {
    Reject("max_range_m", options.max_range_m, "must be a finite number > 0");
  }
}

// Body FRD -> local ENU: yaw (heading) about down, then pitch, then roll, as
// NED, then the NED -> ENU axis swap.
Eigen::Matrix3d BodyToEnu(const VehicleTruth& v) {
  const Eigen::Matrix3d ned_from_body =
      (Eigen::AngleAxisd(v.heading_rad, Eigen::Vector3d::UnitZ()) *
       Eigen::AngleAxisd(v.pitch_rad, Eigen::Vector3d::UnitY()) *
       Eigen::AngleAxisd(v.roll_rad, Eigen::Vector3d::UnitX()))
          .toRotationMatrix();
  Eigen::Matrix3d enu_from_ned;
  enu_from_ned << 0, 1, 0, 1, 0, 0, 0, 0, -1;
  return enu_from_ned * ned_from_body;
}

}  // namespace

ThermalCamera::ThermalCamera(const common::CameraModel& model, CameraMount mount,
                             ThermalCameraOptions options)
    : model_(model), mount_(mount), options_(options) {
  common::ValidateCamera(model_, mount_.camera_pitch_deg, "thermal camera");
  ValidateOptions(options_, model_.max_scene_c);
  if (std::isnan(options_.fixed_max_c)) options_.fixed_max_c = model_.max_scene_c;
  fx_px_ = 0.5 * model_.width_px / std::tan(0.5 * model_.hfov_deg * common::kRadPerDeg);
  fy_px_ = 0.5 * model_.height_px / std::tan(0.5 * model_.vfov_deg * common::kRadPerDeg);
  const double p = mount_.camera_pitch_deg * common::kRadPerDeg;
  axis_body_ = Eigen::Vector3d(std::cos(p), 0.0, -std::sin(p));
  right_body_ = Eigen::Vector3d::UnitY();
  up_body_ = Eigen::Vector3d(-std::sin(p), 0.0, -std::cos(p));
}

ThermalCamera::RayBasis ThermalCamera::BasisFor(const VehicleTruth& vehicle) const {
  const Eigen::Matrix3d m = BodyToEnu(vehicle);
  RayBasis basis;
  basis.axis = m * axis_body_;
  basis.per_u = m * right_body_ / fx_px_;
  basis.per_v = -(m * up_body_) / fy_px_;
  // A vehicle on (or, crashed, below) the ground sees the ground at its feet.
  basis.origin = Eigen::Vector3d(vehicle.position_m.x(), vehicle.position_m.y(),
                                 std::max(vehicle.altitude_m, 0.0));
  return basis;
}

Eigen::Vector3d ThermalCamera::RayEnu(const VehicleTruth& vehicle, double u_px, double v_px) const {
  const RayBasis b = BasisFor(vehicle);
  return b.axis + (u_px - 0.5 * model_.width_px) * b.per_u +
         (v_px - 0.5 * model_.height_px) * b.per_v;
}

std::optional<Vec2> ThermalCamera::PixelToGround(const VehicleTruth& vehicle, double u_px,
                                                 double v_px) const {
  const Eigen::Vector3d ray = RayEnu(vehicle, u_px, v_px);
  if (ray.z() >= 0.0) return std::nullopt;
  const double t = vehicle.altitude_m / -ray.z();
  return Vec2(vehicle.position_m.x() + t * ray.x(), vehicle.position_m.y() + t * ray.y());
}

std::optional<PixelCoord> ThermalCamera::GroundToPixel(const VehicleTruth& vehicle,
                                                       const Vec2& point_m) const {
  const Eigen::Vector3d to_point(point_m.x() - vehicle.position_m.x(),
                                 point_m.y() - vehicle.position_m.y(), -vehicle.altitude_m);
  const Eigen::Vector3d body = BodyToEnu(vehicle).transpose() * to_point;
  const double depth = body.dot(axis_body_);
  if (depth <= 0.0) return std::nullopt;
  PixelCoord pixel;
  pixel.u_px = 0.5 * model_.width_px + fx_px_ * body.dot(right_body_) / depth;
  pixel.v_px = 0.5 * model_.height_px - fy_px_ * body.dot(up_body_) / depth;
  if (pixel.u_px < 0.0 || pixel.v_px < 0.0 || pixel.u_px >= model_.width_px ||
      pixel.v_px >= model_.height_px) {
    return std::nullopt;
  }
  return pixel;
}

ThermalImage ThermalCamera::Render(const VehicleTruth& vehicle, const TemperatureField& field,
                                   double capture_time_s, Rng& rng) {
  ThermalImage image;
  Render(vehicle, field, capture_time_s, rng, image);
  return image;
}

}  // namespace fireswarm::sim2d
