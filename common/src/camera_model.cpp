#include "fireswarm/common/camera_model.hpp"

#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>

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

}  // namespace fireswarm::common
