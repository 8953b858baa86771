#include "coverage_raster.hpp"

#include <algorithm>
#include <boost/geometry.hpp>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>

#include "lanes.hpp"

namespace fireswarm::planner {
namespace bg = boost::geometry;

namespace {

constexpr double kTargetCells = 4e6;
constexpr double kMinCellM = 1.0;
constexpr double kCellsPerSweep = 10.0;

class Raster {
 public:
  Raster(const Box& box, double cell_m)
      : x0_(box.min_corner().x()),
        y0_(box.min_corner().y()),
        cell_m_(cell_m),
        nx_(CellsAlong(box.max_corner().x() - x0_)),
        ny_(CellsAlong(box.max_corner().y() - y0_)),
        bits_(nx_ * ny_, 0) {}

  std::size_t rows() const { return ny_; }
  double RowY(std::size_t j) const { return y0_ + (static_cast<double>(j) + 0.5) * cell_m_; }

  // Sets `bit` on the cells of row j whose centres lie in [a, b].
  void Mark(std::size_t j, double a, double b, std::uint8_t bit) {
    const double first = std::ceil((a - x0_) / cell_m_ - 0.5);
    const double last = std::floor((b - x0_) / cell_m_ - 0.5);
    if (last < 0.0 || first > static_cast<double>(nx_) - 1.0 || last < first) return;
    const auto i0 = static_cast<std::size_t>(std::max(first, 0.0));
    const auto i1 = static_cast<std::size_t>(std::min(last, static_cast<double>(nx_) - 1.0));
    for (std::size_t i = i0; i <= i1; ++i) bits_[j * nx_ + i] |= bit;
  }

  // Rows whose centres lie in [y_lo, y_hi], as [first, end).
  std::pair<std::size_t, std::size_t> Rows(double y_lo, double y_hi) const {
    const double first = std::max(0.0, std::ceil((y_lo - y0_) / cell_m_ - 0.5));
    const double last =
        std::min(static_cast<double>(ny_) - 1.0, std::floor((y_hi - y0_) / cell_m_ - 0.5));
    if (last < first) return {0, 0};
    return {static_cast<std::size_t>(first), static_cast<std::size_t>(last) + 1};
  }

  std::size_t Count(std::uint8_t mask) const {
    return static_cast<std::size_t>(std::count_if(
        bits_.begin(), bits_.end(), [mask](std::uint8_t b) { return (b & mask) == mask; }));
  }

 private:
  std::size_t CellsAlong(double extent_m) const {
    return static_cast<std::size_t>(std::max(1.0, std::ceil(extent_m / cell_m_)));
  }

  double x0_, y0_, cell_m_;
  std::size_t nx_, ny_;
  std::vector<std::uint8_t> bits_;
};

constexpr std::uint8_t kInsideBit = 1;
constexpr std::uint8_t kSeenBit = 2;

// Marks the slice of the capsule (segment a-b grown by r) on every row it spans.
void MarkCapsule(Raster& raster, Point a, Point b, double r) {
  const auto [first, end] = raster.Rows(std::min(a.y(), b.y()) - r, std::max(a.y(), b.y()) + r);
  const double dx = b.x() - a.x(), dy = b.y() - a.y();
  const double length = std::hypot(dx, dy);
  const double nx = length > 0 ? -dy / length * r : 0.0, ny = length > 0 ? dx / length * r : 0.0;
  for (std::size_t j = first; j < end; ++j) {
    const double y = raster.RowY(j);
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (const Point& c : {a, b}) {  // the end discs
      const double h = r * r - (y - c.y()) * (y - c.y());
      if (h < 0.0) continue;
      lo = std::min(lo, c.x() - std::sqrt(h));
      hi = std::max(hi, c.x() + std::sqrt(h));
    }
    for (const double side : {1.0, -1.0}) {  // the two sides, offset by r
      const double ay = a.y() + side * ny, by = b.y() + side * ny;
      if (ay == by || (y - ay) * (y - by) > 0.0) continue;
      const double t = (y - ay) / (by - ay);
      const double x = a.x() + side * nx + t * dx;
      lo = std::min(lo, x);
      hi = std::max(hi, x);
    }
    if (lo <= hi) raster.Mark(j, lo, hi, kSeenBit);
  }
}

}  // namespace

double CoverageFraction(const MultiPolygon& region, const std::vector<Path>& paths, double radius_m,
                        double cell_m) {
  if (region.empty()) return 1.0;
  Box box;
  bg::envelope(region, box);
  Raster raster(box, cell_m);
  for (std::size_t j = 0; j < raster.rows(); ++j) {
    for (const Polygon& polygon : region) {
      for (const auto& [a, b] : LineIntervals(polygon, raster.RowY(j)))
        raster.Mark(j, a, b, kInsideBit);
    }
  }
  for (const Path& path : paths) {
    for (std::size_t i = 0; i + 1 < path.size(); ++i)
      MarkCapsule(raster, path[i], path[i + 1], radius_m);
    if (path.size() == 1) MarkCapsule(raster, path[0], path[0], radius_m);
  }
  const std::size_t inside = raster.Count(kInsideBit);
  if (inside == 0) return 1.0;
  return static_cast<double>(raster.Count(kInsideBit | kSeenBit)) / static_cast<double>(inside);
}

double CoverageCellM(double region_area_m2, double sweep_width_m) {
  const double cell_m = std::sqrt(std::max(region_area_m2, 0.0) / kTargetCells);
  return std::clamp(cell_m, std::min(kMinCellM, sweep_width_m / kCellsPerSweep),
                    sweep_width_m / kCellsPerSweep);
}

}  // namespace fireswarm::planner
