// The seed's thermal fire detector, per frame (seed section 7.3): threshold the
// white-hot image, label the connected hot regions, and take each region's
// centroid (seed eq. 5-6). Going beyond the seed's fixed threshold, "hot" is
// relative to the frame's own background, so the same detector works with a
// fixed radiometric range and with automatic gain; a region is fire only when
// its hottest pixel is fire-hot, which rejects sun-heated rock.
#pragma once

#include <limits>
#include <vector>

#include "fireswarm/agents/geolocation.hpp"
#include "fireswarm/agents/vehicle_io.hpp"
#include "fireswarm/common/camera_model.hpp"

namespace fireswarm::agents {

/// How pixels are classed hot and regions fire.
///
/// The background is the frame's median temperature and its noise 1.4826 times
/// the median absolute deviation (a robust sigma: fire and rock do not move
/// either while they cover less than half the frame). A pixel is hot when it
/// reads above background + max(noise_sigmas * noise, min_excess_k), or at or
/// above the fire level min(min_fire_temperature_c, saturation_c): a pixel that
/// hot is hot whatever the background, which keeps a fire that fills most of
/// the frame (and so raises the median) or saturates the sensor detected.
struct DetectorConfig {
  double noise_sigmas = 5.0;  ///< k: threshold above the background in robust sigmas
  /// Floor of the threshold above the background, kelvin: under automatic gain
  /// plain-ground noise is stretched over the whole grey range, and this keeps it
  /// from ever passing (sensor noise is ~0.1 K, sun-heated rock 15-45 K).
  double min_excess_k = 10.0;
  /// A region is fire when its hottest pixel reaches the fire level: flames read
  /// ~700 C and embers ~300 C (sim2d defaults), sun-heated rock 40-70 C.
  double min_fire_temperature_c = 150.0;
  /// The temperature at which the sensor saturates (common::CameraModel::max_scene_c),
  /// or +inf when unknown. A camera that saturates below min_fire_temperature_c
  /// (AMG8833 at 80 C, Lepton at 140 C) shows a fire as saturated pixels: these
  /// count as fire-hot.
  double saturation_c = std::numeric_limits<double>::infinity();
  int min_region_px = 1;  ///< smaller regions are dropped

  /// Throws std::invalid_argument naming the first bad field.
  void Validate() const;
};

/// The defaults with the saturation of `model` (its max_scene_c).
DetectorConfig DetectorConfigFor(const common::CameraModel& model);

/// One 8-connected region of hot pixels.
struct HotRegion {
  /// Seed eq. 5-6: the unweighted mean of the pixel centres (col + 0.5, row + 0.5),
  /// the continuous coordinates of geolocation.hpp. Unweighted, so saturated
  /// pixels (which all read the same) do not pull it.
  ImagePoint centroid;
  int pixel_count = 0;
  double peak_temperature_c = 0.0;  ///< hottest pixel (a saturated one reads the range top)
  int min_col = 0, min_row = 0;     ///< bounding box, inclusive
  int max_col = 0, max_row = 0;
  bool is_fire = false;  ///< peak_temperature_c reaches the fire level
};

/// What the frame's background looked like, for tests and diagnostics.
struct FrameBackground {
  double background_c = 0.0;  ///< median pixel temperature
  double noise_k = 0.0;       ///< robust sigma (1.4826 MAD), kelvin
  double hot_above_c = 0.0;   ///< relative threshold: hotter pixels are hot
  double fire_level_c = 0.0;  ///< pixels at or above are hot and fire-hot
};

/// The background statistics and thresholds of `frame` under `config`.
/// Throws std::invalid_argument when the frame is malformed (see FindHotRegions).
FrameBackground EstimateBackground(const CameraFrame& frame, const DetectorConfig& config);

/// Every hot region of `frame` with at least config.min_region_px pixels, in
/// raster order of their first pixel. Throws std::invalid_argument naming the
/// field when the frame's size does not match its pixels or its range is not
/// finite and increasing (range_max_c > range_min_c).
std::vector<HotRegion> FindHotRegions(const CameraFrame& frame, const DetectorConfig& config);

}  // namespace fireswarm::agents
