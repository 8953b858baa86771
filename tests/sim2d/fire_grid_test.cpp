// FireGrid: configuration checks, ignitions, burn-out and cooling, truth
// accessors, determinism, and that only the burning front costs work.
#include "fireswarm/sim2d/fire_grid.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>

namespace fireswarm::sim2d {
namespace {

void ExpectRejected(const std::function<void(FireConfig&)>& spoil, const std::string& field) {
  FireConfig config;
  spoil(config);
  try {
    config.Validate();
    ADD_FAILURE() << "expected " << field << " to be rejected";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
  }
}

TEST(FireGrid, BadConfigIsRejectedNamingTheField) {
  EXPECT_NO_THROW(FireConfig{}.Validate());
  ExpectRejected([](FireConfig& c) { c.cell_size_m = 0.0; }, "cell_size_m");
  ExpectRejected([](FireConfig& c) { c.width_m = -5.0; }, "width_m");
  ExpectRejected([](FireConfig& c) { c.height_m = NAN; }, "height_m");
  ExpectRejected([](FireConfig& c) { c.wind_speed_mps = -1.0; }, "wind_speed_mps");
  ExpectRejected([](FireConfig& c) { c.jitter_fraction = 1.5; }, "jitter_fraction");
  ExpectRejected([](FireConfig& c) { c.forest.head_ros_ref_mpm = 0.0; }, "forest.head_ros_ref_mpm");
  ExpectRejected([](FireConfig& c) { c.open.burn_duration_s = -1.0; }, "open.burn_duration_s");
  ExpectRejected([](FireConfig& c) { c.flame_c = 10.0; }, "flame_c");
  ExpectRejected([](FireConfig& c) { c.ember_c = 900.0; }, "ember_c");
  ExpectRejected([](FireConfig& c) { c.cooling_tau_s = 0.0; }, "cooling_tau_s");
  ExpectRejected([](FireConfig& c) { c.cell_size_m = 0.01; }, "cell_size_m");  // 1e10 cells
  FireConfig bad;
  bad.cell_size_m = -1.0;
  EXPECT_THROW(FireGrid(bad, MakeRng(1, "fire")), std::invalid_argument);
}

TEST(FireGrid, CoversTheAreaWithCells) {
  FireConfig config;
  config.origin_m = Vec2(-100.0, -50.0);
  config.width_m = 203.0;
  config.height_m = 100.0;
  const FireGrid grid(config, MakeRng(1, "fire"));
  EXPECT_EQ(grid.cols(), 41);
  EXPECT_EQ(grid.rows(), 20);
  EXPECT_EQ(grid.CellAt(Vec2(-100.0, -50.0)), (CellIndex{0, 0}));
  EXPECT_EQ(grid.CellAt(Vec2(-94.0, -44.0)), (CellIndex{1, 1}));
  EXPECT_FALSE(grid.CellAt(Vec2(-100.1, 0.0)).has_value());
  EXPECT_TRUE(grid.CellCenter({0, 0}).isApprox(Vec2(-97.5, -47.5)));
  EXPECT_EQ(grid.FuelAt({3, 3}), Fuel::kForest);
}

TEST(FireGrid, BadIgnitionsAreRejected) {
  FireGrid grid(FireConfig{}, MakeRng(1, "fire"));
  EXPECT_THROW(grid.AddIgnition({Vec2(-1.0, 10.0), 0.0}), std::invalid_argument);
  grid.SetFuelRect(Vec2(0.0, 0.0), Vec2(20.0, 20.0), Fuel::kNone);
  EXPECT_THROW(grid.AddIgnition({Vec2(10.0, 10.0), 0.0}), std::invalid_argument);
  grid.AdvanceTo(100.0);
  EXPECT_THROW(grid.AddIgnition({Vec2(500.0, 500.0), 50.0}), std::invalid_argument);
  EXPECT_THROW(grid.AdvanceTo(99.0), std::invalid_argument);
}

TEST(FireGrid, IgnitesAtItsTimeBurnsOutAndCools) {
  FireConfig config;
  FireGrid grid(config, MakeRng(1, "fire"));
  // One forest cell on bare ground, so the fire cannot spread from it.
  grid.SetFuelRect(Vec2(0.0, 0.0), Vec2(1000.0, 1000.0), Fuel::kNone);
  grid.SetFuelRect(Vec2(501.0, 501.0), Vec2(504.0, 504.0), Fuel::kForest);
  const Vec2 spot(502.0, 502.0);
  grid.AddIgnition({spot, 10.0});
  const CellIndex cell = *grid.CellAt(spot);
  grid.AdvanceTo(9.0);
  EXPECT_EQ(grid.StateAt(cell), CellState::kUnburned);
  EXPECT_DOUBLE_EQ(grid.CellTemperatureC(cell), config.ambient_c);
  grid.AdvanceTo(10.0);
  EXPECT_EQ(grid.StateAt(cell), CellState::kBurning);
  EXPECT_DOUBLE_EQ(grid.CellTemperatureC(cell), config.flame_c);
  EXPECT_DOUBLE_EQ(*grid.IgnitionTimeS(cell), 10.0);
  EXPECT_TRUE(grid.AnyHotIn({spot - Vec2(1, 1), spot + Vec2(1, 1)}));
  EXPECT_EQ(grid.BurnedAreaM2(), 25.0);

  const double out_s = 10.0 + config.forest.burn_duration_s;
  grid.AdvanceTo(out_s + config.cooling_tau_s);
  EXPECT_EQ(grid.StateAt(cell), CellState::kCooling);
  const double expected_c = config.ambient_c + (config.ember_c - config.ambient_c) * std::exp(-1.0);
  EXPECT_NEAR(grid.CellTemperatureC(cell), expected_c, 1e-9);

  grid.AdvanceTo(out_s + 20.0 * config.cooling_tau_s);
  EXPECT_EQ(grid.StateAt(cell), CellState::kBurnedCold);
  EXPECT_DOUBLE_EQ(grid.CellTemperatureC(cell), config.ambient_c);
  EXPECT_FALSE(grid.AnyHotIn({spot - Vec2(1, 1), spot + Vec2(1, 1)}));
}

TEST(FireGrid, TruthAccessorsReportFrontAreaAndIgnitions) {
  FireGrid grid(FireConfig{}, MakeRng(5, "fire"));
  grid.AddIgnition({Vec2(300.0, 300.0), 0.0});
  grid.AddIgnition({Vec2(700.0, 700.0), 100.0});
  grid.AdvanceTo(1200.0);
  ASSERT_EQ(grid.ignitions().size(), 2U);
  EXPECT_EQ(grid.ignitions()[1].cell, *grid.CellAt(Vec2(700.0, 700.0)));
  EXPECT_DOUBLE_EQ(grid.ignitions()[1].ignition.time_s, 100.0);
  const std::vector<CellIndex> burning = grid.BurningCells();
  EXPECT_EQ(burning.size(), grid.burning_count());
  EXPECT_GT(burning.size(), 2U);
  for (const CellIndex& c : burning) EXPECT_EQ(grid.StateAt(c), CellState::kBurning);
  EXPECT_GE(grid.BurnedAreaM2(), static_cast<double>(burning.size()) * 25.0);
  // The first ignition burned out after 600 s: it is no longer in the front.
  EXPECT_EQ(grid.StateAt(*grid.CellAt(Vec2(300.0, 300.0))), CellState::kCooling);
  EXPECT_TRUE(grid.AnyHotIn({Vec2(290.0, 290.0), Vec2(310.0, 310.0)}));
  EXPECT_FALSE(grid.AnyHotIn({Vec2(0.0, 0.0), Vec2(100.0, 100.0)}));
}

TEST(FireGrid, SameSeedSameFireWhateverTheStepSize) {
  FireConfig config;
  FireGrid coarse(config, MakeRng(42, "fire"));
  FireGrid fine(config, MakeRng(42, "fire"));
  for (FireGrid* g : {&coarse, &fine}) g->AddIgnition({Vec2(500.0, 500.0), 0.0});
  coarse.AdvanceTo(1800.0);
  for (int t = 1; t <= 1800; ++t) fine.AdvanceTo(t);
  int burned = 0;
  for (int r = 0; r < coarse.rows(); ++r) {
    for (int c = 0; c < coarse.cols(); ++c) {
      ASSERT_EQ(coarse.IgnitionTimeS({c, r}), fine.IgnitionTimeS({c, r}));
      burned += coarse.IgnitionTimeS({c, r}).has_value() ? 1 : 0;
    }
  }
  EXPECT_GT(burned, 10);
  FireGrid other_seed(config, MakeRng(43, "fire"));
  other_seed.AddIgnition({Vec2(500.0, 500.0), 0.0});
  other_seed.AdvanceTo(1800.0);
  EXPECT_NE(other_seed.events_processed(), 0U);
  bool differs = false;
  for (int r = 0; r < coarse.rows() && !differs; ++r) {
    for (int c = 0; c < coarse.cols() && !differs; ++c) {
      differs = coarse.IgnitionTimeS({c, r}) != other_seed.IgnitionTimeS({c, r});
    }
  }
  EXPECT_TRUE(differs);
}

TEST(FireGrid, OnlyTheFrontIsUpdatedOnALargeGrid) {
  FireConfig config;
  config.width_m = 5000.0;  // 25 km^2: a million 5 m cells
  config.height_m = 5000.0;
  FireGrid grid(config, MakeRng(9, "fire"));
  grid.SetFuelRect(Vec2(2000.0, 2000.0), Vec2(3000.0, 3000.0), Fuel::kOpen);
  grid.AddIgnition({Vec2(2500.0, 2500.0), 0.0});
  for (int t = 1; t <= 600; ++t) grid.AdvanceTo(t);
  const double cells = static_cast<double>(grid.cols()) * grid.rows();
  EXPECT_EQ(cells, 1.0e6);
  const double burned_cells = grid.BurnedAreaM2() / 25.0;
  EXPECT_GT(burned_cells, 200.0);  // a real front, in grass
  // Work: each ignited cell looks at its 16 neighbours, nothing else is visited.
  EXPECT_LE(static_cast<double>(grid.cells_touched()), 16.0 * burned_cells);
  EXPECT_LT(static_cast<double>(grid.cells_touched()), 0.02 * cells);
  EXPECT_LT(static_cast<double>(grid.events_processed()), 0.02 * cells);
}

TEST(FireGrid, RandomIgnitionsLandOnFuelWithinTheWindow) {
  FireGrid grid(FireConfig{}, MakeRng(1, "fire"));
  grid.SetFuelRect(Vec2(0.0, 0.0), Vec2(1000.0, 500.0), Fuel::kNone);
  Rng rng = MakeRng(431, "ignitions");
  const std::vector<Ignition> ignitions = RandomIgnitions(grid, 20, 10.0, 60.0, rng);
  ASSERT_EQ(ignitions.size(), 20U);
  for (const Ignition& ig : ignitions) {
    EXPECT_NE(grid.FuelAt(*grid.CellAt(ig.position_m)), Fuel::kNone);
    EXPECT_GE(ig.time_s, 10.0);
    EXPECT_LE(ig.time_s, 60.0);
    grid.AddIgnition(ig);
  }
  Rng again = MakeRng(431, "ignitions");
  EXPECT_EQ(RandomIgnitions(grid, 20, 10.0, 60.0, again)[7].position_m, ignitions[7].position_m);
  grid.SetFuelRect(Vec2(0.0, 0.0), Vec2(1000.0, 1000.0), Fuel::kNone);
  EXPECT_THROW(RandomIgnitions(grid, 1, 0.0, 1.0, rng), std::invalid_argument);
  EXPECT_THROW(RandomIgnitions(grid, -1, 0.0, 1.0, rng), std::invalid_argument);
}

}  // namespace
}  // namespace fireswarm::sim2d
