// Where a fire is for scoring (FireHotCentre) and how random fires are placed
// (ExpandFires: inside the area, min_spacing_m apart).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

#include "fireswarm/run/scenario.hpp"
#include "fireswarm/sim2d/fire_grid.hpp"
#include "scoring.hpp"
#include "small_area.hpp"
#include "world_setup.hpp"

namespace fireswarm::run::internal {
namespace {

using sim2d::Vec2;

sim2d::FireGrid StillGrid() {
  sim2d::FireConfig config;
  config.wind_speed_mps = 0.0;
  config.jitter_fraction = 0.0;
  return sim2d::FireGrid(config, sim2d::MakeRng(1, "fire"));
}

TEST(FireHotCentre, IsTheCentreOfTheCellThatBurnsNotTheIgnitionPoint) {
  sim2d::FireGrid grid = StillGrid();
  const Vec2 ignition(501.0, 503.5);  // 1.5 m west and 1 m north of its cell's centre
  EXPECT_FALSE(FireHotCentre(grid, ignition).has_value());  // nothing burns yet
  grid.AddIgnition({ignition, 0.0});
  grid.AdvanceTo(1.0);
  const std::optional<Vec2> centre = FireHotCentre(grid, ignition);
  ASSERT_TRUE(centre.has_value());
  EXPECT_NEAR(centre->x(), 502.5, 1e-9);
  EXPECT_NEAR(centre->y(), 502.5, 1e-9);
}

TEST(FireHotCentre, FollowsTheSpreadButNotAnotherFire) {
  sim2d::FireGrid grid = StillGrid();
  const Vec2 ignition(502.5, 502.5);
  grid.AddIgnition({ignition, 0.0});
  grid.AddIgnition({Vec2(702.5, 502.5), 0.0});  // 200 m east: another fire
  grid.AddIgnition({Vec2(507.5, 502.5), 0.0});  // the next cell east: the same fire
  grid.AdvanceTo(1.0);
  const std::optional<Vec2> centre = FireHotCentre(grid, ignition);
  ASSERT_TRUE(centre.has_value());
  EXPECT_NEAR(centre->x(), 505.0, 1e-9);
  EXPECT_NEAR(centre->y(), 502.5, 1e-9);
}

TEST(FireHotCentre, IgnoresCellsCooledBelowWhatACameraSees) {
  sim2d::FireGrid grid = StillGrid();
  // One forest cell in bare ground: it burns, burns out and cools, alone.
  grid.SetFuelRect(Vec2(0.0, 0.0), Vec2(1000.0, 1000.0), sim2d::Fuel::kNone);
  grid.SetFuelRect(Vec2(501.0, 501.0), Vec2(504.0, 504.0), sim2d::Fuel::kForest);
  const Vec2 ignition(502.5, 502.5);
  grid.AddIgnition({ignition, 0.0});
  // Burned out after 600 s, then cooling from 300 C toward 25 C with a 600 s
  // time constant: 10 K over ambient at 600 + 600 ln(275 / 10) = 2,589 s.
  grid.AdvanceTo(2'550.0);
  EXPECT_TRUE(FireHotCentre(grid, ignition).has_value());
  grid.AdvanceTo(2'630.0);
  EXPECT_FALSE(FireHotCentre(grid, ignition).has_value());
}

// The small area with one fire and `random_fires` (a YAML mapping).
Scenario SmallArea(const std::string& random_fires) {
  return test::SmallArea("fires:\n  - {lat: 45.00230, lon: 7.00480, start_s: 0}\nrandom_fires: " +
                         random_fires + "\n");
}

TEST(ExpandFires, RandomFiresKeepTheirSpacingFromEveryFire) {
  const Scenario scenario = SmallArea("{count: 12, seed: 5, min_spacing_m: 90}");
  const std::vector<FireSpec> fires = ExpandFires(scenario);
  ASSERT_EQ(fires.size(), 13U);
  double closest_m = 1e9;
  for (std::size_t i = 0; i < fires.size(); ++i) {
    for (std::size_t j = i + 1; j < fires.size(); ++j) {
      const common::EastNorth a = scenario.area.frame.ToLocal(fires[i].position);
      const common::EastNorth b = scenario.area.frame.ToLocal(fires[j].position);
      closest_m = std::min(closest_m, std::hypot(a.east_m - b.east_m, a.north_m - b.north_m));
    }
  }
  EXPECT_GE(closest_m, 90.0);
  EXPECT_LT(closest_m, 150.0);  // 13 fires in 800 m x 500 m: some are near the limit
}

TEST(ExpandFires, TooManyFiresForTheSpacingIsAClearError) {
  // 800 m x 500 m cannot hold 40 fires 200 m apart.
  const Scenario scenario = SmallArea("{count: 40, seed: 5, min_spacing_m: 200}");
  try {
    ExpandFires(scenario);
    FAIL() << "40 fires 200 m apart were placed";
  } catch (const ScenarioError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("small_area.yaml"), std::string::npos) << what;
    EXPECT_NE(what.find("random_fires"), std::string::npos) << what;
    EXPECT_NE(what.find("min_spacing_m"), std::string::npos) << what;
  }
}

}  // namespace
}  // namespace fireswarm::run::internal
