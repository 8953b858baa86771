// A thermal camera on a vehicle: pinhole geometry from pixel to ground and
// back, and a renderer that ray-casts every pixel's footprint onto the flat
// ground, integrates the temperature field's radiance over it, adds sensor
// noise (NETD) and maps the result to an 8-bit white-hot image.
//
// Geometry (docs/thermal_camera.md has a figure):
//  * Mount: `camera_pitch_deg` relative to the vehicle's level body, negative
//    down; -90 looks straight down (default), 0 looks forward. The camera's
//    optical axis lies in the vehicle's forward-down plane.
//  * Image: columns grow toward the vehicle's right; rows grow from the top,
//    and the top of the image is the vehicle's forward direction for a nadir
//    camera (the image's "up" is the axis turned 90 deg toward the nose-up side).
//  * Pixel coordinates are continuous: (u_px, v_px) = (0, 0) is the top-left
//    corner of the top-left pixel, pixel (col, row) covers [col, col+1) x
//    [row, row+1), and the optical axis passes through (width/2, height/2).
//  * Pinhole focal lengths from the full fields of view:
//    fx = (width/2) / tan(hfov/2), fy = (height/2) / tan(vfov/2). (The seed's
//    eq. 9 and 11 use a constant angle per pixel instead; the two agree at the
//    image centre and differ by a few pixels toward the edges.)
//  * Vehicle attitude as in vehicle_state.hpp: body FRD relative to NED, yaw
//    (heading) then pitch then roll; the world is local ENU over flat ground.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <span>
#include <vector>

#include "fireswarm/common/camera_model.hpp"
#include "fireswarm/sim2d/random.hpp"
#include "fireswarm/sim2d/temperature_field.hpp"
#include "fireswarm/sim2d/thermal_image.hpp"
#include "fireswarm/sim2d/vehicle_state.hpp"

namespace fireswarm::sim2d {

class NormalStream;  // private to sim2d (thermal_noise.hpp)

/// How the camera is fixed to the vehicle.
struct CameraMount {
  double camera_pitch_deg = -90.0;  ///< relative to the level body, negative down, in [-90, 0]
};

enum class GainMode {
  kFixed,  ///< fixed radiometric range [fixed_min_c, fixed_max_c]
  kAuto,   ///< automatic gain: the frame's coldest to hottest pixel
};

struct ThermalCameraOptions {
  GainMode gain = GainMode::kFixed;
  double fixed_min_c = 0.0;  ///< maps to grey 0 in kFixed
  /// Maps to grey 255 in kFixed; NaN (default) means the model's saturation temperature.
  double fixed_max_c = std::numeric_limits<double>::quiet_NaN();
  double agc_min_span_k = 2.0;     ///< kAuto never stretches less than this range
  double max_range_m = 3000.0;     ///< ground beyond this horizontal range reads ambient
  bool keep_temperatures = false;  ///< fill ThermalImage::apparent_temperature_c
};

/// A continuous image position, pixels from the image's top-left corner.
struct PixelCoord {
  double u_px = 0.0;  ///< along columns (vehicle right)
  double v_px = 0.0;  ///< along rows (down the image; forward is up for nadir)
  int col() const { return static_cast<int>(std::floor(u_px)); }
  int row() const { return static_cast<int>(std::floor(v_px)); }
};

class ThermalCamera {
 public:
  /// Throws std::invalid_argument naming the field ("camera_pitch_deg",
  /// "fixed_max_c", "max_range_m", ...) when the mount or options are bad, or the
  /// model's sizes or fields of view are not positive.
  ThermalCamera(const common::CameraModel& model, CameraMount mount = {},
                ThermalCameraOptions options = {});

  const common::CameraModel& model() const { return model_; }
  const CameraMount& mount() const { return mount_; }
  const ThermalCameraOptions& options() const { return options_; }
  double focal_x_px() const { return fx_px_; }
  double focal_y_px() const { return fy_px_; }

  /// Direction (not normalised) of the ray through image position (u_px, v_px), local ENU.
  Eigen::Vector3d RayEnu(const VehicleTruth& vehicle, double u_px, double v_px) const;
  /// Where the ray through (u_px, v_px) meets the ground; nullopt above the horizon.
  std::optional<Vec2> PixelToGround(const VehicleTruth& vehicle, double u_px, double v_px) const;
  /// The image position of a ground point (inverse of PixelToGround); nullopt when
  /// it is behind the camera or outside the image.
  std::optional<PixelCoord> GroundToPixel(const VehicleTruth& vehicle, const Vec2& point_m) const;

  /// Renders one frame at `capture_time_s` (the field shows the fire at its
  /// current time). Noise comes from `rng` (one draw per frame seeds a fast
  /// in-frame normal generator). Reuses `out`'s storage. Not const: the camera
  /// keeps scratch buffers between frames, so one camera serves one thread.
  void Render(const VehicleTruth& vehicle, const TemperatureField& field, double capture_time_s,
              Rng& rng, ThermalImage& out);
  ThermalImage Render(const VehicleTruth& vehicle, const TemperatureField& field,
                      double capture_time_s, Rng& rng);

 private:
  // The frame's ray basis: ray(u, v) = axis + (u - w/2) * per_u + (v - h/2) * per_v.
  struct RayBasis {
    Eigen::Vector3d axis, per_u, per_v, origin;
  };
  RayBasis BasisFor(const VehicleTruth& vehicle) const;
  // Fills temperatures_c_ with truth; returns true instead when all of it is ambient.
  bool RenderTruthTemperatures(const RayBasis& basis, const TemperatureField& field);
  // Fixed gain, plain ground at one temperature: the grey level of
  // ambient + NETD * z for every noise-table entry z. The level never falls as
  // z grows, so it is also `base` plus the number of `steps` (table-index
  // thresholds, one per level gained) that a pixel's index reaches.
  struct UniformGrey {
    std::vector<std::uint8_t> of_index;
    std::uint8_t base = 0;
    std::vector<std::uint16_t> steps;
  };
  const UniformGrey& UniformGreyFor(float ambient_c);
  void SenseUniformGround(const UniformGrey& grey, NormalStream& noise,
                          std::span<std::uint8_t> pixels);
  // Per-pixel rays: sky, horizon, and (when hot_in_view) radiance near hot things.
  void RenderNearHotThings(const RayBasis& basis, const TemperatureField& field, bool hot_in_view);

  common::CameraModel model_;
  CameraMount mount_;
  ThermalCameraOptions options_;
  double fx_px_ = 0.0;
  double fy_px_ = 0.0;
  Eigen::Vector3d axis_body_, right_body_, up_body_;  // camera axes in body FRD
  // Scratch, kept between frames to avoid allocations.
  std::vector<float> temperatures_c_;
  std::vector<Eigen::Vector2d> corner_ground_;
  std::vector<std::uint8_t> corner_kind_;
  HotCellMask hot_mask_;  // the frame's hot cells, rebuilt per frame with fire in view
  // For a frame of plain ground (fixed gain): 64 pixels' greys at a time.
  UniformGrey uniform_grey_;
  float uniform_grey_ambient_c_ = std::numeric_limits<float>::quiet_NaN();
};

}  // namespace fireswarm::sim2d
