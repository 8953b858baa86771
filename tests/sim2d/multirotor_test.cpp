// The multirotor plant: hover, tilt, drag, attitude lag, ground contact, battery.
#include <gtest/gtest.h>

#include <cmath>

#include "battery_model.hpp"
#include "fireswarm/sim2d/world.hpp"
#include "multirotor_dynamics.hpp"
#include "world_test_helpers.hpp"

namespace fireswarm::sim2d {
namespace {

using testing::Climb;
using testing::CountEvents;
using testing::Hover;
using testing::kG;
using testing::RunWith;
using testing::TakeOffTo;

World OneVehicle(const MultirotorParams& params = {}) {
  WorldConfig config;
  VehicleConfig vehicle;
  vehicle.id = 1;
  vehicle.multirotor = params;
  config.vehicles.push_back(vehicle);
  return World(config);
}

TEST(Multirotor, HoverHoldsAltitudeWithZeroClimbFor60s) {
  World world = OneVehicle();
  TakeOffTo(world, 1, 20.0);
  ASSERT_EQ(world.Truth(1).phase, FlightPhase::kFlying);
  const double start_m = world.Truth(1).altitude_m;
  EXPECT_NEAR(start_m, 20.0, 0.5);
  double low_m = start_m;
  double high_m = start_m;
  RunWith(world, 60.0, [&] {
    low_m = std::min(low_m, world.Truth(1).altitude_m);
    high_m = std::max(high_m, world.Truth(1).altitude_m);
  });
  EXPECT_LT(high_m - low_m, 0.05);
  EXPECT_EQ(world.Truth(1).phase, FlightPhase::kFlying);
  EXPECT_LT(world.Truth(1).velocity_mps.norm(), 1e-3);
}

TEST(Multirotor, HorizontalForceOfTiltedHoverThrustIsWeightTimesTanPitch) {
  const MultirotorParams params;
  VehicleTruth truth;
  truth.pitch_rad = -0.2;  // nose down, heading north
  const double thrust_n = params.mass_kg * kG / std::cos(truth.pitch_rad);
  const Vec2 force =
      HorizontalForce(params, truth, AttitudeTrig::Of(truth), thrust_n, Vec2::Zero());
  EXPECT_NEAR(force.y(), params.mass_kg * kG * std::tan(0.2), 1e-9);
  EXPECT_NEAR(force.x(), 0.0, 1e-12);
  truth.pitch_rad = 0.0;
  truth.roll_rad = 0.2;  // right wing down, heading north: east
  const Vec2 east = HorizontalForce(params, truth, AttitudeTrig::Of(truth), thrust_n, Vec2::Zero());
  EXPECT_NEAR(east.x(), params.mass_kg * kG * std::tan(0.2), 1e-9);
  truth.heading_rad = std::numbers::pi / 2.0;  // nose east, right wing down: south
  const Vec2 south =
      HorizontalForce(params, truth, AttitudeTrig::Of(truth), thrust_n, Vec2::Zero());
  EXPECT_NEAR(south.y(), -params.mass_kg * kG * std::tan(0.2), 1e-9);
}

TEST(Multirotor, TiltAcceleratesAtGTanPitch) {
  MultirotorParams params;
  params.linear_drag_n_per_mps = 0.0;
  params.quadratic_drag_n_per_mps2 = 0.0;
  World world = OneVehicle(params);
  TakeOffTo(world, 1, 20.0);
  ActuatorCommand command = Hover();
  command.pitch_rad = -0.2;
  world.SetCommand(1, command);
  world.RunFor(1.5);  // the attitude lag settles (tau 0.15 s)
  ASSERT_NEAR(world.Truth(1).pitch_rad, -0.2, 1e-4);
  const Vec2 v0 = world.Truth(1).velocity_mps;
  world.RunFor(1.0);
  const Vec2 accel = world.Truth(1).velocity_mps - v0;
  EXPECT_NEAR(accel.y(), kG * std::tan(0.2), 0.02 * kG * std::tan(0.2));
  EXPECT_NEAR(accel.x(), 0.0, 1e-3);
  EXPECT_NEAR(world.Truth(1).altitude_m, 20.0, 0.5);
}

TEST(Multirotor, DragLimitsSpeedToTheTerminalSpeedOfItsParameters) {
  const MultirotorParams params;
  World world = OneVehicle(params);
  TakeOffTo(world, 1, 20.0);
  const double pitch_rad = 0.3;
  ActuatorCommand command = Hover();
  command.pitch_rad = -pitch_rad;
  world.SetCommand(1, command);
  world.RunFor(40.0);
  // m g tan(pitch) = k1 v + k2 v^2
  const double push_n = params.mass_kg * kG * std::tan(pitch_rad);
  const double k1 = params.linear_drag_n_per_mps;
  const double k2 = params.quadratic_drag_n_per_mps2;
  const double terminal_mps = (-k1 + std::sqrt(k1 * k1 + 4.0 * k2 * push_n)) / (2.0 * k2);
  EXPECT_NEAR(world.Truth(1).velocity_mps.norm(), terminal_mps, 0.02 * terminal_mps);
  EXPECT_GT(terminal_mps, 5.0);
}

TEST(Multirotor, AttitudeFollowsCommandThroughLagAndRateLimit) {
  const MultirotorParams params;
  const MultirotorCoefficients c = MakeCoefficients(params, 0.001);
  VehicleTruth truth;
  ActuatorCommand command = Hover();
  command.roll_rad = 0.2;  // 0.2 / 0.15 s = 1.3 rad/s: within the rate limit
  for (int i = 0; i < 150; ++i) StepAttitude(params, c, command, Vec2::Zero(), truth);
  EXPECT_NEAR(truth.roll_rad, 0.2 * (1.0 - std::exp(-1.0)), 2e-3);
  // A step of 1 rad (clamped to the 0.61 rad tilt limit) would want 4 rad/s.
  VehicleTruth level;
  command.roll_rad = 1.0;
  StepAttitude(params, c, command, Vec2::Zero(), level);
  EXPECT_NEAR(level.roll_rate_radps, params.max_attitude_rate_radps, 1e-9);
  for (int i = 0; i < 3000; ++i) StepAttitude(params, c, command, Vec2::Zero(), level);
  EXPECT_NEAR(level.roll_rad, params.max_tilt_rad, 1e-6);
}

TEST(Multirotor, YawRateFollowsCommandAndHeadingIntegrates) {
  World world = OneVehicle();
  TakeOffTo(world, 1, 10.0);
  const double heading0 = world.Truth(1).heading_rad;
  ActuatorCommand command = Hover();
  command.yaw_rate_radps = 0.5;
  world.SetCommand(1, command);
  world.RunFor(2.0);
  EXPECT_NEAR(world.Truth(1).yaw_rate_radps, 0.5, 1e-3);
  // 2 s at 0.5 rad/s less the lag's 0.2 s * 0.5 rad/s.
  EXPECT_NEAR(world.Truth(1).heading_rad - heading0, 1.0 - 0.1, 0.01);
}

TEST(Multirotor, StaysOnGroundUntilClimbCommandedThenTakesOffAndLandsSoftly) {
  World world = OneVehicle();
  world.SetCommand(1, Hover());
  world.RunFor(3.0);
  EXPECT_EQ(world.Truth(1).phase, FlightPhase::kOnGround);
  EXPECT_EQ(world.Truth(1).altitude_m, 0.0);
  world.SetCommand(1, Climb(1.0));
  world.RunFor(5.0);
  EXPECT_EQ(world.Truth(1).phase, FlightPhase::kFlying);
  EXPECT_EQ(CountEvents(world, EventKind::kTakeOff), 1);
  EXPECT_NEAR(world.Truth(1).climb_rate_mps, 1.0, 0.01);
  world.SetCommand(1, Climb(-1.0));
  world.RunFor(10.0);
  EXPECT_EQ(world.Truth(1).phase, FlightPhase::kOnGround);
  EXPECT_EQ(CountEvents(world, EventKind::kLanding), 1);
  EXPECT_EQ(CountEvents(world, EventKind::kCrash), 0);
}

TEST(Multirotor, HardGroundHitCrashes) {
  World world = OneVehicle();
  TakeOffTo(world, 1, 10.0);
  world.SetCommand(1, Climb(-3.0));  // 3 m/s > the 2.5 m/s crash limit
  world.RunFor(10.0);
  EXPECT_EQ(world.Truth(1).phase, FlightPhase::kCrashed);
  const auto crashes = testing::EventsOf(world, EventKind::kCrash);
  ASSERT_EQ(crashes.size(), 1U);
  EXPECT_NEAR(crashes[0].relative_speed_mps, 3.0, 0.1);
  // A crashed vehicle does not take off again.
  world.SetCommand(1, Climb(2.0));
  world.RunFor(2.0);
  EXPECT_EQ(world.Truth(1).altitude_m, 0.0);
}

TEST(Multirotor, DisarmedInTheAirFallsAndCrashes) {
  World world = OneVehicle();
  TakeOffTo(world, 1, 10.0);
  world.SetCommand(1, ActuatorCommand{});
  world.RunFor(5.0);
  EXPECT_EQ(world.Truth(1).phase, FlightPhase::kCrashed);
  ASSERT_EQ(CountEvents(world, EventKind::kCrash), 1);
  EXPECT_GT(testing::EventsOf(world, EventKind::kCrash)[0].relative_speed_mps, 10.0);
}

TEST(Multirotor, BatteryPowerGrowsWithThrust) {
  const BatteryParams battery;
  const double reference_n = battery.reference_thrust_n;
  EXPECT_NEAR(BatteryPowerW(battery, reference_n),
              battery.reference_power_w + battery.avionics_power_w, 1e-9);
  // Momentum theory: 1.5 x the thrust costs 1.5^1.5 = 1.84 x the motor power.
  EXPECT_NEAR(BatteryPowerW(battery, 1.5 * reference_n) - battery.avionics_power_w,
              1.8371 * battery.reference_power_w, 0.01);
  EXPECT_NEAR(BatteryPowerW(battery, 0.0), battery.avionics_power_w, 1e-12);
}

TEST(Multirotor, HeavierVehicleDrainsItsBatteryFaster) {
  WorldConfig config;
  VehicleConfig light;
  light.id = 1;
  VehicleConfig heavy = light;
  heavy.id = 2;
  heavy.launch_position_m = Vec2(10.0, 0.0);
  heavy.multirotor.mass_kg = 1.8;  // hover needs 1.5 x the thrust
  config.vehicles = {light, heavy};
  World world(config);
  world.SetCommand(1, Climb(1.0));
  world.SetCommand(2, Climb(1.0));
  world.RunFor(5.0);
  world.SetCommand(1, Hover());
  world.SetCommand(2, Hover());
  world.RunFor(60.0);
  const double used_light = 1.0 - world.Truth(1).battery_fraction;
  const double used_heavy = 1.0 - world.Truth(2).battery_fraction;
  EXPECT_GT(used_light, 0.0);
  // Motor power ~ thrust^1.5: 1.5^1.5 = 1.84 times the motors' share.
  EXPECT_GT(used_heavy, 1.7 * used_light) << used_heavy << " vs " << used_light;
}

TEST(Multirotor, EmptyBatteryStopsTheMotorsAndTheVehicleFalls) {
  MultirotorParams params;
  params.battery.capacity_wh = 1.0;  // ~22 s of hover
  World world = OneVehicle(params);
  TakeOffTo(world, 1, 20.0);
  ASSERT_EQ(world.Truth(1).phase, FlightPhase::kFlying);
  world.RunFor(30.0);
  EXPECT_EQ(world.Truth(1).battery_fraction, 0.0);
  ASSERT_EQ(CountEvents(world, EventKind::kBatteryEmpty), 1);
  EXPECT_EQ(world.Truth(1).phase, FlightPhase::kCrashed);
  const auto empty = testing::EventsOf(world, EventKind::kBatteryEmpty)[0];
  const auto crash = testing::EventsOf(world, EventKind::kCrash)[0];
  EXPECT_GT(crash.time_s, empty.time_s);
  EXPECT_LT(crash.time_s - empty.time_s, 3.0);  // ~2 s fall from 20 m
}

TEST(Multirotor, EmptyBatteryOnTheGroundCannotTakeOff) {
  MultirotorParams params;
  params.battery.capacity_wh = 0.01;  // 36 J: the 4 W avionics empty it in 9 s
  World world = OneVehicle(params);
  world.RunFor(10.0);
  EXPECT_EQ(world.Truth(1).battery_fraction, 0.0);
  EXPECT_EQ(CountEvents(world, EventKind::kBatteryEmpty), 1);
  world.SetCommand(1, Climb(2.0));
  world.RunFor(3.0);
  EXPECT_EQ(world.Truth(1).phase, FlightPhase::kOnGround);
  EXPECT_EQ(world.Truth(1).altitude_m, 0.0);
  EXPECT_EQ(CountEvents(world, EventKind::kTakeOff), 0);
}

TEST(Multirotor, TheGroundCrewSwapsThePackSwapSecondsAfterALanding) {
  WorldConfig config;
  config.battery_swap_s = 60.0;
  VehicleConfig vehicle;
  vehicle.id = 1;
  config.vehicles.push_back(vehicle);
  World world(config);
  world.RunFor(100.0);  // standing from the start is no landing: no swap
  EXPECT_EQ(CountEvents(world, EventKind::kBatterySwap), 0);
  TakeOffTo(world, 1, 10.0);
  world.SetCommand(1, Hover());
  world.RunFor(20.0);
  RunWith(world, 30.0, [&] { world.SetCommand(1, Climb(-1.0)); });
  ASSERT_EQ(world.Truth(1).phase, FlightPhase::kOnGround);
  ASSERT_EQ(CountEvents(world, EventKind::kLanding), 1);
  const double landed_s = testing::EventsOf(world, EventKind::kLanding)[0].time_s;
  const double used = world.Truth(1).battery_fraction;
  EXPECT_LT(used, 1.0);
  world.SetCommand(1, ActuatorCommand{});  // disarmed on the ground
  world.RunFor(landed_s + 59.0 - world.time_s());
  EXPECT_EQ(CountEvents(world, EventKind::kBatterySwap), 0);
  world.RunFor(2.0);
  ASSERT_EQ(CountEvents(world, EventKind::kBatterySwap), 1);
  EXPECT_NEAR(testing::EventsOf(world, EventKind::kBatterySwap)[0].time_s, landed_s + 60.0, 0.02);
  EXPECT_GT(world.Truth(1).battery_fraction, 0.9999);
  world.RunFor(120.0);  // once per landing
  EXPECT_EQ(CountEvents(world, EventKind::kBatterySwap), 1);
}

TEST(Multirotor, SteadyWindCarriesAHoveringVehicleAtWindSpeed) {
  WorldConfig config;
  config.wind.speed_mps = 5.0;
  config.wind.from_deg = 0.0;  // from the north: the air moves south
  config.vehicles.push_back(VehicleConfig{});
  World world(config);
  EXPECT_NEAR(world.wind_mps().y(), -5.0, 1e-12);
  TakeOffTo(world, 1, 10.0);
  world.RunFor(60.0);
  EXPECT_NEAR(world.Truth(1).velocity_mps.y(), -5.0, 0.05);
  EXPECT_NEAR(world.Truth(1).velocity_mps.x(), 0.0, 0.05);
}

}  // namespace
}  // namespace fireswarm::sim2d
