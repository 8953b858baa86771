// How much of the search area the cameras have seen: the one measure of coverage
// fireswarm reports. The run's scorer marks it from the simulator's truth, the
// server from telemetry (ServerConfig::area), so both speak of the same ground.
//
// The search area (area minus no-fly zones) is rasterised in square cells (5 m,
// coarser when the area would need more than kMaxCoverageCells); each Mark()
// sets seen the cells whose centres lie in the camera's ground footprint: a
// rectangle around the ground point under the optical axis, across the track the
// camera's near-edge width (common::FootprintWidthM), along it from the near to
// the far edge of the vertical field of view (far edge capped at kFarEdgeCapM for
// cameras looking near the horizon), for level flight (roll and pitch of the body
// are ignored) over flat ground.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "fireswarm/common/camera_model.hpp"
#include "fireswarm/planner/geometry.hpp"

namespace fireswarm::planner {

/// The raster's finest cell, m.
inline constexpr double kCoverageGridCellM = 5.0;
/// The most cells a raster may have; a larger area gets coarser cells.
inline constexpr double kMaxCoverageCells = 2'000'000.0;
/// Where the footprint's far edge is capped when the image reaches the horizon, m.
inline constexpr double kFarEdgeCapM = 1'000.0;
/// Below this altitude a vehicle is taking off or landing: its camera is not
/// searching, and Mark() marks nothing, m above ground.
inline constexpr double kMinCoverageAltitudeM = 2.0;

/// The search area rasterised, with the cells a camera has seen.
class CoverageGrid {
 public:
  /// `area` and `no_fly` in one local frame (x metres east, y north), as
  /// SearchArea: a cell is searchable when its centre is covered by `area`
  /// (holes excluded) and not within `no_fly`.
  CoverageGrid(const MultiPolygon& area, const MultiPolygon& no_fly);

  /// Marks what a camera (model, mount pitch from the horizon in degrees, -90
  /// straight down, in [-90, 0)) sees from a vehicle flying level at
  /// `position_en_m` (local metres east, north), heading `heading_rad` (clockwise
  /// from north) and `altitude_m` above the ground. Nothing below
  /// kMinCoverageAltitudeM or when a value is not finite.
  void Mark(const Eigen::Vector2d& position_en_m, double heading_rad, double altitude_m,
            const common::CameraModel& camera, double camera_pitch_deg);

  /// Seen cells / searchable cells, 0 when the area has none.
  double Fraction() const;
  /// The side of a cell, m.
  double cell_m() const { return cell_m_; }
  std::size_t searchable_cells() const { return searchable_; }
  std::size_t seen_cells() const { return seen_; }
  /// The raster: `rows` cells from the south, `cols` from the west, cell (0, 0)'s
  /// south-west corner at `south_west_en_m` (local metres east, north).
  int rows() const { return rows_; }
  int cols() const { return cols_; }
  Eigen::Vector2d south_west_en_m() const { return {min_e_, min_n_}; }
  /// Whether cell (row, col) is searchable (its centre in the area, not in a
  /// no-fly zone); false outside the raster.
  bool Searchable(int row, int col) const;
  /// Whether a camera has seen cell (row, col); false outside the raster.
  bool Seen(int row, int col) const;
  /// Every cell's Seen() as bits: cell (row, col) is bit (k mod 8) of byte k / 8,
  /// k = row * cols() + col, least significant bit first.
  std::vector<std::uint8_t> SeenBitset() const;

 private:
  double min_e_ = 0.0;
  double min_n_ = 0.0;
  double cell_m_ = kCoverageGridCellM;
  int cols_ = 0;
  int rows_ = 0;
  std::vector<std::uint8_t> state_;  // 0 outside, 1 searchable unseen, 2 seen
  std::size_t searchable_ = 0;
  std::size_t seen_ = 0;
};

}  // namespace fireswarm::planner
