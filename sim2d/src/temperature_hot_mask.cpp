// HotCellMask: the frame's hot cells and distractor boxes on the fire grid's
// lattice, as a summed-area table so a pixel's box is one four-term lookup.
#include <algorithm>
#include <cmath>
#include <limits>

#include "fireswarm/sim2d/temperature_field.hpp"

namespace fireswarm::sim2d {
namespace {

// Lattice index of a coordinate, clamped far enough out that int conversion is safe.
// (Multiplying by the inverse cell size may move a point on a grid line to the
// neighbouring cell: the answer is then off by a zero-area touch.)
int LatticeIndex(double coordinate_m, double origin_m, double per_cell_m) {
  constexpr double kLimit = 1e9;
  return static_cast<int>(
      std::clamp(std::floor((coordinate_m - origin_m) * per_cell_m), -kLimit, kLimit));
}

}  // namespace

int HotCellMask::ColOf(double x_m) const {
  return LatticeIndex(x_m, origin_m_.x(), per_cell_m_);
}
int HotCellMask::RowOf(double y_m) const {
  return LatticeIndex(y_m, origin_m_.y(), per_cell_m_);
}

bool HotCellMask::Build(const TemperatureField& field, const GroundBox& box, double negligible_k) {
  const FireGrid& fire = field.fire();
  origin_m_ = fire.config().origin_m;
  per_cell_m_ = 1.0 / fire.config().cell_size_m;
  rects_.clear();
  const double ambient_c = field.ambient_c();
  fire.ForEachHotCellIn(box, [&](CellIndex cell) {
    if (fire.StateAt(cell) == CellState::kCooling &&
        fire.CellTemperatureC(cell) - ambient_c <= negligible_k) {
      return;
    }
    rects_.push_back({cell.col, cell.row, cell.col, cell.row});
  });
  const std::span<const Distractor> distractors = field.distractors();
  for (const Distractor& d : distractors) {
    // The field's own conservative box around the disc's 24-gon.
    const Vec2 r(d.radius_m * 1.05, d.radius_m * 1.05);
    const GroundBox disc{d.center_m - r, d.center_m + r};
    if (!disc.Overlaps(box)) continue;
    const Vec2 lo = disc.min_m.cwiseMax(box.min_m);
    const Vec2 hi = disc.max_m.cwiseMin(box.max_m);
    rects_.push_back({ColOf(lo.x()), RowOf(lo.y()), ColOf(hi.x()), RowOf(hi.y())});
  }
  cols_ = rows_ = 0;
  sums_.clear();
  if (rects_.empty()) return false;
  int col_hi = std::numeric_limits<int>::min(), row_hi = std::numeric_limits<int>::min();
  col0_ = row0_ = std::numeric_limits<int>::max();
  for (const CellRect& rect : rects_) {
    col0_ = std::min(col0_, rect.col_lo);
    row0_ = std::min(row0_, rect.row_lo);
    col_hi = std::max(col_hi, rect.col_hi);
    row_hi = std::max(row_hi, rect.row_hi);
  }
  cols_ = col_hi - col0_ + 1;
  rows_ = row_hi - row0_ + 1;
  const auto stride = static_cast<std::size_t>(cols_) + 1;
  sums_.assign(stride * (static_cast<std::size_t>(rows_) + 1), 0);
  // Occupancy first (at offset +1, +1), then prefix sums in place.
  for (const CellRect& rect : rects_) {
    for (int row = rect.row_lo; row <= rect.row_hi; ++row) {
      std::uint32_t* line = sums_.data() + static_cast<std::size_t>(row - row0_ + 1) * stride + 1;
      for (int col = rect.col_lo; col <= rect.col_hi; ++col) line[col - col0_] = 1;
    }
  }
  for (std::size_t row = 1; row <= static_cast<std::size_t>(rows_); ++row) {
    std::uint32_t running = 0;
    for (std::size_t col = 1; col < stride; ++col) {
      running += sums_[row * stride + col];
      sums_[row * stride + col] = running + sums_[(row - 1) * stride + col];
    }
  }
  return true;
}

bool HotCellMask::AnyIn(const GroundBox& box) const {
  if (cols_ == 0) return false;
  const int c0 = std::max(ColOf(box.min_m.x()), col0_) - col0_;
  const int c1 = std::min(ColOf(box.max_m.x()), col0_ + cols_ - 1) - col0_;
  const int r0 = std::max(RowOf(box.min_m.y()), row0_) - row0_;
  const int r1 = std::min(RowOf(box.max_m.y()), row0_ + rows_ - 1) - row0_;
  if (c0 > c1 || r0 > r1) return false;
  const auto stride = static_cast<std::size_t>(cols_) + 1;
  const auto at = [&](int row, int col) {
    return sums_[static_cast<std::size_t>(row) * stride + static_cast<std::size_t>(col)];
  };
  return at(r1 + 1, c1 + 1) - at(r0, c1 + 1) - at(r1 + 1, c0) + at(r0, c0) != 0;
}

}  // namespace fireswarm::sim2d
