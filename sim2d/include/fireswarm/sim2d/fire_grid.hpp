// Fire spread on a square grid over the area: fuel per cell, ignitions, and a
// cellular minimum-travel-time spread driven by fuel and wind. Cells go
// unburned -> burning (for the fuel's burn duration) -> burned (cooling toward
// ambient). Event driven: a priority queue holds the next ignitions, burn-outs
// and cool-downs, so the cost of AdvanceTo scales with the cells that change,
// not with the size of the grid. Pure: no clock, no I/O; jitter comes from the
// Rng given at construction.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <optional>
#include <queue>
#include <span>
#include <vector>

#include "fireswarm/sim2d/fire_config.hpp"
#include "fireswarm/sim2d/random.hpp"

namespace fireswarm::sim2d {

enum class CellState : std::uint8_t {
  kUnburned,
  kBurning,     ///< flaming, at FireConfig::flame_c
  kCooling,     ///< burned out, cooling exponentially from ember_c toward ambient
  kBurnedCold,  ///< burned out and within cooled_threshold_k of ambient
};

/// A cell address; col grows east, row grows north, (0, 0) is the south-west cell.
struct CellIndex {
  int col = 0;
  int row = 0;
  bool operator==(const CellIndex&) const = default;
};

/// An ignition as it was applied, for scoring against detections.
struct IgnitionRecord {
  Ignition ignition;  ///< as requested
  CellIndex cell;     ///< the cell it lit
};

/// A square of the ground in local ENU metres.
struct GroundBox {
  Vec2 min_m = Vec2::Zero();
  Vec2 max_m = Vec2::Zero();

  /// True if the two boxes share a point (touching edges count).
  bool Overlaps(const GroundBox& other) const {
    return min_m.x() <= other.max_m.x() && other.min_m.x() <= max_m.x() &&
           min_m.y() <= other.max_m.y() && other.min_m.y() <= max_m.y();
  }
};

class FireGrid {
 public:
  /// Cells side `cell_size_m` covering the area, all forest. Throws
  /// std::invalid_argument (naming the field) when `config` is invalid.
  FireGrid(FireConfig config, Rng rng);

  const FireConfig& config() const { return config_; }
  int cols() const { return cols_; }
  int rows() const { return rows_; }
  double now_s() const { return now_s_; }

  /// Marks every cell whose centre lies in the box [min_m, max_m] as `fuel`.
  void SetFuelRect(const Vec2& min_m, const Vec2& max_m, Fuel fuel);
  /// Marks every cell whose centre lies inside the polygon (local metres, >= 3
  /// vertices, either winding, not closed) as `fuel`. Throws std::invalid_argument
  /// for fewer than 3 vertices.
  void SetFuelPolygon(std::span<const Vec2> vertices_m, Fuel fuel);

  /// Schedules an ignition. Throws std::invalid_argument when the position is
  /// outside the grid, on a cell without fuel, or the time is before now_s().
  void AddIgnition(const Ignition& ignition);

  /// Runs every ignition, spread, burn-out and cool-down event up to and
  /// including `t_s`. The result does not depend on how the time is cut into
  /// steps (events carry exact times). Throws std::invalid_argument if t_s < now_s().
  void AdvanceTo(double t_s);

  std::optional<CellIndex> CellAt(const Vec2& position_m) const;
  Vec2 CellCenter(CellIndex cell) const;
  Fuel FuelAt(CellIndex cell) const { return fuel_[Flat(cell)]; }
  CellState StateAt(CellIndex cell) const { return state_[Flat(cell)]; }
  /// Time the cell ignited, or nullopt if it has not.
  std::optional<double> IgnitionTimeS(CellIndex cell) const;
  /// Temperature of the cell's ground at now_s(), Celsius (ambient when unburned).
  double CellTemperatureC(CellIndex cell) const;

  /// Cells burning at now_s() (truth for scoring and for drawing fire fronts).
  std::vector<CellIndex> BurningCells() const;
  std::size_t burning_count() const { return burning_.size(); }
  /// Area that is burning or has burned, m^2.
  double BurnedAreaM2() const;
  std::span<const IgnitionRecord> ignitions() const { return ignitions_; }

  /// True when some burning or still-warm cell may lie in `box` (a two-level
  /// index of tiles of 16 x 16 cells and blocks of 8 x 8 tiles; false means
  /// certainly none). Cost grows with the box's area in blocks, not in cells.
  bool AnyHotIn(const GroundBox& box) const;
  /// Calls fn(CellIndex) for each burning or cooling cell whose square overlaps `box`.
  template <typename Fn>
  void ForEachHotCellIn(const GroundBox& box, Fn&& fn) const;

  /// Work counters: cells whose state or arrival time was examined or changed,
  /// and events taken off the queue, since construction.
  std::uint64_t cells_touched() const { return cells_touched_; }
  std::uint64_t events_processed() const { return events_processed_; }

 private:
  enum class EventKind : std::uint8_t { kIgnite, kBurnOut, kCooled };
  struct Event {
    double time_s;
    std::uint32_t cell;
    EventKind kind;
    // Ordered by time, then cell and kind, so equal times pop deterministically.
    bool operator>(const Event& other) const;
  };

  std::size_t Flat(CellIndex cell) const {
    return static_cast<std::size_t>(cell.row) * static_cast<std::size_t>(cols_) +
           static_cast<std::size_t>(cell.col);
  }
  CellIndex Unflat(std::uint32_t flat) const;
  void HandleEvent(const Event& event);
  void Ignite(std::uint32_t cell, double time_s);
  void SpreadFrom(std::uint32_t cell, double time_s);
  void ChangeHotCount(CellIndex cell, int delta);
  std::size_t TileOf(CellIndex cell) const;

  FireConfig config_;
  Rng rng_;
  int cols_ = 0;
  int rows_ = 0;
  int tile_cols_ = 0;
  int tile_rows_ = 0;
  double now_s_ = 0.0;
  std::vector<Fuel> fuel_;
  std::vector<CellState> state_;
  std::vector<double> arrival_s_;  ///< ignition time, or the best tentative one; +inf if none
  std::vector<std::uint32_t> tile_hot_count_;
  int block_cols_ = 0;  // blocks of kFireBlockTiles x kFireBlockTiles tiles
  std::vector<std::uint32_t> block_hot_count_;
  std::vector<std::uint32_t> burning_;
  std::priority_queue<Event, std::vector<Event>, std::greater<>> events_;
  std::vector<IgnitionRecord> ignitions_;
  std::size_t burned_cells_ = 0;
  std::uint64_t cells_touched_ = 0;
  std::uint64_t events_processed_ = 0;
  // Spread geometry, fixed for the grid: per neighbour offset, travel time per cell (s).
  std::vector<double> neighbour_forest_s_;
  std::vector<double> neighbour_open_s_;
};

/// `count` ignitions at uniformly random burnable cells of `grid`, at uniformly
/// random times in [start_s, end_s] (seed 4.3.1: random fire positions). Throws
/// std::invalid_argument for count < 0 or end_s < start_s, or when the grid has
/// no burnable cell.
std::vector<Ignition> RandomIgnitions(const FireGrid& grid, int count, double start_s, double end_s,
                                      Rng& rng);

// ---- template implementation ----

inline constexpr int kFireTileCells = 16;  ///< side of one hot-index tile, in cells
inline constexpr int kFireBlockTiles = 8;  ///< side of one hot-index block, in tiles

template <typename Fn>
void FireGrid::ForEachHotCellIn(const GroundBox& box, Fn&& fn) const {
  const double size = config_.cell_size_m;
  const auto clamp_col = [&](double x) {
    const double c = std::floor((x - config_.origin_m.x()) / size);
    return static_cast<int>(std::clamp(c, 0.0, static_cast<double>(cols_ - 1)));
  };
  const auto clamp_row = [&](double y) {
    const double r = std::floor((y - config_.origin_m.y()) / size);
    return static_cast<int>(std::clamp(r, 0.0, static_cast<double>(rows_ - 1)));
  };
  if (!AnyHotIn(box)) return;
  const int c0 = clamp_col(box.min_m.x()), c1 = clamp_col(box.max_m.x());
  const int r0 = clamp_row(box.min_m.y()), r1 = clamp_row(box.max_m.y());
  for (int tr = r0 / kFireTileCells; tr <= r1 / kFireTileCells; ++tr) {
    for (int tc = c0 / kFireTileCells; tc <= c1 / kFireTileCells; ++tc) {
      const std::size_t tile = static_cast<std::size_t>(tr) * static_cast<std::size_t>(tile_cols_) +
                               static_cast<std::size_t>(tc);
      if (tile_hot_count_[tile] == 0) continue;
      const int rb = std::max(r0, tr * kFireTileCells);
      const int re = std::min(r1, tr * kFireTileCells + kFireTileCells - 1);
      const int cb = std::max(c0, tc * kFireTileCells);
      const int ce = std::min(c1, tc * kFireTileCells + kFireTileCells - 1);
      for (int r = rb; r <= re; ++r) {
        for (int c = cb; c <= ce; ++c) {
          const CellState s = state_[Flat({c, r})];
          if (s == CellState::kBurning || s == CellState::kCooling) fn(CellIndex{c, r});
        }
      }
    }
  }
}

}  // namespace fireswarm::sim2d
