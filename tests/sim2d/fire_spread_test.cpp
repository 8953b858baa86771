// The rate-of-spread model and the spread it produces on the grid: calibrated
// to the standard fuel models (forest litter 0.5-2.7 m/min head fire at a 5 mi/h
// midflame wind, grass tens of m/min), elliptical around the wind, stopped by water.
#include "fire_spread.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include "fireswarm/sim2d/fire_grid.hpp"

namespace fireswarm::sim2d {
namespace {

constexpr double kSecondsPerMinute = 60.0;

FireConfig EastwardWindConfig() {
  FireConfig config;
  config.origin_m = Vec2(0.0, 0.0);
  config.width_m = 1500.0;
  config.height_m = 600.0;
  config.wind_speed_mps = kReferenceWindMps;  // 5 mi/h
  config.wind_from_deg = 270.0;               // from the west: the head runs east
  return config;
}

// Easternmost and westernmost x (cell centres) of cells that have ignited, m.
std::pair<double, double> BurnedExtentX(const FireGrid& grid) {
  double east = -1e9, west = 1e9;
  for (int r = 0; r < grid.rows(); ++r) {
    for (int c = 0; c < grid.cols(); ++c) {
      if (grid.StateAt({c, r}) != CellState::kUnburned) {
        const double x = grid.CellCenter({c, r}).x();
        east = std::max(east, x);
        west = std::min(west, x);
      }
    }
  }
  return {east, west};
}

// Head-fire rate, m/min, measured from the burned extent between t0 and t1.
double MeasuredHeadRosMpm(FireGrid& grid, double t0_s, double t1_s) {
  grid.AdvanceTo(t0_s);
  const double east0 = BurnedExtentX(grid).first;
  grid.AdvanceTo(t1_s);
  const double east1 = BurnedExtentX(grid).first;
  return (east1 - east0) / ((t1_s - t0_s) / kSecondsPerMinute);
}

TEST(FireSpread, RosModelHasNoWindCircleAndWindEllipse) {
  EXPECT_DOUBLE_EQ(LengthToBreadth(0.0), 1.0);
  EXPECT_NEAR(LengthToBreadth(kReferenceWindMps), 3.19, 0.02);  // Anderson 1983 at 5 mi/h
  FuelBehaviour forest{0.3, 1.5, 600.0};
  EXPECT_DOUBLE_EQ(HeadRosMpm(forest, 0.0, 1.5), 0.3);
  EXPECT_DOUBLE_EQ(HeadRosMpm(forest, kReferenceWindMps, 1.5), 1.5);
  const double lb = LengthToBreadth(kReferenceWindMps);
  EXPECT_DOUBLE_EQ(RosInDirectionMpm(1.5, lb, 1.0), 1.5);
  EXPECT_LT(RosInDirectionMpm(1.5, lb, -1.0), 0.2 * 1.5);    // backing fire is slow
  EXPECT_DOUBLE_EQ(RosInDirectionMpm(1.5, 1.0, -1.0), 1.5);  // no wind: a circle
}

TEST(FireSpread, ForestHeadFireSpreadsAtFuelModelRateInFiveMphWind) {
  FireGrid grid(EastwardWindConfig(), MakeRng(7, "fire"));
  grid.AddIgnition({Vec2(300.0, 300.0), 0.0});
  const double ros_mpm = MeasuredHeadRosMpm(grid, 600.0, 3000.0);
  // Standard timber-litter fuel models (Anderson FM8-FM10) at 5 mi/h: 0.5-2.7 m/min.
  EXPECT_GE(ros_mpm, 0.5);
  EXPECT_LE(ros_mpm, 2.7);
  // and close to the configured 1.5 m/min (one 5 m cell over 40 min is 0.125 m/min).
  EXPECT_NEAR(ros_mpm, 1.5, 0.35);
}

TEST(FireSpread, GrassSpreadsMuchFasterThanForest) {
  FireConfig config = EastwardWindConfig();
  FireGrid grid(config, MakeRng(7, "fire"));
  grid.SetFuelRect(Vec2(0.0, 0.0), Vec2(1500.0, 600.0), Fuel::kOpen);
  grid.AddIgnition({Vec2(100.0, 300.0), 0.0});
  const double ros_mpm = MeasuredHeadRosMpm(grid, 60.0, 1800.0 / 5.0);
  EXPECT_GT(ros_mpm, 15.0);  // grass (FM1 ~ 26 m/min at 5 mi/h)
  EXPECT_LT(ros_mpm, 35.0);
}

TEST(FireSpread, UpwindIsSlowerThanDownwind) {
  FireGrid grid(EastwardWindConfig(), MakeRng(3, "fire"));
  const Vec2 start(700.0, 300.0);
  grid.AddIgnition({start, 0.0});
  grid.AdvanceTo(3600.0);
  const auto [east, west] = BurnedExtentX(grid);
  const double downwind_m = east - start.x();
  const double upwind_m = start.x() - west;
  EXPECT_GT(downwind_m, 60.0);
  EXPECT_LT(upwind_m, 0.35 * downwind_m);
}

TEST(FireSpread, NoWindSpreadsAlikeInAllDirections) {
  FireConfig config = EastwardWindConfig();
  config.wind_speed_mps = 0.0;
  config.jitter_fraction = 0.0;
  FireGrid grid(config, MakeRng(3, "fire"));
  grid.AddIgnition({Vec2(702.5, 302.5), 0.0});
  grid.AdvanceTo(3600.0);
  const auto [east, west] = BurnedExtentX(grid);
  EXPECT_NEAR(east - 702.5, 702.5 - west, 5.0);
}

TEST(FireSpread, FireDoesNotCrossWater) {
  FireConfig config = EastwardWindConfig();
  FireGrid grid(config, MakeRng(11, "fire"));
  grid.SetFuelRect(Vec2(0.0, 0.0), Vec2(1500.0, 600.0), Fuel::kOpen);
  // A river 10 m wide (two cells) across the whole area, 200 m downwind.
  grid.SetFuelRect(Vec2(300.0, 0.0), Vec2(310.0, 600.0), Fuel::kNone);
  grid.AddIgnition({Vec2(100.0, 300.0), 0.0});
  grid.AdvanceTo(3600.0);
  int burned_bank = 0;
  for (int r = 0; r < grid.rows(); ++r) {
    for (int c = 0; c < grid.cols(); ++c) {
      const Vec2 p = grid.CellCenter({c, r});
      const bool burned = grid.StateAt({c, r}) != CellState::kUnburned;
      if (p.x() > 300.0) {
        ASSERT_FALSE(burned) << "cell at x=" << p.x() << " y=" << p.y() << " burned";
      }
      if (p.x() > 290.0 && p.x() < 300.0 && burned) ++burned_bank;
    }
  }
  EXPECT_GT(burned_bank, 50);  // the fire did reach the river
}

TEST(FireSpread, PolygonFuelIsRespected) {
  FireGrid grid(EastwardWindConfig(), MakeRng(11, "fire"));
  const std::vector<Vec2> lake = {Vec2(400, 200), Vec2(500, 250), Vec2(450, 400)};
  grid.SetFuelPolygon(lake, Fuel::kNone);
  EXPECT_EQ(grid.FuelAt(*grid.CellAt(Vec2(450.0, 280.0))), Fuel::kNone);
  EXPECT_EQ(grid.FuelAt(*grid.CellAt(Vec2(420.0, 380.0))), Fuel::kForest);
  EXPECT_THROW(grid.AddIgnition({Vec2(450.0, 280.0), 0.0}), std::invalid_argument);
}

}  // namespace
}  // namespace fireswarm::sim2d
