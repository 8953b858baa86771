#include "fireswarm/sim2d/temperature_field.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <string>

#include "temperature_polygon.hpp"

namespace fireswarm::sim2d {
namespace {

constexpr double kStefanBoltzmann = 5.670374419e-8;  // W m^-2 K^-4
constexpr double kZeroCelsiusK = 273.15;
constexpr int kDiscSides = 24;
// Footprints spanning at most this many cells are cut along grid lines.
constexpr std::size_t kMaxSplitCells = 16;

// A regular polygon with the disc's area (radius scaled up slightly), so
// covered fractions of a disc come out right on average.
std::vector<Vec2> DiscPolygon(const Distractor& d) {
  const double step = 2.0 * std::numbers::pi / kDiscSides;
  const double scale = std::sqrt(std::numbers::pi / (0.5 * kDiscSides * std::sin(step)));
  std::vector<Vec2> polygon;
  for (int i = 0; i < kDiscSides; ++i) {
    polygon.push_back(d.center_m +
                      d.radius_m * scale * Vec2(std::cos(i * step), std::sin(i * step)));
  }
  return polygon;
}

double Uniform(Rng& rng, double lo, double hi) {
  return lo + (hi - lo) * static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

}  // namespace

double RadianceFromC(double temperature_c) {
  const double kelvin = temperature_c + kZeroCelsiusK;
  const double k2 = kelvin * kelvin;
  return kStefanBoltzmann * k2 * k2;
}

double ApparentCFromRadiance(double radiance_wpm2) {
  return std::sqrt(std::sqrt(std::max(radiance_wpm2, 0.0) / kStefanBoltzmann)) - kZeroCelsiusK;
}

std::vector<Distractor> RandomDistractors(int count, const GroundBox& area, Rng& rng, double min_c,
                                          double max_c, double min_radius_m, double max_radius_m) {
  if (count < 0) throw std::invalid_argument("random distractors: count must be >= 0");
  if (!(max_c >= min_c)) throw std::invalid_argument("random distractors: max_c < min_c");
  if (!(min_radius_m > 0.0 && max_radius_m >= min_radius_m)) {
    throw std::invalid_argument("random distractors: need 0 < min_radius_m <= max_radius_m");
  }
  std::vector<Distractor> result;
  for (int i = 0; i < count; ++i) {
    Distractor d;
    d.center_m = Vec2(Uniform(rng, area.min_m.x(), area.max_m.x()),
                      Uniform(rng, area.min_m.y(), area.max_m.y()));
    d.radius_m = Uniform(rng, min_radius_m, max_radius_m);
    d.temperature_c = Uniform(rng, min_c, max_c);
    result.push_back(d);
  }
  return result;
}

TemperatureField::TemperatureField(const FireGrid& fire, std::vector<Distractor> distractors,
                                   double sky_c)
    : fire_(&fire), distractors_(std::move(distractors)), sky_c_(sky_c) {
  if (!std::isfinite(sky_c_))
    throw std::invalid_argument("temperature field: sky_c must be finite");
  for (std::size_t i = 0; i < distractors_.size(); ++i) {
    const Distractor& d = distractors_[i];
    const std::string name = "distractors[" + std::to_string(i) + "]";
    if (!d.center_m.allFinite()) throw std::invalid_argument(name + ".center_m must be finite");
    if (!std::isfinite(d.radius_m) || d.radius_m <= 0.0) {
      throw std::invalid_argument(name + ".radius_m = " + std::to_string(d.radius_m) +
                                  " must be > 0");
    }
    if (!std::isfinite(d.temperature_c) || d.temperature_c < -60.0 || d.temperature_c > 200.0) {
      throw std::invalid_argument(name + ".temperature_c = " + std::to_string(d.temperature_c) +
                                  " must be in [-60, 200] C");
    }
    const Vec2 r(d.radius_m * 1.05, d.radius_m * 1.05);  // covers the 24-gon's corners
    distractor_boxes_.push_back({d.center_m - r, d.center_m + r});
    distractor_polygons_.push_back(DiscPolygon(d));
  }
}

double TemperatureField::TemperatureAt(const Vec2& point_m) const {
  double t = ambient_c();
  if (const std::optional<CellIndex> cell = fire_->CellAt(point_m)) {
    t = fire_->CellTemperatureC(*cell);
  }
  for (const Distractor& d : distractors_) {
    if ((point_m - d.center_m).squaredNorm() <= d.radius_m * d.radius_m) {
      t = std::max(t, d.temperature_c);
    }
  }
  return t;
}

bool TemperatureField::AnyHotIn(const GroundBox& box) const {
  for (const GroundBox& b : distractor_boxes_) {
    if (box.Overlaps(b)) return true;
  }
  return fire_->AnyHotIn(box);
}

double TemperatureField::ApparentTemperatureOverC(const GroundQuad& quad) const {
  return ApparentCFromRadiance(MeanRadianceOver(quad));
}

double TemperatureField::CellExcessRadiance(CellIndex cell) const {
  const CellState state = fire_->StateAt(cell);
  if (state != CellState::kBurning && state != CellState::kCooling) return 0.0;
  return RadianceFromC(fire_->CellTemperatureC(cell)) - RadianceFromC(ambient_c());
}

double TemperatureField::MeanRadianceOver(const GroundQuad& quad) const {
  const double ambient = RadianceFromC(ambient_c());
  GroundQuad ccw = quad;
  double area = SignedAreaM2(ccw);
  if (area < 0.0) {
    std::reverse(ccw.begin(), ccw.end());
    area = -area;
  }
  if (area <= 0.0) return RadianceFromC(TemperatureAt(quad[0]));
  GroundBox box{quad[0], quad[0]};
  for (const Vec2& p : quad) {
    box.min_m = box.min_m.cwiseMin(p);
    box.max_m = box.max_m.cwiseMax(p);
  }
  double excess = 0.0;  // W/m^2 * m^2
  // A footprint over a few cells is cut along the grid lines (one split per
  // line); a large one clips each hot cell it may touch.
  std::array<CellOverlap, kMaxSplitCells> pieces;
  const double size = fire_->config().cell_size_m;
  const int n = SplitQuadIntoCells(ccw, fire_->config().origin_m, size, pieces.data(),
                                   static_cast<int>(pieces.size()));
  if (n >= 0) {
    for (int i = 0; i < n; ++i) {
      const CellOverlap& piece = pieces[static_cast<std::size_t>(i)];
      if (piece.col < 0 || piece.row < 0 || piece.col >= fire_->cols() ||
          piece.row >= fire_->rows()) {
        continue;
      }
      excess += piece.area_m2 * CellExcessRadiance({piece.col, piece.row});
    }
  } else {
    fire_->ForEachHotCellIn(box, [&](CellIndex cell) {
      const Vec2 lo = fire_->CellCenter(cell) - Vec2(0.5 * size, 0.5 * size);
      excess += QuadBoxOverlapAreaM2(ccw, lo, lo + Vec2(size, size)) * CellExcessRadiance(cell);
    });
  }
  for (std::size_t i = 0; i < distractors_.size(); ++i) {
    if (!box.Overlaps(distractor_boxes_[i])) continue;
    const double covered = OverlapAreaM2(distractor_polygons_[i], ccw);
    excess += covered * (RadianceFromC(distractors_[i].temperature_c) - ambient);
  }
  return ambient + excess / area;
}

}  // namespace fireswarm::sim2d
