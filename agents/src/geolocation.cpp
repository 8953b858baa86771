#include "fireswarm/agents/geolocation.hpp"

#include <Eigen/Geometry>
#include <array>
#include <cassert>
#include <cmath>
#include <stdexcept>
#include <string_view>

#include "fireswarm/common/angles.hpp"

namespace fireswarm::agents {
namespace {

// Rays closer to the horizon than this (down component of the unnormalised ray)
// do not meet the ground at a meaningful distance.
constexpr double kMinDownRay = 1e-9;

// Body FRD -> NED: heading about down, then pitch, then roll (as sim2d's camera).
Eigen::Matrix3d NedFromBody(double roll_rad, double pitch_rad, double heading_rad) {
  return (Eigen::AngleAxisd(heading_rad, Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(pitch_rad, Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(roll_rad, Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

// The inputs a fix depends on, in the order of GeolocationSigmas (after the
// horizontal position, which adds to the result directly).
enum Input { kAltitude, kRoll, kPitch, kHeading, kU, kV, kInputCount };
using InputVector = Eigen::Matrix<double, kInputCount, 1>;

// Central-difference steps: small against the sigmas, large against rounding.
constexpr std::array<double, kInputCount> kSteps = {1e-4, 1e-7, 1e-7, 1e-7, 1e-5, 1e-5};

// (east, north) of the intersection for the inputs x, or nullopt above the horizon.
std::optional<Eigen::Vector2d> GroundOffsetEastNorth(const ObserverPose& pose,
                                                     const InputVector& x) {
  const CameraGeometry& camera = pose.camera;
  if (!(x[kAltitude] > 0.0)) return std::nullopt;
  const double fx_px = 0.5 * camera.width_px / std::tan(0.5 * camera.hfov_deg * common::kRadPerDeg);
  const double fy_px =
      0.5 * camera.height_px / std::tan(0.5 * camera.vfov_deg * common::kRadPerDeg);
  const double p = camera.camera_pitch_deg * common::kRadPerDeg;
  const Eigen::Vector3d axis(std::cos(p), 0.0, -std::sin(p));
  const Eigen::Vector3d right = Eigen::Vector3d::UnitY();
  const Eigen::Vector3d up(-std::sin(p), 0.0, -std::cos(p));
  const Eigen::Vector3d ray_body = axis + (x[kU] - 0.5 * camera.width_px) / fx_px * right -
                                   (x[kV] - 0.5 * camera.height_px) / fy_px * up;
  const Eigen::Vector3d ray = NedFromBody(x[kRoll], x[kPitch], x[kHeading]) * ray_body;
  if (ray.z() < kMinDownRay) return std::nullopt;
  const double t = x[kAltitude] / ray.z();
  // The ray is NED: x north, y east.
  return Eigen::Vector2d(t * ray.y(), t * ray.x());
}

InputVector InputsOf(const ObserverPose& pose, ImagePoint pixel) {
  InputVector x;
  x << pose.altitude_m, pose.roll_rad, pose.pitch_rad, pose.heading_rad, pixel.u_px, pixel.v_px;
  return x;
}

}  // namespace

CameraGeometry GeometryOf(const common::CameraModel& model, double camera_pitch_deg) {
  common::ValidateCamera(model, camera_pitch_deg, "camera geometry");
  CameraGeometry geometry;
  geometry.width_px = model.width_px;
  geometry.height_px = model.height_px;
  geometry.hfov_deg = model.hfov_deg;
  geometry.vfov_deg = model.vfov_deg;
  geometry.camera_pitch_deg = camera_pitch_deg;
  return geometry;
}

std::optional<common::EastNorth> IntersectGround(const ObserverPose& pose, ImagePoint pixel) {
  const std::optional<Eigen::Vector2d> east_north_m =
      GroundOffsetEastNorth(pose, InputsOf(pose, pixel));
  if (!east_north_m) return std::nullopt;
  return common::EastNorth{east_north_m->x(), east_north_m->y()};
}

std::optional<GroundFix> GeolocatePixel(const ObserverPose& pose, ImagePoint pixel,
                                        const GeolocationSigmas& sigmas) {
  const InputVector x = InputsOf(pose, pixel);
  const std::optional<Eigen::Vector2d> east_north_m = GroundOffsetEastNorth(pose, x);
  if (!east_north_m) return std::nullopt;

  // First-order propagation: J diag(sigma^2) J^T, J by central differences,
  // rows (east, north).
  Eigen::Matrix<double, 2, kInputCount> jacobian;
  for (int i = 0; i < kInputCount; ++i) {
    InputVector plus = x, minus = x;
    const double step = kSteps[static_cast<std::size_t>(i)];
    plus[i] += step;
    minus[i] -= step;
    const std::optional<Eigen::Vector2d> a = GroundOffsetEastNorth(pose, plus);
    const std::optional<Eigen::Vector2d> b = GroundOffsetEastNorth(pose, minus);
    if (!a || !b) return std::nullopt;
    jacobian.col(i) = (*a - *b) / (2.0 * step);
  }
  InputVector variances;
  variances << sigmas.altitude_m * sigmas.altitude_m, sigmas.roll_rad * sigmas.roll_rad,
      sigmas.pitch_rad * sigmas.pitch_rad, sigmas.heading_rad * sigmas.heading_rad,
      sigmas.pixel_px * sigmas.pixel_px, sigmas.pixel_px * sigmas.pixel_px;

  GroundFix fix;
  fix.offset_m = common::EastNorth{east_north_m->x(), east_north_m->y()};
  // One fix per call: a LocalFrame at the vehicle is the one way to geodesy.
  fix.position = common::LocalFrame(pose.position).ToGeodetic(fix.offset_m);
  const auto pixel_part = jacobian.rightCols<2>();
  const Eigen::Matrix2d pixel_covariance =
      pixel_part * variances.tail<2>().asDiagonal() * pixel_part.transpose();
  fix.pixel_covariance_en_m2 = 0.5 * (pixel_covariance + pixel_covariance.transpose());
  // The GPS horizontal error moves the fix with the vehicle, one to one.
  const Eigen::Matrix2d propagated = jacobian * variances.asDiagonal() * jacobian.transpose();
  // Symmetric to the last bit, so consumers may rely on (0, 1) == (1, 0).
  fix.covariance_en_m2 = 0.5 * (propagated + propagated.transpose()) +
                         sigmas.horizontal_m * sigmas.horizontal_m * Eigen::Matrix2d::Identity();
  return fix;
}

ImagePoint SeedCentroid(std::span<const int> cols, std::span<const int> rows) {
  assert(cols.size() == rows.size() && !cols.empty());
  double sum_u = 0.0, sum_v = 0.0;
  for (std::size_t i = 0; i < cols.size(); ++i) {
    sum_u += cols[i] + 0.5;
    sum_v += rows[i] + 0.5;
  }
  const auto n = static_cast<double>(cols.size());
  ImagePoint centroid;
  centroid.u_px = sum_u / n;
  centroid.v_px = sum_v / n;
  return centroid;
}

SeedGeolocationResult SeedFlatTerrainGeolocation(const SeedGeolocationInput& input) {
  const double dx = input.width_px / 2.0 - input.centroid_x_px;                            // eq. 7
  const double dy = input.height_px / 2.0 - input.centroid_y_px;                           // eq. 8
  const double x_t = dx * input.hfov_deg / input.width_px;                                 // eq. 9
  const double omega_t = input.gps_heading_deg + x_t;                                      // eq. 10
  const double phi_t = dy * input.vfov_deg / input.height_px;                              // eq. 11
  const double theta_t = 90.0 - (input.frame_pitch_deg + input.camera_mount_deg) + phi_t;  // eq. 12
  const double d_t = input.height_m * std::tan(theta_t * common::kRadPerDeg);              // eq. 13

  const double lat_gps = input.position.lat_deg * common::kRadPerDeg;
  const double lon_gps = input.position.lon_deg * common::kRadPerDeg;
  const double omega = omega_t * common::kRadPerDeg;
  const double delta = d_t / input.earth_radius_m;
  const double lat_t = std::asin(std::sin(lat_gps) * std::cos(delta) +
                                 std::cos(lat_gps) * std::sin(delta) * std::cos(omega));  // eq. 14
  const double lon_t =
      lon_gps + std::atan2(std::sin(omega) * std::sin(delta) * std::cos(lat_gps),
                           std::cos(delta) - std::sin(lat_gps) * std::sin(lat_t));  // eq. 15

  SeedGeolocationResult result;
  result.bearing_deg = omega_t;
  result.ground_distance_m = d_t;
  result.angle_from_vertical_deg = theta_t;
  result.position.lat_deg = lat_t * common::kDegPerRad;
  result.position.lon_deg = lon_t * common::kDegPerRad;
  return result;
}

SeedGeolocationInput SeedInputFromImage(ImagePoint centroid, const ObserverPose& pose) {
  SeedGeolocationInput input;
  // Eq. 7 and 10 count columns from the right: mirror ours.
  input.centroid_x_px = pose.camera.width_px - centroid.u_px;
  input.centroid_y_px = centroid.v_px;
  input.width_px = pose.camera.width_px;
  input.height_px = pose.camera.height_px;
  input.hfov_deg = pose.camera.hfov_deg;
  input.vfov_deg = pose.camera.vfov_deg;
  input.gps_heading_deg = pose.heading_rad * common::kDegPerRad;
  input.frame_pitch_deg = -pose.pitch_rad * common::kDegPerRad;  // phi_f: nose down positive
  input.camera_mount_deg = -pose.camera.camera_pitch_deg;        // phi_c: depression
  input.height_m = pose.altitude_m;
  input.position = pose.position;
  return input;
}

}  // namespace fireswarm::agents
