// The coverage raster (coverage_grid.hpp): searchable cells, and the camera
// footprint's cells marked seen.
#include "fireswarm/planner/coverage_grid.hpp"

#include <algorithm>
#include <boost/geometry.hpp>
#include <cmath>
#include <limits>

#include "fireswarm/common/angles.hpp"

namespace fireswarm::planner {
namespace {

namespace bg = boost::geometry;

constexpr std::uint8_t kOutside = 0;
constexpr std::uint8_t kUnseen = 1;
constexpr std::uint8_t kSeen = 2;
// Mark: a footprint edge this near parallel to the rows (|sin| or |cos| of the
// heading) bounds no row's span; the cell test alone decides.
constexpr double kFlatSlope = 1e-6;

using Ring = Polygon::ring_type;

// Each row's cell centres that lie inside `polygon` (its holes left out), by
// scanline: where the row's centre line crosses the polygon's rings, sorted,
// delimits the inside in pairs (even-odd). Calls fill(row, first col, last col)
// for each run of inside centres; `inclusive` counts a centre on the boundary in.
template <class Fill>
void ForEachInsideRun(const Polygon& polygon, double min_e, double min_n, double cell_m, int rows,
                      int cols, bool inclusive, Fill fill) {
  std::vector<const Ring*> rings = {&polygon.outer()};
  for (const Ring& inner : polygon.inners()) rings.push_back(&inner);
  Box box;
  bg::envelope(polygon.outer(), box);
  const int first_row =
      std::max(0, static_cast<int>(std::floor((box.min_corner().y() - min_n) / cell_m - 0.5)));
  const int last_row = std::min(
      rows - 1, static_cast<int>(std::ceil((box.max_corner().y() - min_n) / cell_m - 0.5)));
  std::vector<double> crossings;
  for (int r = first_row; r <= last_row; ++r) {
    const double y = min_n + (r + 0.5) * cell_m;
    crossings.clear();
    for (const Ring* ring : rings) {
      // Every edge, the closing one too (a closed ring's is empty: skipped below).
      for (std::size_t i = 0; i < ring->size(); ++i) {
        const Point& a = (*ring)[i];
        const Point& b = (*ring)[(i + 1) % ring->size()];
        // Half-open in y, so a vertex on the line counts once.
        if ((a.y() <= y) == (b.y() <= y)) continue;
        crossings.push_back(a.x() + (y - a.y()) * (b.x() - a.x()) / (b.y() - a.y()));
      }
    }
    std::sort(crossings.begin(), crossings.end());
    for (std::size_t i = 0; i + 1 < crossings.size(); i += 2) {
      // Columns whose centre min_e + (c + 0.5) cell_m lies in [x0, x1] (or (x0, x1)).
      const double c0 = (crossings[i] - min_e) / cell_m - 0.5;
      const double c1 = (crossings[i + 1] - min_e) / cell_m - 0.5;
      const double first = inclusive ? std::ceil(c0) : std::floor(c0) + 1.0;
      const double last = inclusive ? std::floor(c1) : std::ceil(c1) - 1.0;
      const int from = static_cast<int>(std::max(first, 0.0));
      const int to = static_cast<int>(std::min(last, static_cast<double>(cols - 1)));
      if (from <= to) fill(r, from, to);
    }
  }
}

}  // namespace

CoverageGrid::CoverageGrid(const MultiPolygon& area, const MultiPolygon& no_fly) {
  if (area.empty()) return;
  Box box;
  bg::envelope(area, box);
  min_e_ = box.min_corner().x();
  min_n_ = box.min_corner().y();
  const double width = box.max_corner().x() - min_e_;
  const double height = box.max_corner().y() - min_n_;
  cell_m_ = std::max(kCoverageGridCellM, std::sqrt(width * height / kMaxCoverageCells));
  cols_ = std::max(1, static_cast<int>(std::ceil(width / cell_m_)));
  rows_ = std::max(1, static_cast<int>(std::ceil(height / cell_m_)));
  state_.assign(static_cast<std::size_t>(cols_) * static_cast<std::size_t>(rows_), kOutside);
  const auto run = [this](int r, int c) {
    return state_.begin() + static_cast<std::ptrdiff_t>(static_cast<std::size_t>(r) *
                                                            static_cast<std::size_t>(cols_) +
                                                        static_cast<std::size_t>(c));
  };
  // Covered by the area (its boundary in: bg::covered_by), then not within a
  // no-fly zone (its boundary out: bg::within). Up to 2 million cells: by rows,
  // not point by point.
  for (const Polygon& polygon : area) {
    ForEachInsideRun(
        polygon, min_e_, min_n_, cell_m_, rows_, cols_, true,
        [&](int r, int c0, int c1) { std::fill(run(r, c0), run(r, c1) + 1, kUnseen); });
  }
  for (const Polygon& zone : no_fly) {
    ForEachInsideRun(
        zone, min_e_, min_n_, cell_m_, rows_, cols_, false,
        [&](int r, int c0, int c1) { std::fill(run(r, c0), run(r, c1) + 1, kOutside); });
  }
  searchable_ = static_cast<std::size_t>(std::count(state_.begin(), state_.end(), kUnseen));
}

void CoverageGrid::Mark(const Eigen::Vector2d& position_en_m, double heading_rad, double altitude_m,
                        const common::CameraModel& camera, double camera_pitch_deg) {
  if (!position_en_m.allFinite() || !std::isfinite(heading_rad) || !std::isfinite(altitude_m) ||
      altitude_m < kMinCoverageAltitudeM || state_.empty()) {
    return;
  }
  const double h = altitude_m;
  const double depression = -camera_pitch_deg * common::kRadPerDeg;
  const double half_v = camera.vfov_deg * common::kRadPerDeg / 2.0;
  // Ground distance ahead of the vehicle of the image's near and far edges
  // (negative: behind). An edge at or above the horizon is capped.
  const double near_angle = depression + half_v;
  const double far_angle = depression - half_v;
  const double near_m = h / std::tan(near_angle);
  const double far_m =
      far_angle > 0.0 ? std::min(h / std::tan(far_angle), kFarEdgeCapM) : kFarEdgeCapM;
  const double half_w = common::FootprintWidthM(camera, h, camera_pitch_deg) / 2.0;
  const Eigen::Vector2d forward(std::sin(heading_rad), std::cos(heading_rad));
  const Eigen::Vector2d right(forward.y(), -forward.x());
  const Eigen::Vector2d& p = position_en_m;
  double lo_e = std::numeric_limits<double>::infinity();
  double lo_n = lo_e;
  double hi_e = -lo_e;
  double hi_n = -lo_e;
  for (const double along : {near_m, far_m}) {
    for (const double across : {-half_w, half_w}) {
      const Eigen::Vector2d corner = p + along * forward + across * right;
      lo_e = std::min(lo_e, corner.x());
      hi_e = std::max(hi_e, corner.x());
      lo_n = std::min(lo_n, corner.y());
      hi_n = std::max(hi_n, corner.y());
    }
  }
  // Clamp before the cast: a footprint far off the grid must not overflow int.
  const auto col = [&](double e) {
    return static_cast<int>(
        std::clamp(std::floor((e - min_e_) / cell_m_), -1.0, static_cast<double>(cols_)));
  };
  const auto row = [&](double n) {
    return static_cast<int>(
        std::clamp(std::floor((n - min_n_) / cell_m_), -1.0, static_cast<double>(rows_)));
  };
  const int c0 = std::max(0, col(lo_e));
  const int c1 = std::min(cols_ - 1, col(hi_e));
  const int r0 = std::max(0, row(lo_n));
  const int r1 = std::min(rows_ - 1, row(hi_n));
  for (int r = r0; r <= r1; ++r) {
    // The row's centres inside the footprint lie between where the row crosses
    // its four edges: a turned footprint fills half its bounding box. One cell
    // more each side absorbs rounding; each cell is still tested below.
    const double dn = min_n_ + (r + 0.5) * cell_m_ - p.y();
    double lo_de = -std::numeric_limits<double>::infinity();
    double hi_de = std::numeric_limits<double>::infinity();
    // lower <= de * slope + dn * other <= upper, for de (east from the vehicle).
    const auto within = [&](double slope, double other, double lower, double upper) {
      if (std::abs(slope) < kFlatSlope) return;  // the row's edge crossing is far off: all of it
      const double a = (lower - dn * other) / slope;
      const double b = (upper - dn * other) / slope;
      lo_de = std::max(lo_de, std::min(a, b));
      hi_de = std::min(hi_de, std::max(a, b));
    };
    within(forward.x(), forward.y(), near_m, far_m);
    within(right.x(), right.y(), -half_w, half_w);
    if (lo_de > hi_de) continue;
    const int first = std::max(c0, col(p.x() + lo_de) - 1);
    const int last = std::min(c1, col(p.x() + hi_de) + 1);
    for (int c = first; c <= last; ++c) {
      std::uint8_t& cell = state_[static_cast<std::size_t>(r) * static_cast<std::size_t>(cols_) +
                                  static_cast<std::size_t>(c)];
      if (cell != kUnseen) continue;
      const Eigen::Vector2d d =
          Eigen::Vector2d(min_e_ + (c + 0.5) * cell_m_, min_n_ + (r + 0.5) * cell_m_) - p;
      const double along = d.dot(forward);
      if (along < near_m || along > far_m || std::abs(d.dot(right)) > half_w) continue;
      cell = kSeen;
      ++seen_;
    }
  }
}

bool CoverageGrid::Searchable(int row, int col) const {
  if (row < 0 || row >= rows_ || col < 0 || col >= cols_) return false;
  return state_[static_cast<std::size_t>(row) * static_cast<std::size_t>(cols_) +
                static_cast<std::size_t>(col)] != kOutside;
}

bool CoverageGrid::Seen(int row, int col) const {
  if (row < 0 || row >= rows_ || col < 0 || col >= cols_) return false;
  return state_[static_cast<std::size_t>(row) * static_cast<std::size_t>(cols_) +
                static_cast<std::size_t>(col)] == kSeen;
}

std::vector<std::uint8_t> CoverageGrid::SeenBitset() const {
  static_assert(kSeen == 2 && kUnseen == 1 && kOutside == 0, "seen <=> bit 1 of the state");
  std::vector<std::uint8_t> bits((state_.size() + 7) / 8, 0);
  const std::size_t whole = state_.size() / 8;
  // Eight cells at a time (up to 2 million of them, every second on the web): bit 1
  // of each state byte moved to bit 0, then the eight gathered into one byte by a
  // multiplication (cell j's bit lands on bit 56 + j).
  for (std::size_t i = 0; i < whole; ++i) {
    std::uint64_t eight = 0;
    for (std::size_t j = 0; j < 8; ++j) {
      eight |= std::uint64_t{state_[8 * i + j]} << (8 * j);
    }
    const std::uint64_t seen = (eight >> 1) & 0x0101010101010101ULL;
    bits[i] = static_cast<std::uint8_t>((seen * 0x0102040810204080ULL) >> 56);
  }
  for (std::size_t k = 8 * whole; k < state_.size(); ++k) {
    if (state_[k] == kSeen) bits[k / 8] |= static_cast<std::uint8_t>(1U << (k % 8));
  }
  return bits;
}

double CoverageGrid::Fraction() const {
  return searchable_ == 0 ? 0.0 : static_cast<double>(seen_) / static_cast<double>(searchable_);
}

}  // namespace fireswarm::planner
