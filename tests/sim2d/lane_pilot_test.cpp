#include "fireswarm/sim2d/lane_pilot.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "fireswarm/sim2d/world.hpp"
#include "world_test_helpers.hpp"

namespace fireswarm::sim2d {
namespace {

using testing::VehicleAt;

LanePilotParams BadAltitude() {
  LanePilotParams params;
  params.altitude_m = -1.0;
  return params;
}

TEST(LanePilot, FliesEveryWaypointAtAltitudeAndLands) {
  WorldConfig config;
  config.vehicles.push_back(VehicleAt(1, Vec2(0.0, 0.0)));
  World world(config);
  LanePilotParams params;
  params.altitude_m = 30.0;
  params.speed_mps = 8.0;
  LanePilot pilot({Vec2(0.0, 100.0), Vec2(60.0, 100.0), Vec2(60.0, 0.0)}, params);
  double max_altitude_m = 0.0;
  double closest_to_corner_m = 1e9;
  for (int step = 0;
       step < 12'000 && !(pilot.finished() && world.Truth(1).phase == FlightPhase::kOnGround);
       ++step) {
    world.SetCommand(1, pilot.Command(world.Truth(1)));
    world.Step();
    const VehicleTruth& truth = world.Truth(1);
    max_altitude_m = std::max(max_altitude_m, truth.altitude_m);
    closest_to_corner_m =
        std::min(closest_to_corner_m, (truth.position_m - Vec2(60.0, 100.0)).norm());
  }
  EXPECT_TRUE(pilot.finished());
  EXPECT_EQ(world.Truth(1).phase, FlightPhase::kOnGround);
  EXPECT_LT((world.Truth(1).position_m - Vec2(60.0, 0.0)).norm(), 10.0);
  EXPECT_NEAR(max_altitude_m, 30.0, 3.0);
  EXPECT_LT(closest_to_corner_m, params.acceptance_radius_m);
  for (const WorldEvent& event : world.events()) EXPECT_NE(event.kind, EventKind::kCrash);
}

TEST(LanePilot, LawnmowerLanesAreSpacedAndAlternate) {
  const auto lanes = LawnmowerLanes(Vec2(0.0, 0.0), Vec2(100.0, 50.0), 20.0);
  ASSERT_EQ(lanes.size(), 10U);  // lanes at x = 10, 30, 50, 70, 90
  EXPECT_DOUBLE_EQ(lanes[0].x(), 10.0);
  EXPECT_DOUBLE_EQ(lanes[0].y(), 0.0);
  EXPECT_DOUBLE_EQ(lanes[1].y(), 50.0);
  EXPECT_DOUBLE_EQ(lanes[2].x(), 30.0);
  EXPECT_DOUBLE_EQ(lanes[2].y(), 50.0);
  EXPECT_THROW(LawnmowerLanes(Vec2(0.0, 0.0), Vec2(1.0, 1.0), 0.0), std::invalid_argument);
  EXPECT_THROW(LanePilot({}, BadAltitude()), std::invalid_argument);
}

}  // namespace
}  // namespace fireswarm::sim2d
