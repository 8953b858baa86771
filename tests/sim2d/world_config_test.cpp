// WorldConfig::Validate: bad values are rejected with a message naming the field.
#include "fireswarm/sim2d/world_config.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "fireswarm/sim2d/world.hpp"

namespace fireswarm::sim2d {
namespace {

std::string ErrorOf(const WorldConfig& config) {
  try {
    config.Validate();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

WorldConfig WithVehicle(int id) {
  WorldConfig config;
  VehicleConfig vehicle;
  vehicle.id = id;
  config.vehicles.push_back(vehicle);
  return config;
}

TEST(WorldConfig, DefaultsAreValid) {
  EXPECT_EQ(ErrorOf(WithVehicle(1)), "");
}

TEST(WorldConfig, BadVehicleFieldIsNamedWithItsValue) {
  WorldConfig config = WithVehicle(3);
  config.vehicles[0].multirotor.mass_kg = -1.0;
  EXPECT_EQ(ErrorOf(config), "vehicle 3: multirotor.mass_kg must be > 0, got -1");
  EXPECT_THROW(World{config}, std::invalid_argument);
}

TEST(WorldConfig, BadWorldFieldsAreNamed) {
  WorldConfig config;
  config.step_s = 0.0;
  EXPECT_EQ(ErrorOf(config), "step_s must be > 0, got 0");
  config = WorldConfig{};
  config.collision.near_miss_separation_m = -2.0;
  EXPECT_EQ(ErrorOf(config), "collision.near_miss_separation_m must be > 0, got -2");
  config = WorldConfig{};
  config.substeps = 0;
  EXPECT_EQ(ErrorOf(config), "substeps must be >= 1, got 0");
  config = WorldConfig{};
  config.origin = common::LatLon{95.0, 0.0};
  EXPECT_NE(ErrorOf(config).find("origin"), std::string::npos);
}

TEST(WorldConfig, ThrustBelowWeightIsRejected) {
  WorldConfig config = WithVehicle(2);
  config.vehicles[0].multirotor.max_thrust_n = 10.0;  // 1.2 kg weighs 11.8 N
  EXPECT_EQ(ErrorOf(config),
            "vehicle 2: multirotor.max_thrust_n must exceed the weight (mass_kg * g) to fly, "
            "got 10");
}

TEST(WorldConfig, SensorRateAboveTheStepRateIsRejected) {
  WorldConfig config = WithVehicle(5);
  config.vehicles[0].sensors.attitude.rate_hz = 500.0;  // step 10 ms
  EXPECT_EQ(ErrorOf(config),
            "vehicle 5: sensors.attitude.rate_hz must be <= 100 (one sample per step at most: "
            "1 / step_s), got 500");
  config.step_s = 0.002;
  EXPECT_EQ(ErrorOf(config), "");
}

TEST(WorldConfig, BadFaultsAreRejected) {
  WorldConfig config = WithVehicle(4);
  FaultSpec fault;
  fault.start_s = 5.0;
  fault.end_s = 3.0;
  config.vehicles[0].faults.push_back(fault);
  EXPECT_EQ(ErrorOf(config), "vehicle 4: fault.end_s must be > start_s, got 3");
  config.vehicles[0].faults[0] = FaultSpec{};
  config.vehicles[0].faults[0].kind = FaultKind::kExtraNoise;
  config.vehicles[0].faults[0].noise_factor = 0.5;
  EXPECT_EQ(ErrorOf(config), "vehicle 4: fault.noise_factor must be >= 1, got 0.5");
}

TEST(WorldConfig, DuplicateAndInvalidIdsAreRefused) {
  WorldConfig config = WithVehicle(7);
  config.vehicles.push_back(config.vehicles[0]);
  config.vehicles[1].launch_position_m = Vec2(5.0, 0.0);
  EXPECT_EQ(ErrorOf(config), "vehicles: duplicate id 7");
  EXPECT_EQ(ErrorOf(WithVehicle(0)), "vehicle id must be >= 1, got 0");
}

TEST(WorldConfig, WorldRefusesDuplicatesAddedLater) {
  World world(WithVehicle(7));
  try {
    world.AddVehicle(7, Vec2(10.0, 0.0));
    FAIL() << "duplicate accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()), "vehicle 7: duplicate receiver id");
  }
  EXPECT_EQ(world.vehicle_count(), 1U);
  FaultSpec bad;
  bad.end_s = -1.0;
  EXPECT_THROW(world.ScheduleFault(7, bad), std::invalid_argument);
  EXPECT_THROW(world.ScheduleFault(8, FaultSpec{}), std::out_of_range);
}

}  // namespace
}  // namespace fireswarm::sim2d
