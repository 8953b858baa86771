#include "fireswarm/common/camera_model.hpp"

#include <array>
#include <cmath>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>

#include "fireswarm/common/angles.hpp"

namespace fireswarm::common {
namespace {

// Vertical field of view of a sensor with square pixels, from its horizontal one.
double VfovFromHfovDeg(double hfov_deg, int width_px, int height_px) {
  const double half_h = hfov_deg * std::numbers::pi / 360.0;
  const double half_v = std::atan(std::tan(half_h) * height_px / width_px);
  return half_v * 360.0 / std::numbers::pi;
}

// Data sheets: Panasonic AMG8833 (Grid-EYE): 8x8, 60 deg both axes, 10 frames/s,
// temperature resolution 0.25 C, object range up to 80 C. FLIR Lepton 3.5:
// 160x120, 57 deg HFOV, < 50 mK NETD, 8.7 Hz (export rate), high-gain mode
// saturates at about 140 C. The seed camera (thesis Table 4.1 and section 7.3):
// 96x64 pixels, 75 x 60 deg; its rate and noise are not stated, so they follow
// the Lepton-class sensors the thesis compares it with.
const std::array<CameraModel, 3> kModels = {{
    {"seed", 96, 64, 75.0, 60.0, 9.0, 0.1, 150.0},
    {"amg8833", 8, 8, 60.0, 60.0, 10.0, 0.25, 80.0},
    {"lepton35", 160, 120, 57.0, VfovFromHfovDeg(57.0, 160, 120), 8.7, 0.05, 140.0},
}};

}  // namespace

std::span<const CameraModel> CameraModels() {
  return kModels;
}

const CameraModel* FindCameraModel(std::string_view name) {
  for (const CameraModel& model : kModels) {
    if (model.name == name) return &model;
  }
  return nullptr;
}

std::string CameraModelNames() {
  std::string names;
  for (const CameraModel& model : kModels) {
    if (!names.empty()) names += '|';
    names += model.name;
  }
  return names;
}

const CameraModel& CameraModelByName(std::string_view name) {
  if (const CameraModel* model = FindCameraModel(name)) return *model;
  throw std::invalid_argument("unknown camera model '" + std::string(name) +
                              "' (known: " + CameraModelNames() + ")");
}

double FootprintWidthM(const CameraModel& camera, double altitude_m, double pitch_deg) {
  if (!(altitude_m > 0.0) || !std::isfinite(altitude_m)) {
    throw std::invalid_argument("altitude_m must be > 0, got " + std::to_string(altitude_m));
  }
  if (!(pitch_deg >= -90.0 && pitch_deg < 0.0)) {
    throw std::invalid_argument(
        "camera_pitch_deg must be in [-90, 0) (down from the horizon), got " +
        std::to_string(pitch_deg));
  }
  const double depression_rad = DegToRad(-pitch_deg);
  const double tan_half_h = std::tan(DegToRad(camera.hfov_deg) / 2.0);
  const double tan_half_v = std::tan(DegToRad(camera.vfov_deg) / 2.0);
  // A ray through image row b (b = tan of its angle above the axis) meets the
  // ground at range h / (sin d - b cos d) along the axis; the near edge is b = -tan(vfov/2).
  const double near_edge_denominator =
      std::sin(depression_rad) + tan_half_v * std::cos(depression_rad);
  return 2.0 * altitude_m * tan_half_h / near_edge_denominator;
}

void ValidateCamera(const CameraModel& model, double camera_pitch_deg, std::string_view context) {
  const auto reject = [&](std::string_view field, double value, std::string_view rule) {
    std::ostringstream message;
    message << context << ": " << field << " = " << value << " " << rule;
    throw std::invalid_argument(message.str());
  };
  if (model.width_px <= 0) reject("width_px", model.width_px, "must be > 0");
  if (model.height_px <= 0) reject("height_px", model.height_px, "must be > 0");
  if (!(model.hfov_deg > 0.0 && model.hfov_deg < 180.0)) {
    reject("hfov_deg", model.hfov_deg, "must be in (0, 180)");
  }
  if (!(model.vfov_deg > 0.0 && model.vfov_deg < 180.0)) {
    reject("vfov_deg", model.vfov_deg, "must be in (0, 180)");
  }
  if (!(model.netd_k >= 0.0)) reject("netd_k", model.netd_k, "must be >= 0");
  if (!std::isfinite(model.max_scene_c)) reject("max_scene_c", model.max_scene_c, "must be finite");
  if (!(camera_pitch_deg >= -90.0 && camera_pitch_deg <= 0.0)) {
    reject("camera_pitch_deg", camera_pitch_deg, "must be in [-90, 0] (negative down)");
  }
}

}  // namespace fireswarm::common
