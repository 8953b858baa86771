// Drone-drone contacts only when altitude bands overlap, and near misses.
#include <gtest/gtest.h>

#include <cmath>

#include "fireswarm/sim2d/world.hpp"
#include "world_test_helpers.hpp"

namespace fireswarm::sim2d {
namespace {

using testing::CountEvents;
using testing::EventsOf;
using testing::FlyTo;
using testing::RunWith;

constexpr double kSeparationM = 3.0;

World TwoVehicles(Vec2 launch_a, Vec2 launch_b) {
  WorldConfig config;
  config.collision.near_miss_separation_m = kSeparationM;
  VehicleConfig a;
  a.id = 1;
  a.launch_position_m = launch_a;
  VehicleConfig b;
  b.id = 2;
  b.launch_position_m = launch_b;
  config.vehicles = {a, b};
  return World(config);
}

// Both climb to their heights over their launch points, then fly at each other
// along the east axis (each aims 20 m past the other's start).
void HeadOn(World& world, double altitude_a_m, double altitude_b_m, double max_speed_mps,
            double north_offset_m = 0.0) {
  RunWith(world, 12.0, [&] {
    world.SetCommand(1, FlyTo(world.Truth(1), Vec2(-20.0, 0.0), altitude_a_m));
    world.SetCommand(2, FlyTo(world.Truth(2), Vec2(20.0, north_offset_m), altitude_b_m));
  });
  RunWith(world, 20.0, [&] {
    world.SetCommand(1, FlyTo(world.Truth(1), Vec2(40.0, 0.0), altitude_a_m, max_speed_mps));
    world.SetCommand(
        2, FlyTo(world.Truth(2), Vec2(-40.0, north_offset_m), altitude_b_m, max_speed_mps));
  });
}

TEST(Collision, SameAltitudeVehiclesCollideAndTheCollisionIsRecorded) {
  World world = TwoVehicles(Vec2(-20.0, 0.0), Vec2(20.0, 0.0));
  HeadOn(world, 10.0, 10.0, 2.0);
  const auto collisions = EventsOf(world, EventKind::kCollision);
  ASSERT_GE(collisions.size(), 1U);
  EXPECT_EQ(collisions[0].vehicle_a, 1);
  EXPECT_EQ(collisions[0].vehicle_b, 2);
  // Both at about 2 m/s toward each other.
  EXPECT_NEAR(collisions[0].relative_speed_mps, 4.0, 0.6);
  EXPECT_GT(collisions[0].time_s, 12.0);
  // They bounced: still on their own sides, never through each other.
  EXPECT_LT(world.Truth(1).position_m.x(), world.Truth(2).position_m.x());
  const double gap_m = (world.Truth(1).position_m - world.Truth(2).position_m).norm();
  EXPECT_GT(gap_m, 0.45);  // two 0.25 m discs, less Box2D's slop
}

TEST(Collision, VehiclesInSeparateAltitudeBandsPassThroughEachOther) {
  World world = TwoVehicles(Vec2(-20.0, 0.0), Vec2(20.0, 0.0));
  HeadOn(world, 10.0, 12.0, 3.0);
  EXPECT_EQ(CountEvents(world, EventKind::kCollision), 0);
  EXPECT_GT(world.Truth(1).position_m.x(), world.Truth(2).position_m.x());  // crossed
  // One encounter, one near-miss event: at its closest they were 2 m apart, vertically.
  const auto near_misses = EventsOf(world, EventKind::kNearMiss);
  ASSERT_EQ(near_misses.size(), 1U);
  EXPECT_NEAR(near_misses[0].min_separation_m, 2.0, 0.1);
  EXPECT_FALSE(near_misses[0].open);
  EXPECT_NEAR(world.min_separation_m(), near_misses[0].min_separation_m, 1e-12);
}

TEST(Collision, NearMissIsOneEventPerEncounterWithItsMinimumSeparation) {
  // Same height, 1.5 m apart sideways: close, but the discs never touch.
  World world = TwoVehicles(Vec2(-20.0, 0.0), Vec2(20.0, 1.5));
  HeadOn(world, 10.0, 10.0, 3.0, 1.5);
  EXPECT_EQ(CountEvents(world, EventKind::kCollision), 0);
  const auto near_misses = EventsOf(world, EventKind::kNearMiss);
  ASSERT_EQ(near_misses.size(), 1U);
  EXPECT_NEAR(near_misses[0].min_separation_m, 1.5, 0.15);
  EXPECT_FALSE(near_misses[0].open);
}

TEST(Collision, VehicleDescendingIntoAnotherBandWhileDiscsOverlapCollides) {
  World world = TwoVehicles(Vec2(0.0, 0.0), Vec2(6.0, 0.0));
  // Vehicle 2 hovers 1.5 m above and 0.3 m east of vehicle 1: discs overlap, bands do not.
  const Vec2 above_m(0.3, 0.0);
  RunWith(world, 25.0, [&] {
    world.SetCommand(1, FlyTo(world.Truth(1), Vec2(0.0, 0.0), 10.0));
    const bool high_enough = world.Truth(2).altitude_m > 11.0;
    world.SetCommand(2, FlyTo(world.Truth(2), high_enough ? above_m : Vec2(6.0, 0.0), 11.5));
  });
  ASSERT_LT((world.Truth(2).position_m - world.Truth(1).position_m).norm(), 0.45);
  ASSERT_EQ(CountEvents(world, EventKind::kCollision), 0);
  const double descent_start_s = world.time_s();
  RunWith(world, 5.0, [&] {
    world.SetCommand(1, FlyTo(world.Truth(1), Vec2(0.0, 0.0), 10.0));
    world.SetCommand(2, FlyTo(world.Truth(2), above_m, 9.0));
  });
  const auto collisions = EventsOf(world, EventKind::kCollision);
  ASSERT_GE(collisions.size(), 1U);
  EXPECT_GT(collisions[0].time_s, descent_start_s);
  // The contact began when the bands met: 0.15 m apart (two 0.075 m half-heights).
  EXPECT_LT(collisions[0].min_separation_m, 0.5);
  EXPECT_GT(collisions[0].relative_speed_mps, 0.3);  // mostly the descent rate
}

TEST(Collision, HardCollisionCrashesBothVehicles) {
  World world = TwoVehicles(Vec2(-20.0, 0.0), Vec2(20.0, 0.0));
  HeadOn(world, 10.0, 10.0, 6.0);
  const auto collisions = EventsOf(world, EventKind::kCollision);
  ASSERT_GE(collisions.size(), 1U);
  EXPECT_GT(collisions[0].relative_speed_mps, 4.0);
  EXPECT_EQ(world.Truth(1).phase, FlightPhase::kCrashed);
  EXPECT_EQ(world.Truth(2).phase, FlightPhase::kCrashed);
  const auto crashes = EventsOf(world, EventKind::kCrash);
  ASSERT_GE(crashes.size(), 2U);
  EXPECT_EQ(crashes[0].vehicle_b, 2);         // crashed into vehicle 2
  EXPECT_EQ(world.Truth(1).altitude_m, 0.0);  // fell down
}

TEST(Collision, VehiclesStandingApartOnTheGroundRecordNothing) {
  World world = TwoVehicles(Vec2(0.0, 0.0), Vec2(1.0, 0.0));
  world.RunFor(5.0);
  EXPECT_TRUE(world.events().empty());
  EXPECT_TRUE(std::isinf(world.min_separation_m()));
}

}  // namespace
}  // namespace fireswarm::sim2d
