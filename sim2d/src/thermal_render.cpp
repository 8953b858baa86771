// ThermalCamera::Render: truth temperatures per pixel, then the sensor (noise,
// saturation, gain). "Render only what a camera can see": when the frame's
// ground footprint holds no hot cell or distractor, every pixel is ambient and
// no ray is cast per pixel; otherwise only pixels whose own footprint touches a
// hot thing integrate radiance over it.
#include <algorithm>
#include <cassert>
#include <cmath>
#include <span>
#include <utility>
#include <vector>

#include "fireswarm/sim2d/thermal_camera.hpp"
#include "thermal_noise.hpp"

namespace fireswarm::sim2d {
namespace {

enum CornerKind : std::uint8_t { kGround = 0, kFar = 1, kSky = 2 };

// A cooling cell whose temperature is within this fraction of the camera's
// NETD of ambient is not rendered on its own: a pixel it fills would read at
// most this many sigmas of noise warm (it still counts in pixels that other hot
// things send to the exact integral).
constexpr double kNegligibleNetdFraction = 0.05;

// Rays closer to horizontal than this (ENU z of the unnormalised ray) see sky.
constexpr double kMinDownRay = 1e-9;

CornerKind Classify(const Eigen::Vector3d& ray, const Eigen::Vector3d& origin, double max_range_m,
                    Eigen::Vector2d& ground_m) {
  if (ray.z() > -kMinDownRay) return kSky;
  const double t = origin.z() / -ray.z();
  ground_m = origin.head<2>() + t * ray.head<2>();
  return t * t * ray.head<2>().squaredNorm() > max_range_m * max_range_m ? kFar : kGround;
}

// Side of the square tiles of pixels that RenderNearHotThings clears at once.
constexpr int kTilePx = 8;

GroundBox BoxOf(const GroundQuad& quad) {
  GroundBox box{quad[0], quad[0]};
  for (const Vec2& p : quad) {
    box.min_m = box.min_m.cwiseMin(p);
    box.max_m = box.max_m.cwiseMax(p);
  }
  return box;
}

// The sensor, fused into one pass per pixel: truth + NETD noise (1 sigma), then
// saturation at the model's limit, then (fixed gain) the white-hot grey level.
template <typename TruthC>
void Sense(TruthC truth_c, float netd_k, float saturation_c, NormalStream& noise,
           std::span<float> temperatures_c) {
  for (std::size_t i = 0; i < temperatures_c.size(); ++i) {
    temperatures_c[i] = std::min(truth_c(i) + netd_k * noise.Next(), saturation_c);
  }
}

template <typename TruthC>
void SenseFixedGain(TruthC truth_c, float netd_k, float saturation_c, NormalStream& noise,
                    float min_c, float scale, std::span<float> temperatures_c,
                    std::span<std::uint8_t> pixels) {
  for (std::size_t i = 0; i < temperatures_c.size(); ++i) {
    const float t = std::min(truth_c(i) + netd_k * noise.Next(), saturation_c);
    temperatures_c[i] = t;
    pixels[i] = WhiteHotGrey(t, min_c, scale);
  }
}

// Automatic gain: the frame's coldest to hottest pixel, widened about its middle
// to at least min_span_k.
std::pair<double, double> AutoGainRangeC(std::span<const float> temperatures_c, double min_span_k) {
  const auto [lo, hi] = std::minmax_element(temperatures_c.begin(), temperatures_c.end());
  const double lo_c = *lo, hi_c = *hi;
  if (hi_c - lo_c >= min_span_k) return {lo_c, hi_c};
  const double mid_c = 0.5 * (lo_c + hi_c);
  return {mid_c - 0.5 * min_span_k, mid_c + 0.5 * min_span_k};
}

}  // namespace

const ThermalCamera::UniformGrey& ThermalCamera::UniformGreyFor(float ambient_c) {
  if (uniform_grey_ambient_c_ == ambient_c) return uniform_grey_;
  const float* z = NormalQuantileTable();
  const auto netd_k = static_cast<float>(model_.netd_k);
  const auto saturation_c = static_cast<float>(model_.max_scene_c);
  const auto min_c = static_cast<float>(options_.fixed_min_c);
  const auto scale = static_cast<float>(255.0 / (options_.fixed_max_c - options_.fixed_min_c));
  std::vector<std::uint8_t>& of_index = uniform_grey_.of_index;
  of_index.resize(NormalStream::kTableSize);
  for (std::size_t k = 0; k < of_index.size(); ++k) {
    of_index[k] = WhiteHotGrey(std::min(ambient_c + netd_k * z[k], saturation_c), min_c, scale);
  }
  uniform_grey_.base = of_index.front();
  uniform_grey_.steps.clear();
  for (std::size_t k = 1; k < of_index.size(); ++k) {
    assert(of_index[k] >= of_index[k - 1]);
    // Indices from k on select entry k or later: one step per level gained.
    for (int level = of_index[k - 1]; level < of_index[k]; ++level) {
      uniform_grey_.steps.push_back(static_cast<std::uint16_t>(k));
    }
  }
  uniform_grey_ambient_c_ = ambient_c;
  return uniform_grey_;
}

void ThermalCamera::SenseUniformGround(const UniformGrey& grey, NormalStream& noise,
                                       std::span<std::uint8_t> pixels) {
  if (grey.steps.size() > kMaxPlainGroundSteps) {
    for (std::uint8_t& pixel : pixels) pixel = grey.of_index[noise.NextIndex()];
    return;
  }
  FillPlainGround(grey.base, grey.steps, noise, pixels);
}

void ThermalCamera::Render(const VehicleTruth& vehicle, const TemperatureField& field,
                           double capture_time_s, Rng& rng, ThermalImage& out) {
  const std::size_t n =
      static_cast<std::size_t>(model_.width_px) * static_cast<std::size_t>(model_.height_px);
  temperatures_c_.resize(n);
  out.width_px = model_.width_px;
  out.height_px = model_.height_px;
  out.capture_time_s = capture_time_s;
  out.pixels.resize(n);
  // Uniform: every pixel sees ambient ground, temperatures_c_ was not written.
  const bool uniform = RenderTruthTemperatures(BasisFor(vehicle), field);
  const auto ambient_c = static_cast<float>(field.ambient_c());
  const auto uniform_truth = [ambient_c](std::size_t) { return ambient_c; };
  const auto pixel_truth = [this](std::size_t i) { return temperatures_c_[i]; };
  const auto netd_k = static_cast<float>(model_.netd_k);
  const auto saturation_c = static_cast<float>(model_.max_scene_c);
  NormalStream noise(rng);

  if (options_.gain == GainMode::kFixed) {
    const auto min_c = static_cast<float>(options_.fixed_min_c);
    const auto scale = static_cast<float>(255.0 / (options_.fixed_max_c - options_.fixed_min_c));
    out.range_min_c = options_.fixed_min_c;
    out.range_max_c = options_.fixed_max_c;
    if (uniform && !options_.keep_temperatures) {
      SenseUniformGround(UniformGreyFor(ambient_c), noise, out.pixels);
    } else if (uniform) {
      SenseFixedGain(uniform_truth, netd_k, saturation_c, noise, min_c, scale, temperatures_c_,
                     out.pixels);
    } else {
      SenseFixedGain(pixel_truth, netd_k, saturation_c, noise, min_c, scale, temperatures_c_,
                     out.pixels);
    }
  } else {
    if (uniform) {
      Sense(uniform_truth, netd_k, saturation_c, noise, temperatures_c_);
    } else {
      Sense(pixel_truth, netd_k, saturation_c, noise, temperatures_c_);
    }
    const auto [lo_c, hi_c] = AutoGainRangeC(temperatures_c_, options_.agc_min_span_k);
    MapWhiteHot(temperatures_c_, lo_c, hi_c, out.pixels);
    out.range_min_c = lo_c;
    out.range_max_c = hi_c;
  }
  if (options_.keep_temperatures) {
    out.apparent_temperature_c.assign(temperatures_c_.begin(), temperatures_c_.end());
  } else {
    out.apparent_temperature_c.clear();
  }
}

bool ThermalCamera::RenderTruthTemperatures(const RayBasis& basis, const TemperatureField& field) {
  const double half_w = 0.5 * model_.width_px;
  const double half_h = 0.5 * model_.height_px;
  // The frame's footprint is the quad of its four corner rays when all of them
  // meet the ground within range (the footprint is then convex and in range);
  // otherwise it lies within max_range_m of the camera.
  GroundBox box{basis.origin.head<2>(), basis.origin.head<2>()};
  bool all_ground = true;
  for (const double du : {-half_w, half_w}) {
    for (const double dv : {-half_h, half_h}) {
      Eigen::Vector2d p = basis.origin.head<2>();
      const Eigen::Vector3d ray = basis.axis + du * basis.per_u + dv * basis.per_v;
      all_ground = all_ground && Classify(ray, basis.origin, options_.max_range_m, p) == kGround;
      box.min_m = box.min_m.cwiseMin(p);
      box.max_m = box.max_m.cwiseMax(p);
    }
  }
  if (!all_ground) {
    const Vec2 range(options_.max_range_m, options_.max_range_m);
    box = {basis.origin.head<2>() - range, basis.origin.head<2>() + range};
  }
  // The coarse tile index first (cheap for frames far from fire), then the
  // frame's own hot cells; cooling cells warm by at most a small fraction of the
  // NETD (one sigma of noise) are left out, they cannot change what is seen.
  const bool hot_in_view =
      field.AnyHotIn(box) && hot_mask_.Build(field, box, kNegligibleNetdFraction * model_.netd_k);
  if (all_ground && !hot_in_view) return true;
  RenderNearHotThings(basis, field, hot_in_view);
  return false;
}

void ThermalCamera::RenderNearHotThings(const RayBasis& basis, const TemperatureField& field,
                                        bool hot_in_view) {
  const int w = model_.width_px;
  const int h = model_.height_px;
  const auto corners = static_cast<std::size_t>((w + 1) * (h + 1));
  corner_ground_.resize(corners);
  corner_kind_.resize(corners);
  const auto corner = [w](int r, int c) { return static_cast<std::size_t>(r * (w + 1) + c); };
  // Corners are classified only where needed (tile corners, then the corners of
  // tiles that are not cleared at once); the same expression everywhere, so a
  // corner shared by two tiles gets the same ground point.
  const auto classify = [&](int r, int c) {
    const std::size_t k = corner(r, c);
    const Eigen::Vector3d ray =
        basis.axis + (r - 0.5 * h) * basis.per_v + (c - 0.5 * w) * basis.per_u;
    corner_kind_[k] = Classify(ray, basis.origin, options_.max_range_m, corner_ground_[k]);
  };
  const double ambient_c = field.ambient_c();
  const double ambient_w = RadianceFromC(ambient_c);
  const double sky_w = RadianceFromC(field.sky_c());
  const auto pixel_c = [&](int r, int c) {
    const std::size_t k[4] = {corner(r, c), corner(r, c + 1), corner(r + 1, c + 1),
                              corner(r + 1, c)};
    int sky = 0, ground = 0;
    for (const std::size_t i : k) {
      sky += corner_kind_[i] == kSky ? 1 : 0;
      ground += corner_kind_[i] == kGround ? 1 : 0;
    }
    if (ground == 4 && hot_in_view) {
      const GroundQuad quad = {corner_ground_[k[0]], corner_ground_[k[1]], corner_ground_[k[2]],
                               corner_ground_[k[3]]};
      if (hot_mask_.AnyIn(BoxOf(quad))) return field.ApparentTemperatureOverC(quad);
    } else if (sky > 0) {
      // A pixel across the horizon: sky for the share of its corners above it,
      // far (ambient) ground for the rest.
      const double f = sky / 4.0;
      return ApparentCFromRadiance(f * sky_w + (1.0 - f) * ambient_w);
    }
    return ambient_c;
  };
  // Tiles of pixels: when a tile's four outer corners meet the ground, its
  // footprint is their convex quad (a plane maps lines to lines) and every
  // inner corner is ground too, so one mask lookup clears a tile far from fire.
  for (int r0 = 0; r0 < h; r0 += kTilePx) {
    const int r1 = std::min(r0 + kTilePx, h);
    for (int c0 = 0; c0 < w; c0 += kTilePx) {
      const int c1 = std::min(c0 + kTilePx, w);
      for (const int r : {r0, r1}) {
        for (const int c : {c0, c1}) classify(r, c);
      }
      const std::size_t k[4] = {corner(r0, c0), corner(r0, c1), corner(r1, c1), corner(r1, c0)};
      bool tile_cold = hot_in_view;
      for (const std::size_t i : k) tile_cold = tile_cold && corner_kind_[i] == kGround;
      tile_cold =
          tile_cold && !hot_mask_.AnyIn(BoxOf({corner_ground_[k[0]], corner_ground_[k[1]],
                                               corner_ground_[k[2]], corner_ground_[k[3]]}));
      for (int r = r0; r <= r1 && !tile_cold; ++r) {
        for (int c = c0; c <= c1; ++c) classify(r, c);
      }
      for (int r = r0; r < r1; ++r) {
        float* row = temperatures_c_.data() + static_cast<std::size_t>(r * w);
        for (int c = c0; c < c1; ++c) {
          row[c] = static_cast<float>(tile_cold ? ambient_c : pixel_c(r, c));
        }
      }
    }
  }
}

}  // namespace fireswarm::sim2d
