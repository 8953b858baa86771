// The SVG map's arithmetic (see svg_geometry.hpp).
#include "svg_geometry.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>

#include "fireswarm/common/angles.hpp"
#include "fireswarm/run/scenario.hpp"
#include "xml_text.hpp"

namespace fireswarm::run::internal {
namespace {

constexpr double kHalfTurnDeg = 180.0;
constexpr double kQuarterTurnDeg = 90.0;
constexpr double kMetresPerKm = 1'000.0;

double Distance(Px a, Px b) {
  return std::hypot(a.x - b.x, a.y - b.y);
}

double DistanceToSegment(Px p, Px a, Px b) {
  const double dx = b.x - a.x;
  const double dy = b.y - a.y;
  const double length2 = dx * dx + dy * dy;
  if (length2 == 0.0) return Distance(p, a);
  const double t = std::clamp(((p.x - a.x) * dx + (p.y - a.y) * dy) / length2, 0.0, 1.0);
  return Distance(p, Px{a.x + t * dx, a.y + t * dy});
}

// "#rrggbb" of hue (deg), saturation and lightness (0..1), the CSS HSL model.
std::string HslHex(double hue_deg, double saturation, double lightness) {
  constexpr double kSectorDeg = 60.0;
  constexpr double kFullByte = 255.0;
  const double chroma = (1.0 - std::abs(2.0 * lightness - 1.0)) * saturation;
  const double sector = hue_deg / kSectorDeg;
  const double second = chroma * (1.0 - std::abs(std::fmod(sector, 2.0) - 1.0));
  std::array<double, 3> rgb{};
  switch (static_cast<int>(sector) % 6) {
    case 0:
      rgb = {chroma, second, 0.0};
      break;
    case 1:
      rgb = {second, chroma, 0.0};
      break;
    case 2:
      rgb = {0.0, chroma, second};
      break;
    case 3:
      rgb = {0.0, second, chroma};
      break;
    case 4:
      rgb = {second, 0.0, chroma};
      break;
    default:
      rgb = {chroma, 0.0, second};
      break;
  }
  constexpr std::string_view kHexDigits = "0123456789abcdef";
  std::string hex = "#";
  for (const double channel : rgb) {
    const auto byte = static_cast<unsigned>(
        std::lround(std::clamp(channel + lightness - chroma / 2.0, 0.0, 1.0) * kFullByte));
    hex += kHexDigits[byte / 16];
    hex += kHexDigits[byte % 16];
  }
  return hex;
}

}  // namespace

void Bounds::Add(common::EastNorth point) {
  if (empty) {
    min_east_m = max_east_m = point.east_m;
    min_north_m = max_north_m = point.north_m;
    empty = false;
    return;
  }
  min_east_m = std::min(min_east_m, point.east_m);
  max_east_m = std::max(max_east_m, point.east_m);
  min_north_m = std::min(min_north_m, point.north_m);
  max_north_m = std::max(max_north_m, point.north_m);
}

MapView FitView(Bounds bounds, double min_extent_m, double padding_fraction, double max_width_px,
                double max_height_px, Px top_left) {
  if (bounds.empty) bounds.Add({0.0, 0.0});
  const double centre_east_m = (bounds.min_east_m + bounds.max_east_m) / 2.0;
  const double centre_north_m = (bounds.min_north_m + bounds.max_north_m) / 2.0;
  double width_m = std::max(bounds.max_east_m - bounds.min_east_m, min_extent_m);
  double height_m = std::max(bounds.max_north_m - bounds.min_north_m, min_extent_m);
  const double padding_m = padding_fraction * std::max(width_m, height_m);
  width_m += 2.0 * padding_m;
  height_m += 2.0 * padding_m;
  MapView view;
  view.px_per_m = std::min(max_width_px / width_m, max_height_px / height_m);
  view.west_m = centre_east_m - width_m / 2.0;
  view.north_m = centre_north_m + height_m / 2.0;
  view.top_left = top_left;
  view.width_px = width_m * view.px_per_m;
  view.height_px = height_m * view.px_per_m;
  return view;
}

std::vector<Px> ThinPolyline(const std::vector<Px>& points, double min_step_px,
                             double max_deviation_px) {
  std::vector<Px> spaced;
  for (const Px& point : points) {
    if (spaced.empty() || Distance(point, spaced.back()) >= min_step_px) spaced.push_back(point);
  }
  // The last point stays: where the drone ended matters more than one pixel.
  if (!points.empty() && spaced.size() > 1 && Distance(points.back(), spaced.back()) > 0.0) {
    spaced.back() = points.back();
  }
  if (spaced.size() < 3) return spaced;

  // Douglas-Peucker with an explicit stack: a day-long track must not recurse deep.
  std::vector<bool> keep(spaced.size(), false);
  keep.front() = true;
  keep.back() = true;
  std::vector<std::pair<std::size_t, std::size_t>> spans{{0, spaced.size() - 1}};
  while (!spans.empty()) {
    const auto [first, last] = spans.back();
    spans.pop_back();
    double worst_px = 0.0;
    std::size_t worst = first;
    for (std::size_t i = first + 1; i < last; ++i) {
      const double deviation_px = DistanceToSegment(spaced[i], spaced[first], spaced[last]);
      if (deviation_px > worst_px) {
        worst_px = deviation_px;
        worst = i;
      }
    }
    if (worst_px > max_deviation_px) {
      keep[worst] = true;
      spans.emplace_back(first, worst);
      spans.emplace_back(worst, last);
    }
  }
  std::vector<Px> thinned;
  for (std::size_t i = 0; i < spaced.size(); ++i) {
    if (keep[i]) thinned.push_back(spaced[i]);
  }
  return thinned;
}

std::optional<EllipsePx> CovarianceEllipse(const std::array<double, 3>& covariance_ne_m2,
                                           double sigmas, double px_per_m) {
  const auto [nn, ne, ee] = covariance_ne_m2;
  // On the picture x is east and y is south, so the north-east covariance changes
  // sign: [[ee, -ne], [-ne, nn]].
  Eigen::Matrix2d covariance_xy;
  covariance_xy << ee, -ne, -ne, nn;
  if (!covariance_xy.allFinite()) return std::nullopt;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(covariance_xy);
  if (solver.info() != Eigen::Success) return std::nullopt;
  const Eigen::Vector2d variances = solver.eigenvalues();  // ascending
  // A covariance is positive semidefinite; a small negative eigenvalue is rounding.
  constexpr double kRelativeRounding = 1e-9;
  const double rounding = kRelativeRounding * std::max(1.0, std::abs(variances(1)));
  if (variances(0) < -rounding) return std::nullopt;
  const Eigen::Vector2d major = solver.eigenvectors().col(1);
  // An eigenvector's sign is arbitrary; fold the angle into (-90, 90].
  // A circle has no major axis: any eigenvector will do, so none is written.
  const bool circle = variances(1) - variances(0) <= rounding;
  double rotate_deg = circle ? 0.0 : std::atan2(major.y(), major.x()) * common::kDegPerRad;
  if (rotate_deg <= -kQuarterTurnDeg) rotate_deg += kHalfTurnDeg;
  if (rotate_deg > kQuarterTurnDeg) rotate_deg -= kHalfTurnDeg;
  return EllipsePx{sigmas * std::sqrt(std::max(variances(1), 0.0)) * px_per_m,
                   sigmas * std::sqrt(std::max(variances(0), 0.0)) * px_per_m, rotate_deg};
}

double ScaleBarLengthM(double max_m) {
  const double decade = std::pow(10.0, std::floor(std::log10(max_m)));
  for (const double step : {5.0, 2.0}) {
    if (step * decade <= max_m) return step * decade;
  }
  return decade;
}

std::string LengthLabel(double length_m) {
  if (length_m >= kMetresPerKm) return ShortNumber(length_m / kMetresPerKm) + " km";
  return ShortNumber(length_m) + " m";
}

std::string DroneColour(int receiver_id) {
  // Tableau 10 without its red (fire) and pink (close to the false tracks' magenta),
  // then four darker or stronger ones that stay apart from those.
  static constexpr std::array<std::string_view, 12> kPalette{
      "#1f77b4", "#ff7f0e", "#2ca02c", "#9467bd", "#8c564b", "#bcbd22",
      "#17becf", "#7f7f7f", "#393b79", "#e6ab02", "#008080", "#637939"};
  const int index = std::max(receiver_id - kMinReceiverId, 0);
  if (static_cast<std::size_t>(index) < kPalette.size()) {
    return std::string(kPalette[static_cast<std::size_t>(index)]);
  }
  // Hues a golden angle apart never repeat; two lightnesses in turn part neighbours.
  constexpr double kGoldenAngleDeg = 137.50776405;
  constexpr double kFullTurnDeg = 360.0;
  constexpr double kSaturation = 0.7;
  constexpr double kDarkLightness = 0.38;
  constexpr double kLightLightness = 0.52;
  const double hue_deg = std::fmod(index * kGoldenAngleDeg, kFullTurnDeg);
  return HslHex(hue_deg, kSaturation, index % 2 == 0 ? kDarkLightness : kLightLightness);
}

}  // namespace fireswarm::run::internal
