// The ground temperature the thermal cameras see: ambient ground, the fire
// grid's burning and cooling cells, and hot non-fire distractors (sun-heated
// rock, 40-70 C) that a detector must not report as fire. Besides a point
// query it integrates radiance over a pixel's ground footprint, so a small fire
// far away warms a pixel only partially.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "fireswarm/sim2d/fire_grid.hpp"
#include "fireswarm/sim2d/random.hpp"

namespace fireswarm::sim2d {

/// A hot patch that is not fire: a disc of ground at a fixed temperature.
struct Distractor {
  Vec2 center_m = Vec2::Zero();  ///< local ENU
  double radius_m = 5.0;
  double temperature_c = 55.0;
};

/// `count` distractors with centres uniform in `area`, radii uniform in
/// [min_radius_m, max_radius_m] and temperatures uniform in [min_c, max_c]
/// (default 40-70 C, sun-heated rock). Throws std::invalid_argument on bad ranges.
std::vector<Distractor> RandomDistractors(int count, const GroundBox& area, Rng& rng,
                                          double min_c = 40.0, double max_c = 70.0,
                                          double min_radius_m = 2.0, double max_radius_m = 8.0);

/// Stefan-Boltzmann exitance of a black body at `temperature_c`, W/m^2.
double RadianceFromC(double temperature_c);
/// The black-body temperature, Celsius, whose exitance is `radiance_wpm2` (inverse of
/// RadianceFromC).
double ApparentCFromRadiance(double radiance_wpm2);

/// A convex quadrilateral on the ground (a pixel's footprint), either winding.
using GroundQuad = std::array<Vec2, 4>;

class TemperatureField {
 public:
  /// Keeps a reference to `fire` (which must outlive the field). Ambient comes
  /// from the fire's config; `sky_c` is what a ray above the horizon reads.
  /// Throws std::invalid_argument naming "distractors[i].radius_m" or
  /// ".temperature_c" for a non-positive radius or a non-finite temperature,
  /// and "sky_c" when it is not finite.
  TemperatureField(const FireGrid& fire, std::vector<Distractor> distractors, double sky_c = -20.0);

  double ambient_c() const { return fire_->config().ambient_c; }
  double sky_c() const { return sky_c_; }
  const FireGrid& fire() const { return *fire_; }
  std::span<const Distractor> distractors() const { return distractors_; }

  /// Temperature of the ground at `point_m` at the fire's current time, Celsius.
  double TemperatureAt(const Vec2& point_m) const;
  /// False when certainly nothing but ambient ground lies in `box` (cheap).
  bool AnyHotIn(const GroundBox& box) const;
  /// Mean black-body exitance over `quad`, W/m^2: ambient plus, for each hot
  /// cell and distractor, its excess exitance times the fraction of the quad it
  /// covers (exact polygon overlap; distractor discs as area-preserving 24-gons;
  /// distractors overlapping fire add, they are assumed apart).
  double MeanRadianceOver(const GroundQuad& quad) const;
  /// The black-body temperature, Celsius, of MeanRadianceOver(quad).
  double ApparentTemperatureOverC(const GroundQuad& quad) const;

 private:
  // Exitance of a cell above ambient, W/m^2 (0 for unburned or cold cells).
  double CellExcessRadiance(CellIndex cell) const;

  const FireGrid* fire_;
  std::vector<Distractor> distractors_;
  std::vector<GroundBox> distractor_boxes_;
  std::vector<std::vector<Vec2>> distractor_polygons_;
  double sky_c_;
};

/// Where in one box (a camera frame's ground footprint) something hot enough
/// to see lies, at the fire grid's cell resolution: built once per frame, it
/// lets each pixel ask exactly (to a cell) and in O(1) whether anything hot
/// touches its footprint, where TemperatureField::AnyHotIn answers per 80 m
/// tile and sends whole neighbourhoods of a small fire to the exact integral.
class HotCellMask {
 public:
  /// Marks every cell of the fire grid's lattice (extended beyond the grid for
  /// distractors) inside `box` that holds a burning cell, a cooling cell more
  /// than `negligible_k` kelvin above ambient, or part of a distractor's
  /// bounding box. Returns false when it marked none. Reuses its storage.
  bool Build(const TemperatureField& field, const GroundBox& box, double negligible_k);
  /// True when `box` touches a marked cell (closed squares). False means only
  /// ambient ground and cells at most `negligible_k` warm lie in `box`.
  bool AnyIn(const GroundBox& box) const;

 private:
  struct CellRect {
    int col_lo, row_lo, col_hi, row_hi;  // inclusive, fire-grid lattice indices
  };
  int ColOf(double x_m) const;
  int RowOf(double y_m) const;

  Vec2 origin_m_ = Vec2::Zero();
  double per_cell_m_ = 1.0;  // 1 / cell size, 1/m
  // Marked extent: lattice cells [col0_, col0_ + cols_) x [row0_, row0_ + rows_).
  int col0_ = 0, row0_ = 0, cols_ = 0, rows_ = 0;
  std::vector<CellRect> rects_;
  // Summed-area table of marked cells, (cols_ + 1) x (rows_ + 1), row-major.
  std::vector<std::uint32_t> sums_;
};

}  // namespace fireswarm::sim2d
