// The thermal cameras fireswarm knows: what the simulator renders and what the
// planner sizes its sweep lanes by. One table, so the two never disagree.
#pragma once

#include <span>
#include <string>
#include <string_view>

namespace fireswarm::common {

/// A thermal camera's sensor and optics (square pixels, pinhole model).
struct CameraModel {
  std::string_view name;
  int width_px = 0;       ///< columns, along the horizontal field of view
  int height_px = 0;      ///< rows, along the vertical field of view
  double hfov_deg = 0.0;  ///< full horizontal field of view
  double vfov_deg = 0.0;  ///< full vertical field of view
  double frame_rate_hz = 0.0;
  double netd_k = 0.0;       ///< noise-equivalent temperature difference, kelvin (1 sigma)
  double max_scene_c = 0.0;  ///< hottest scene temperature the sensor reports before it saturates
};

/// Every known model: `seed` (the thesis' simulated camera, 96x64, 75x60 deg, seed
/// Table 4.1 and eq. 9-11), `amg8833` (Panasonic Grid-EYE, 8x8, 60x60 deg, 10 Hz)
/// and `lepton35` (FLIR Lepton 3.5, 160x120, 57 deg HFOV, 8.7 Hz).
std::span<const CameraModel> CameraModels();

/// The model called `name`, or nullptr when there is none.
const CameraModel* FindCameraModel(std::string_view name);

/// Looks `name` up; throws std::invalid_argument naming the known models when
/// there is no such camera.
const CameraModel& CameraModelByName(std::string_view name);

/// The known names joined by '|' ("seed|amg8833|lepton35"), for help and errors.
std::string CameraModelNames();

/// Checks a camera model and its mount pitch (degrees from the horizon, in [-90, 0],
/// -90 straight down). Throws std::invalid_argument "<context>: <field> = <value>
/// <rule>" naming the first bad field: width_px, height_px, hfov_deg, vfov_deg
/// (in (0, 180)), netd_k, max_scene_c or camera_pitch_deg.
void ValidateCamera(const CameraModel& model, double camera_pitch_deg, std::string_view context);

/// Across-track width in metres of the ground the camera sees, flying level at
/// `altitude_m` above flat ground with the camera mounted at `pitch_deg` from the
/// horizon (-90 = straight down, the image's horizontal axis across the track).
///
/// Nadir: 2 h tan(hfov / 2). Tilted: the pinhole image row that meets the ground
/// nearest the drone (the near edge) is the narrowest across the track, so its
/// width, 2 h tan(hfov / 2) / (sin d + tan(vfov / 2) cos d) with d = -pitch the
/// depression of the optical axis, is the width seen along the whole image; using
/// it keeps neighbouring lanes overlapping even at the near edge (conservative).
/// Throws std::invalid_argument naming `altitude_m` (not > 0) or
/// `camera_pitch_deg` (not in [-90, 0)).
double FootprintWidthM(const CameraModel& camera, double altitude_m, double pitch_deg);

}  // namespace fireswarm::common
