// World bookkeeping: vehicles, time, lookups, spans, wind convention.
#include "fireswarm/sim2d/world.hpp"

#include <box2d/b2_timer.h>
#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <thread>

#include "world_test_helpers.hpp"

namespace fireswarm::sim2d {
namespace {

TEST(World, VehiclesStartOnTheGroundAtTheirLaunchPointsInInsertionOrder) {
  World world(WorldConfig{});
  world.AddVehicle(5, Vec2(10.0, -3.0));
  VehicleConfig second;
  second.id = 2;
  second.launch_position_m = Vec2(-4.0, 8.0);
  second.launch_heading_rad = -std::numbers::pi / 2.0;
  world.AddVehicle(second);
  ASSERT_EQ(world.vehicle_count(), 2U);
  ASSERT_EQ(world.Truths().size(), 2U);
  EXPECT_EQ(world.Truths()[0].id, 5);
  EXPECT_EQ(world.Truths()[1].id, 2);
  EXPECT_EQ(world.IndexOf(2), 1U);
  EXPECT_TRUE(world.HasVehicle(5));
  EXPECT_FALSE(world.HasVehicle(6));
  const VehicleTruth& truth = world.Truth(2);
  EXPECT_EQ(truth.phase, FlightPhase::kOnGround);
  EXPECT_EQ(truth.position_m, Vec2(-4.0, 8.0));
  EXPECT_NEAR(truth.heading_rad, 1.5 * std::numbers::pi, 1e-12);  // wrapped to [0, 2 pi)
  EXPECT_EQ(truth.battery_fraction, 1.0);
  world.RunFor(1.0);
  EXPECT_NEAR(world.Truth(5).position_m.x(), 10.0, 1e-5);  // Box2D keeps floats
  EXPECT_EQ(world.Truth(5).altitude_m, 0.0);
}

// sim2d replaces Box2D's profiling timer (world.cpp): no clock read per
// b2World::Step. Were the library's own in use, 5 ms would read as 5 ms.
TEST(World, Box2dProfilingReadsNoClock) {
  b2Timer timer;
  std::this_thread::sleep_for(std::chrono::milliseconds(5));
  EXPECT_EQ(timer.GetMilliseconds(), 0.0F);
}

TEST(World, TimeAdvancesByFixedSteps) {
  WorldConfig config;
  config.step_s = 0.004;
  config.substeps = 2;
  World world(config);
  EXPECT_EQ(world.time_s(), 0.0);
  world.Step();
  EXPECT_EQ(world.step_count(), 1);
  EXPECT_DOUBLE_EQ(world.time_s(), 0.004);
  world.RunFor(1.0);
  EXPECT_EQ(world.step_count(), 251);
  EXPECT_DOUBLE_EQ(world.time_s(), 251 * 0.004);
}

TEST(World, UnknownIdsThrowOutOfRange) {
  World world(WorldConfig{});
  world.AddVehicle(1, Vec2::Zero());
  EXPECT_THROW(world.Truth(2), std::out_of_range);
  EXPECT_THROW(world.Sensors(2), std::out_of_range);
  EXPECT_THROW(world.SetCommand(2, ActuatorCommand{}), std::out_of_range);
  EXPECT_THROW(world.SetCommandAt(1, ActuatorCommand{}), std::out_of_range);
}

TEST(World, SensorSpanIsAlignedWithTruths) {
  World world(WorldConfig{});
  world.AddVehicle(3, Vec2(0.0, 0.0));
  world.AddVehicle(9, Vec2(50.0, 0.0));
  world.Step();
  ASSERT_EQ(world.AllSensors().size(), 2U);
  EXPECT_EQ(&world.AllSensors()[1], &world.Sensors(9));
}

TEST(World, CommandsByIndexFlyTheSameVehicle) {
  World world(WorldConfig{});
  world.AddVehicle(3, Vec2(0.0, 0.0));
  world.SetCommandAt(world.IndexOf(3), testing::Climb(1.0));
  world.RunFor(3.0);
  EXPECT_EQ(world.Truth(3).phase, FlightPhase::kFlying);
}

TEST(World, WindBlowsFromItsBearing) {
  WorldConfig config;
  config.wind.speed_mps = 3.0;
  config.wind.from_deg = 90.0;  // from the east: the air moves west
  World world(config);
  EXPECT_NEAR(world.wind_mps().x(), -3.0, 1e-12);
  EXPECT_NEAR(world.wind_mps().y(), 0.0, 1e-12);
}

TEST(World, GustsWanderAroundTheSteadyWind) {
  WorldConfig config;
  config.wind.speed_mps = 3.0;
  config.wind.gust_std_mps = 1.0;
  config.wind.gust_time_constant_s = 2.0;
  World world(config);
  double sum_sq = 0.0;
  int samples = 0;
  for (int step = 0; step < 60000; ++step) {
    world.Step();
    const Vec2 gust = world.wind_mps() - Vec2(0.0, -3.0);
    sum_sq += gust.squaredNorm();
    ++samples;
  }
  EXPECT_NEAR(std::sqrt(sum_sq / (2.0 * samples)), 1.0, 0.2);
}

TEST(World, MovedWorldKeepsWorking) {
  World world(WorldConfig{});
  world.AddVehicle(1, Vec2::Zero());
  World moved = std::move(world);
  moved.SetCommand(1, testing::Climb(1.0));
  moved.RunFor(2.0);
  EXPECT_EQ(moved.Truth(1).phase, FlightPhase::kFlying);
}

}  // namespace
}  // namespace fireswarm::sim2d
