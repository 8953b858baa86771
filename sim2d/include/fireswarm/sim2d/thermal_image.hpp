// An 8-bit white-hot thermal image (seed section 4.3.1, Table 4.1: warmer is
// brighter, 0 = coldest of the range, 255 = hottest), the mapping from
// temperatures to grey levels, and binary PGM files for looking at images.
#pragma once

#include <algorithm>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace fireswarm::sim2d {

/// One camera frame. Row-major, row 0 at the top; for a nadir camera the top
/// of the image is the vehicle's forward direction and columns grow to its right.
struct ThermalImage {
  int width_px = 0;
  int height_px = 0;
  std::vector<std::uint8_t> pixels;  ///< width_px * height_px grey levels, white-hot
  double capture_time_s = 0.0;       ///< simulated time of the exposure
  /// The temperatures, Celsius, that grey 0 and 255 stand for in this frame (the
  /// fixed range, or this frame's automatic gain): grey g is
  /// range_min_c + g / 255 * (range_max_c - range_min_c), as a radiometric camera
  /// reports with every frame. Both 0 for a frame that did not come from a camera.
  double range_min_c = 0.0;
  double range_max_c = 0.0;
  /// Reported temperature per pixel (after noise and saturation), Celsius, same
  /// layout as `pixels`; empty unless the camera was asked to keep it (tests, scoring).
  std::vector<float> apparent_temperature_c;

  std::uint8_t At(int col, int row) const {
    return pixels[static_cast<std::size_t>(row) * static_cast<std::size_t>(width_px) +
                  static_cast<std::size_t>(col)];
  }
  float TemperatureC(int col, int row) const {
    return apparent_temperature_c[static_cast<std::size_t>(row) *
                                      static_cast<std::size_t>(width_px) +
                                  static_cast<std::size_t>(col)];
  }
};

/// The white-hot grey level of one temperature: (t - min_c) * scale rounded and
/// clamped to 0..255, where scale = 255 / (max_c - min_c).
inline std::uint8_t WhiteHotGrey(float temperature_c, float min_c, float scale) {
  const float grey = (temperature_c - min_c) * scale + 0.5F;
  return static_cast<std::uint8_t>(std::min(std::max(grey, 0.0F), 255.0F));
}

/// White-hot mapping: min_c -> 0, max_c -> 255, linear and rounded between,
/// clamped outside. Requires max_c > min_c and out.size() == temperatures_c.size().
void MapWhiteHot(std::span<const float> temperatures_c, double min_c, double max_c,
                 std::span<std::uint8_t> out);

/// Writes `image` as a binary PGM (P5, maxval 255). Throws std::runtime_error
/// naming the path when the file cannot be written.
void WritePgm(const std::string& path, const ThermalImage& image);

/// Reads a binary PGM (P5, maxval 255, '#' comments allowed) written by WritePgm
/// or another tool; capture time 0, no temperatures. Throws std::runtime_error
/// naming the path and the problem when the file is missing or not such a PGM.
ThermalImage ReadPgm(const std::string& path);

}  // namespace fireswarm::sim2d
