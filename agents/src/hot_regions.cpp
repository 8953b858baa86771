#include "fireswarm/agents/hot_regions.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <utility>

namespace fireswarm::agents {
namespace {

constexpr int kGreyLevels = 256;
// Median absolute deviation -> sigma for Gaussian noise.
constexpr double kMadToSigma = 1.4826;

using Histogram = std::array<int, kGreyLevels>;

[[noreturn]] void Reject(std::string_view what, std::string_view field, double value,
                         std::string_view rule) {
  std::ostringstream message;
  message << what << ": " << field << " = " << value << " " << rule;
  throw std::invalid_argument(message.str());
}

void ValidateFrame(const CameraFrame& frame) {
  if (frame.width_px <= 0) Reject("camera frame", "width_px", frame.width_px, "must be > 0");
  if (frame.height_px <= 0) Reject("camera frame", "height_px", frame.height_px, "must be > 0");
  const auto expected =
      static_cast<std::size_t>(frame.width_px) * static_cast<std::size_t>(frame.height_px);
  if (frame.pixels.size() != expected) {
    Reject("camera frame", "pixels.size()", static_cast<double>(frame.pixels.size()),
           "must be width_px * height_px");
  }
  if (!std::isfinite(frame.range_min_c)) {
    Reject("camera frame", "range_min_c", frame.range_min_c, "must be finite");
  }
  if (!std::isfinite(frame.range_max_c) || !(frame.range_max_c > frame.range_min_c)) {
    Reject("camera frame", "range_max_c", frame.range_max_c, "must be finite and > range_min_c");
  }
}

// Kelvin per grey level and the temperature of a grey level (vehicle_io.hpp).
double KelvinPerGrey(const CameraFrame& frame) {
  return (frame.range_max_c - frame.range_min_c) / (kGreyLevels - 1);
}
double TemperatureOf(const CameraFrame& frame, int grey) {
  return frame.range_min_c + grey * KelvinPerGrey(frame);
}

Histogram HistogramOf(const CameraFrame& frame) {
  // Four partial histograms: on plain ground neighbouring pixels share a grey
  // level, and one table's increments would each wait for the one before (the
  // histogram of every frame is most of the detector's time).
  std::array<Histogram, 4> part{};
  const std::span<const std::uint8_t> pixels = frame.pixels;
  std::size_t i = 0;
  for (; i + 4 <= pixels.size(); i += 4) {
    ++part[0][pixels[i]];
    ++part[1][pixels[i + 1]];
    ++part[2][pixels[i + 2]];
    ++part[3][pixels[i + 3]];
  }
  for (; i < pixels.size(); ++i) ++part[0][pixels[i]];
  Histogram histogram{};
  for (std::size_t grey = 0; grey < histogram.size(); ++grey) {
    histogram[grey] = part[0][grey] + part[1][grey] + part[2][grey] + part[3][grey];
  }
  return histogram;
}

// The lower median: the smallest level with at least half the pixels at or below it.
int MedianGrey(const Histogram& histogram, int count) {
  const int half = (count + 1) / 2;
  int seen = 0;
  for (int grey = 0; grey < kGreyLevels; ++grey) {
    seen += histogram[static_cast<std::size_t>(grey)];
    if (seen >= half) return grey;
  }
  return kGreyLevels - 1;
}

// Median of |grey - median| in grey levels, from the same histogram.
int MadGrey(const Histogram& histogram, int count, int median) {
  const int half = (count + 1) / 2;
  int seen = histogram[static_cast<std::size_t>(median)];
  for (int d = 1; d < kGreyLevels; ++d) {
    if (seen >= half) return d - 1;
    if (median - d >= 0) seen += histogram[static_cast<std::size_t>(median - d)];
    if (median + d < kGreyLevels) seen += histogram[static_cast<std::size_t>(median + d)];
  }
  return kGreyLevels - 1;
}

// A saturated pixel reads the range top, which quantisation and float
// rounding may leave a fraction of a grey level under the sensor's limit.
double FireLevelC(const CameraFrame& frame, const DetectorConfig& config) {
  return std::min(config.min_fire_temperature_c, config.saturation_c - 0.5 * KelvinPerGrey(frame));
}

// Folds the pixels from `start` on, in whole blocks of kBlock, into the darkest
// and brightest grey level; returns where the blocks end. A loop of fixed length
// with scalar accumulators: GCC vectorises it at -O2 (its cheap cost model takes
// no loop of unknown length), and reduces the vectors once per block.
template <std::size_t kBlock>
std::size_t FoldGreyRange(std::span<const std::uint8_t> pixels, std::size_t start, std::uint8_t& lo,
                          std::uint8_t& hi) {
  std::size_t i = start;
  for (; i + kBlock <= pixels.size(); i += kBlock) {
    const std::uint8_t* block = pixels.data() + i;
    for (std::size_t k = 0; k < kBlock; ++k) {
      lo = std::min(lo, block[k]);
      hi = std::max(hi, block[k]);
    }
  }
  return i;
}

// The darkest and brightest grey level of the frame: long blocks first (a seed
// frame is six of them), short ones for the rest, then pixel by pixel.
std::pair<int, int> GreyRangeOf(std::span<const std::uint8_t> pixels) {
  std::uint8_t lo = 255;
  std::uint8_t hi = 0;
  std::size_t i = FoldGreyRange<1024>(pixels, 0, lo, hi);
  i = FoldGreyRange<64>(pixels, i, lo, hi);
  for (; i < pixels.size(); ++i) {
    lo = std::min(lo, pixels[i]);
    hi = std::max(hi, pixels[i]);
  }
  return {lo, hi};
}

// True when no pixel can be hot, whatever the histogram says: the background
// (the median) is at least the darkest pixel, so the relative threshold is at
// least min_excess_k above it; the brightest pixel reaching neither that nor
// the fire level leaves every pixel cold. Float rounding is monotonic, so this
// holds bit for bit against BackgroundOf's threshold. Plain ground, most
// frames, is settled here without the histogram.
bool SurelyCold(const CameraFrame& frame, const DetectorConfig& config) {
  const auto [min_grey, max_grey] = GreyRangeOf(frame.pixels);
  const double max_c = TemperatureOf(frame, max_grey);
  return max_c <= TemperatureOf(frame, min_grey) + config.min_excess_k &&
         max_c < FireLevelC(frame, config);
}

FrameBackground BackgroundOf(const CameraFrame& frame, const DetectorConfig& config,
                             const Histogram& histogram) {
  const int count = frame.width_px * frame.height_px;
  const int median = MedianGrey(histogram, count);
  FrameBackground background;
  background.background_c = TemperatureOf(frame, median);
  background.noise_k = kMadToSigma * MadGrey(histogram, count, median) * KelvinPerGrey(frame);
  background.hot_above_c = background.background_c +
                           std::max(config.noise_sigmas * background.noise_k, config.min_excess_k);
  background.fire_level_c = FireLevelC(frame, config);
  return background;
}

// Flood-fills the 8-connected hot region containing `start`, labelling it
// `label`; `stack` is scratch.
HotRegion FillRegion(const CameraFrame& frame, const std::array<bool, kGreyLevels>& hot, int start,
                     int label, std::vector<int>& labels, std::vector<int>& stack) {
  const int w = frame.width_px, h = frame.height_px;
  HotRegion region;
  region.min_col = region.max_col = start % w;
  region.min_row = region.max_row = start / w;
  double sum_col = 0.0, sum_row = 0.0;
  int peak_grey = 0;
  stack.clear();
  stack.push_back(start);
  labels[static_cast<std::size_t>(start)] = label;
  while (!stack.empty()) {
    const int index = stack.back();
    stack.pop_back();
    const int col = index % w, row = index / w;
    ++region.pixel_count;
    sum_col += col;
    sum_row += row;
    peak_grey = std::max<int>(peak_grey, frame.pixels[static_cast<std::size_t>(index)]);
    region.min_col = std::min(region.min_col, col);
    region.max_col = std::max(region.max_col, col);
    region.min_row = std::min(region.min_row, row);
    region.max_row = std::max(region.max_row, row);
    for (int dr = -1; dr <= 1; ++dr) {
      for (int dc = -1; dc <= 1; ++dc) {
        const int c = col + dc, r = row + dr;
        if (c < 0 || r < 0 || c >= w || r >= h) continue;
        const auto next = static_cast<std::size_t>(r * w + c);
        if (labels[next] != 0 || !hot[frame.pixels[next]]) continue;
        labels[next] = label;
        stack.push_back(static_cast<int>(next));
      }
    }
  }
  // Seed eq. 5-6 over pixel centres.
  region.centroid.u_px = sum_col / region.pixel_count + 0.5;
  region.centroid.v_px = sum_row / region.pixel_count + 0.5;
  region.peak_temperature_c = TemperatureOf(frame, peak_grey);
  return region;
}

}  // namespace

void DetectorConfig::Validate() const {
  constexpr std::string_view kWhat = "detector config";
  if (!(noise_sigmas >= 0.0) || !std::isfinite(noise_sigmas)) {
    Reject(kWhat, "noise_sigmas", noise_sigmas, "must be a finite number >= 0");
  }
  if (!(min_excess_k > 0.0) || !std::isfinite(min_excess_k)) {
    Reject(kWhat, "min_excess_k", min_excess_k, "must be a finite number > 0");
  }
  if (!std::isfinite(min_fire_temperature_c)) {
    Reject(kWhat, "min_fire_temperature_c", min_fire_temperature_c, "must be finite");
  }
  if (std::isnan(saturation_c)) Reject(kWhat, "saturation_c", saturation_c, "must not be NaN");
  if (min_region_px < 1) Reject(kWhat, "min_region_px", min_region_px, "must be >= 1");
}

DetectorConfig DetectorConfigFor(const common::CameraModel& model) {
  DetectorConfig config;
  config.saturation_c = model.max_scene_c;
  return config;
}

FrameBackground EstimateBackground(const CameraFrame& frame, const DetectorConfig& config) {
  ValidateFrame(frame);
  return BackgroundOf(frame, config, HistogramOf(frame));
}

std::vector<HotRegion> FindHotRegions(const CameraFrame& frame, const DetectorConfig& config) {
  ValidateFrame(frame);
  if (SurelyCold(frame, config)) return {};  // the usual frame: plain ground
  const Histogram histogram = HistogramOf(frame);
  const FrameBackground background = BackgroundOf(frame, config, histogram);

  // Hot or not is a property of the grey level: one table for the frame.
  std::array<bool, kGreyLevels> hot{};
  bool any_hot = false;
  for (int grey = 0; grey < kGreyLevels; ++grey) {
    const double t_c = TemperatureOf(frame, grey);
    hot[static_cast<std::size_t>(grey)] =
        t_c > background.hot_above_c || t_c >= background.fire_level_c;
    any_hot = any_hot || (hot[static_cast<std::size_t>(grey)] &&
                          histogram[static_cast<std::size_t>(grey)] > 0);
  }
  std::vector<HotRegion> regions;
  if (!any_hot) return regions;  // the usual frame: plain ground

  std::vector<int> labels(frame.pixels.size(), 0);
  std::vector<int> stack;
  int next_label = 1;
  for (std::size_t i = 0; i < frame.pixels.size(); ++i) {
    if (labels[i] != 0 || !hot[frame.pixels[i]]) continue;
    HotRegion region = FillRegion(frame, hot, static_cast<int>(i), next_label++, labels, stack);
    if (region.pixel_count < config.min_region_px) continue;
    region.is_fire = region.peak_temperature_c >= background.fire_level_c;
    regions.push_back(region);
  }
  return regions;
}

}  // namespace fireswarm::agents
