// The golden-hash test (STYLE 5): a fixed scenario run twice gives the same final
// state hash; a different seed gives a different one.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "fireswarm/sim2d/world.hpp"
#include "world_test_helpers.hpp"

namespace fireswarm::sim2d {
namespace {

// 16 vehicles on a 4 x 4 grid with gusty wind, a few faults, flying crossing
// patterns at two heights (some pairs meet in one band), for 40 s.
std::uint64_t RunScenario(std::uint64_t seed) {
  WorldConfig config;
  config.seed = seed;
  config.wind = WindParams{4.0, 240.0, 1.0, 3.0};
  config.collision.near_miss_separation_m = 4.0;
  for (int i = 0; i < 16; ++i) {
    VehicleConfig vehicle;
    vehicle.id = 10 + i;
    vehicle.launch_position_m = Vec2(8.0 * (i % 4), 8.0 * (i / 4));
    if (i == 3) {
      FaultSpec ballast;
      ballast.kind = FaultKind::kBallast;
      ballast.start_s = 10.0;
      ballast.ballast_offset_m = Vec2(0.0, 0.005);
      vehicle.faults.push_back(ballast);
    }
    if (i == 7) {
      FaultSpec loss;
      loss.kind = FaultKind::kTotalLoss;
      loss.start_s = 25.0;
      vehicle.faults.push_back(loss);
    }
    config.vehicles.push_back(vehicle);
  }
  World world(config);
  testing::RunWith(world, 40.0, [&] {
    for (const VehicleTruth& truth : world.Truths()) {
      const int k = truth.id - 10;
      const double phase = world.time_s() * 0.2 + k;
      const Vec2 target(12.0 + 15.0 * std::cos(phase), 12.0 + 15.0 * std::sin(phase));
      world.SetCommand(truth.id, testing::FlyTo(truth, target, 8.0 + 2.0 * (k % 2), 5.0));
    }
  });
  EXPECT_GT(world.events().size(), 16U);  // take-offs at least; near misses too
  return world.StateHash();
}

TEST(Determinism, SameSeedSameHash) {
  const std::uint64_t first = RunScenario(42);
  const std::uint64_t second = RunScenario(42);
  EXPECT_EQ(first, second);
}

TEST(Determinism, DifferentSeedDifferentHash) {
  EXPECT_NE(RunScenario(42), RunScenario(43));
}

TEST(Determinism, HashSeesASmallStateChange) {
  WorldConfig config;
  config.vehicles.push_back(VehicleConfig{});
  World a(config);
  World b(config);
  a.RunFor(1.0);
  b.RunFor(1.0);
  EXPECT_EQ(a.StateHash(), b.StateHash());
  ActuatorCommand command = testing::Climb(1.0);
  a.SetCommand(1, command);
  command.climb_rate_mps = 1.0 + 1e-9;
  b.SetCommand(1, command);
  a.RunFor(3.0);
  b.RunFor(3.0);
  EXPECT_NE(a.StateHash(), b.StateHash());
}

}  // namespace
}  // namespace fireswarm::sim2d
