#include "fireswarm/sim2d/fire_grid.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

#include "fire_spread.hpp"
#include "fireswarm/common/angles.hpp"

namespace fireswarm::sim2d {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kSecondsPerMinute = 60.0;

// The 16 neighbours of a cell: the 8 adjacent ones and the 8 knight moves. The
// knight moves give 16 spread directions instead of 8, so a wind-driven fire
// grows as an ellipse rather than an octagon.
struct Offset {
  int dc;
  int dr;
};
constexpr std::array<Offset, 16> kNeighbours = {{{1, 0},
                                                 {-1, 0},
                                                 {0, 1},
                                                 {0, -1},
                                                 {1, 1},
                                                 {1, -1},
                                                 {-1, 1},
                                                 {-1, -1},
                                                 {2, 1},
                                                 {2, -1},
                                                 {-2, 1},
                                                 {-2, -1},
                                                 {1, 2},
                                                 {1, -2},
                                                 {-1, 2},
                                                 {-1, -2}}};

// The two cells a diagonal or knight move passes between.
std::pair<Offset, Offset> Intermediates(const Offset& o) {
  if (std::abs(o.dc) == 2) return {{o.dc / 2, 0}, {o.dc / 2, o.dr}};
  if (std::abs(o.dr) == 2) return {{0, o.dr / 2}, {o.dc, o.dr / 2}};
  return {{o.dc, 0}, {0, o.dr}};
}

// Travel time from a cell to each neighbour through `fuel`, s.
std::vector<double> NeighbourTimes(const FireConfig& config, const FuelBehaviour& fuel) {
  const double head_mpm = HeadRosMpm(fuel, config.wind_speed_mps, config.wind_exponent);
  const double lb = LengthToBreadth(config.wind_speed_mps);
  // The head of the fire runs downwind: toward wind_from_deg + 180, clockwise from north.
  const double to_rad = common::DegToRad(config.wind_from_deg + 180.0);
  const Vec2 head_dir(std::sin(to_rad), std::cos(to_rad));
  std::vector<double> times;
  for (const Offset& o : kNeighbours) {
    const Vec2 step(o.dc * config.cell_size_m, o.dr * config.cell_size_m);
    const double cos_from_head = step.normalized().dot(head_dir);
    const double ros_mpm = RosInDirectionMpm(head_mpm, lb, cos_from_head);
    times.push_back(step.norm() / (ros_mpm / kSecondsPerMinute));
  }
  return times;
}

// Uniform in [0, 1) from 53 random bits: the same numbers on every standard library.
double Uniform01(Rng& rng) {
  return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

// Even-odd rule: is `p` inside the polygon?
bool InsidePolygon(std::span<const Vec2> polygon, const Vec2& p) {
  bool inside = false;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++) {
    const Vec2& a = polygon[i];
    const Vec2& b = polygon[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x()) {
      inside = !inside;
    }
  }
  return inside;
}

std::string Where(const Vec2& p) {
  std::ostringstream out;
  out << "(" << p.x() << ", " << p.y() << ")";
  return out.str();
}

}  // namespace

bool FireGrid::Event::operator>(const Event& other) const {
  if (time_s != other.time_s) return time_s > other.time_s;
  if (cell != other.cell) return cell > other.cell;
  return kind > other.kind;
}

FireGrid::FireGrid(FireConfig config, Rng rng) : config_(std::move(config)), rng_(rng) {
  config_.Validate();
  cols_ = static_cast<int>(std::ceil(config_.width_m / config_.cell_size_m));
  rows_ = static_cast<int>(std::ceil(config_.height_m / config_.cell_size_m));
  tile_cols_ = (cols_ + kFireTileCells - 1) / kFireTileCells;
  tile_rows_ = (rows_ + kFireTileCells - 1) / kFireTileCells;
  const std::size_t cells = static_cast<std::size_t>(cols_) * static_cast<std::size_t>(rows_);
  fuel_.assign(cells, Fuel::kForest);
  state_.assign(cells, CellState::kUnburned);
  arrival_s_.assign(cells, kInf);
  tile_hot_count_.assign(
      static_cast<std::size_t>(tile_cols_) * static_cast<std::size_t>(tile_rows_), 0);
  block_cols_ = (tile_cols_ + kFireBlockTiles - 1) / kFireBlockTiles;
  const int block_rows = (tile_rows_ + kFireBlockTiles - 1) / kFireBlockTiles;
  block_hot_count_.assign(
      static_cast<std::size_t>(block_cols_) * static_cast<std::size_t>(block_rows), 0);
  neighbour_forest_s_ = NeighbourTimes(config_, config_.forest);
  neighbour_open_s_ = NeighbourTimes(config_, config_.open);
}

std::optional<CellIndex> FireGrid::CellAt(const Vec2& position_m) const {
  const Vec2 local = (position_m - config_.origin_m) / config_.cell_size_m;
  if (!(local.x() >= 0.0 && local.y() >= 0.0 && local.x() < cols_ && local.y() < rows_)) {
    return std::nullopt;
  }
  return CellIndex{static_cast<int>(local.x()), static_cast<int>(local.y())};
}

Vec2 FireGrid::CellCenter(CellIndex cell) const {
  return config_.origin_m + config_.cell_size_m * Vec2(cell.col + 0.5, cell.row + 0.5);
}

CellIndex FireGrid::Unflat(std::uint32_t flat) const {
  return CellIndex{static_cast<int>(flat % static_cast<std::uint32_t>(cols_)),
                   static_cast<int>(flat / static_cast<std::uint32_t>(cols_))};
}

void FireGrid::SetFuelRect(const Vec2& min_m, const Vec2& max_m, Fuel fuel) {
  const std::array<Vec2, 4> corners = {min_m, Vec2(max_m.x(), min_m.y()), max_m,
                                       Vec2(min_m.x(), max_m.y())};
  SetFuelPolygon(corners, fuel);
}

void FireGrid::SetFuelPolygon(std::span<const Vec2> vertices_m, Fuel fuel) {
  if (vertices_m.size() < 3) {
    throw std::invalid_argument("fuel polygon: vertices has " + std::to_string(vertices_m.size()) +
                                " points, needs at least 3");
  }
  Vec2 lo = vertices_m[0], hi = vertices_m[0];
  for (const Vec2& v : vertices_m) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const auto index_range = [&](double a, double b, double origin, int count) {
    const double first = std::ceil((a - origin) / config_.cell_size_m - 0.5);
    const double last = std::floor((b - origin) / config_.cell_size_m - 0.5);
    return std::pair<int, int>{static_cast<int>(std::max(first, 0.0)),
                               static_cast<int>(std::min(last, count - 1.0))};
  };
  const auto [c0, c1] = index_range(lo.x(), hi.x(), config_.origin_m.x(), cols_);
  const auto [r0, r1] = index_range(lo.y(), hi.y(), config_.origin_m.y(), rows_);
  for (int r = r0; r <= r1; ++r) {
    for (int c = c0; c <= c1; ++c) {
      if (InsidePolygon(vertices_m, CellCenter({c, r}))) fuel_[Flat({c, r})] = fuel;
    }
  }
}

void FireGrid::AddIgnition(const Ignition& ignition) {
  const std::optional<CellIndex> cell = CellAt(ignition.position_m);
  if (!cell) {
    throw std::invalid_argument("ignition position " + Where(ignition.position_m) +
                                " is outside the fire grid");
  }
  if (FuelAt(*cell) == Fuel::kNone) {
    throw std::invalid_argument("ignition position " + Where(ignition.position_m) +
                                " is on a cell without fuel");
  }
  if (!std::isfinite(ignition.time_s) || ignition.time_s < now_s_) {
    throw std::invalid_argument("ignition time_s = " + std::to_string(ignition.time_s) +
                                " is before the fire's current time " + std::to_string(now_s_));
  }
  ignitions_.push_back({ignition, *cell});
  const auto flat = static_cast<std::uint32_t>(Flat(*cell));
  arrival_s_[flat] = std::min(arrival_s_[flat], ignition.time_s);
  events_.push({ignition.time_s, flat, EventKind::kIgnite});
}

void FireGrid::AdvanceTo(double t_s) {
  if (!std::isfinite(t_s) || t_s < now_s_) {
    throw std::invalid_argument("fire AdvanceTo: t_s = " + std::to_string(t_s) +
                                " is before the current time " + std::to_string(now_s_));
  }
  while (!events_.empty() && events_.top().time_s <= t_s) {
    const Event event = events_.top();
    events_.pop();
    ++events_processed_;
    HandleEvent(event);
  }
  now_s_ = t_s;
  // Burned-out cells leave the burning list here, in one pass over the front.
  std::erase_if(burning_, [&](std::uint32_t c) { return state_[c] != CellState::kBurning; });
}

void FireGrid::HandleEvent(const Event& event) {
  const CellIndex cell = Unflat(event.cell);
  switch (event.kind) {
    case EventKind::kIgnite:
      // Stale entries (the cell already caught from a faster neighbour) are skipped.
      if (state_[event.cell] == CellState::kUnburned && fuel_[event.cell] != Fuel::kNone) {
        Ignite(event.cell, event.time_s);
      }
      return;
    case EventKind::kBurnOut: {
      state_[event.cell] = CellState::kCooling;
      const double excess_k = config_.ember_c - config_.ambient_c;
      const double cool_s =
          config_.cooling_tau_s * std::log(std::max(excess_k / config_.cooled_threshold_k, 1.0));
      events_.push({event.time_s + cool_s, event.cell, EventKind::kCooled});
      return;
    }
    case EventKind::kCooled:
      state_[event.cell] = CellState::kBurnedCold;
      ChangeHotCount(cell, -1);
      return;
  }
}

void FireGrid::Ignite(std::uint32_t cell, double time_s) {
  state_[cell] = CellState::kBurning;
  arrival_s_[cell] = time_s;
  burning_.push_back(cell);
  ++burned_cells_;
  ChangeHotCount(Unflat(cell), +1);
  const double burn_s = config_.Behaviour(fuel_[cell]).burn_duration_s;
  events_.push({time_s + burn_s, cell, EventKind::kBurnOut});
  SpreadFrom(cell, time_s);
}

void FireGrid::SpreadFrom(std::uint32_t cell, double time_s) {
  const CellIndex from = Unflat(cell);
  const auto burnable = [&](int c, int r) {
    return c >= 0 && r >= 0 && c < cols_ && r < rows_ && fuel_[Flat({c, r})] != Fuel::kNone;
  };
  for (std::size_t k = 0; k < kNeighbours.size(); ++k) {
    const Offset& o = kNeighbours[k];
    const int c = from.col + o.dc, r = from.row + o.dr;
    if (!burnable(c, r)) continue;
    // A diagonal or knight move may not slip between two cells without fuel.
    if (std::abs(o.dc) + std::abs(o.dr) > 1) {
      const auto [a, b] = Intermediates(o);
      if (!burnable(from.col + a.dc, from.row + a.dr) &&
          !burnable(from.col + b.dc, from.row + b.dr)) {
        continue;
      }
    }
    const std::size_t target = Flat({c, r});
    ++cells_touched_;
    if (state_[target] != CellState::kUnburned) continue;
    const double base_s =
        fuel_[target] == Fuel::kOpen ? neighbour_open_s_[k] : neighbour_forest_s_[k];
    const double jitter = 1.0 + config_.jitter_fraction * (2.0 * Uniform01(rng_) - 1.0);
    const double arrival = time_s + base_s * jitter;
    if (arrival < arrival_s_[target]) {
      arrival_s_[target] = arrival;
      events_.push({arrival, static_cast<std::uint32_t>(target), EventKind::kIgnite});
    }
  }
}

void FireGrid::ChangeHotCount(CellIndex cell, int delta) {
  const int tile_col = cell.col / kFireTileCells, tile_row = cell.row / kFireTileCells;
  std::uint32_t& tile = tile_hot_count_[TileOf(cell)];
  std::uint32_t& block = block_hot_count_[static_cast<std::size_t>(tile_row / kFireBlockTiles) *
                                              static_cast<std::size_t>(block_cols_) +
                                          static_cast<std::size_t>(tile_col / kFireBlockTiles)];
  tile = delta > 0 ? tile + 1 : tile - 1;
  block = delta > 0 ? block + 1 : block - 1;
}

std::size_t FireGrid::TileOf(CellIndex cell) const {
  return static_cast<std::size_t>(cell.row / kFireTileCells) *
             static_cast<std::size_t>(tile_cols_) +
         static_cast<std::size_t>(cell.col / kFireTileCells);
}

std::optional<double> FireGrid::IgnitionTimeS(CellIndex cell) const {
  if (state_[Flat(cell)] == CellState::kUnburned) return std::nullopt;
  return arrival_s_[Flat(cell)];
}

double FireGrid::CellTemperatureC(CellIndex cell) const {
  const std::size_t flat = Flat(cell);
  switch (state_[flat]) {
    case CellState::kBurning:
      return config_.flame_c;
    case CellState::kCooling: {
      const double out_s = arrival_s_[flat] + config_.Behaviour(fuel_[flat]).burn_duration_s;
      const double excess_k = config_.ember_c - config_.ambient_c;
      return config_.ambient_c + excess_k * std::exp(-(now_s_ - out_s) / config_.cooling_tau_s);
    }
    case CellState::kUnburned:
    case CellState::kBurnedCold:
      break;
  }
  return config_.ambient_c;
}

std::vector<CellIndex> FireGrid::BurningCells() const {
  std::vector<CellIndex> cells;
  cells.reserve(burning_.size());
  for (const std::uint32_t c : burning_) cells.push_back(Unflat(c));
  return cells;
}

double FireGrid::BurnedAreaM2() const {
  return static_cast<double>(burned_cells_) * config_.cell_size_m * config_.cell_size_m;
}

bool FireGrid::AnyHotIn(const GroundBox& box) const {
  const double tile_m = config_.cell_size_m * kFireTileCells;
  const Vec2 lo = (box.min_m - config_.origin_m) / tile_m;
  const Vec2 hi = (box.max_m - config_.origin_m) / tile_m;
  if (hi.x() < 0.0 || hi.y() < 0.0 || lo.x() >= tile_cols_ || lo.y() >= tile_rows_) return false;
  const int t0c = static_cast<int>(std::max(lo.x(), 0.0));
  const int t0r = static_cast<int>(std::max(lo.y(), 0.0));
  const int t1c = static_cast<int>(std::min(hi.x(), tile_cols_ - 1.0));
  const int t1r = static_cast<int>(std::min(hi.y(), tile_rows_ - 1.0));
  for (int br = t0r / kFireBlockTiles; br <= t1r / kFireBlockTiles; ++br) {
    for (int bc = t0c / kFireBlockTiles; bc <= t1c / kFireBlockTiles; ++bc) {
      if (block_hot_count_[static_cast<std::size_t>(br) * static_cast<std::size_t>(block_cols_) +
                           static_cast<std::size_t>(bc)] == 0) {
        continue;
      }
      const int r_end = std::min(t1r, br * kFireBlockTiles + kFireBlockTiles - 1);
      const int c_end = std::min(t1c, bc * kFireBlockTiles + kFireBlockTiles - 1);
      for (int tr = std::max(t0r, br * kFireBlockTiles); tr <= r_end; ++tr) {
        for (int tc = std::max(t0c, bc * kFireBlockTiles); tc <= c_end; ++tc) {
          if (tile_hot_count_[static_cast<std::size_t>(tr) * static_cast<std::size_t>(tile_cols_) +
                              static_cast<std::size_t>(tc)] != 0) {
            return true;
          }
        }
      }
    }
  }
  return false;
}

std::vector<Ignition> RandomIgnitions(const FireGrid& grid, int count, double start_s, double end_s,
                                      Rng& rng) {
  if (count < 0) throw std::invalid_argument("random ignitions: count must be >= 0");
  if (!(end_s >= start_s)) {
    throw std::invalid_argument("random ignitions: end_s must not be before start_s");
  }
  const double size = grid.config().cell_size_m;
  std::vector<Ignition> result;
  // Rejection sampling over cells; give up when fuel is (nearly) absent everywhere.
  const long max_tries = 1000L * (count + 1);
  for (long tries = 0; static_cast<int>(result.size()) < count; ++tries) {
    if (tries >= max_tries) {
      throw std::invalid_argument("random ignitions: the fire grid has (almost) no burnable cell");
    }
    const Vec2 p = grid.config().origin_m +
                   Vec2(Uniform01(rng) * grid.cols() * size, Uniform01(rng) * grid.rows() * size);
    const double t = start_s + Uniform01(rng) * (end_s - start_s);
    const std::optional<CellIndex> cell = grid.CellAt(p);
    if (cell && grid.FuelAt(*cell) != Fuel::kNone) result.push_back({p, t});
  }
  return result;
}

}  // namespace fireswarm::sim2d
