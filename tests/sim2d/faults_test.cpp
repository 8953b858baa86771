// Scheduled faults: stream cut, frozen value, bias, extra noise, ballast, total loss.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "fault_state.hpp"
#include "fireswarm/sim2d/world.hpp"
#include "world_test_helpers.hpp"

namespace fireswarm::sim2d {
namespace {

using testing::CountEvents;
using testing::FlyTo;
using testing::Hover;
using testing::RunWith;

World OneVehicle(const std::vector<FaultSpec>& faults) {
  WorldConfig config;
  VehicleConfig vehicle;
  vehicle.faults = faults;
  config.vehicles.push_back(vehicle);
  return World(config);
}

FaultSpec Fault(FaultKind kind, SensorKind sensor, double start_s, double end_s) {
  FaultSpec fault;
  fault.kind = kind;
  fault.sensor = sensor;
  fault.start_s = start_s;
  fault.end_s = end_s;
  return fault;
}

TEST(FaultState, FoldsTheFaultsActiveAtATime) {
  FaultSpec bias = Fault(FaultKind::kBias, SensorKind::kBaro, 1.0, 2.0);
  bias.bias = Eigen::Vector3d(3.0, 0.0, 0.0);
  const FaultSpec loss = Fault(FaultKind::kTotalLoss, SensorKind::kGps, 5.0, 5.5);
  const std::vector<FaultSpec> faults{bias, loss};
  EXPECT_EQ(ActiveFaults(faults, 0.5).sensor(SensorKind::kBaro).bias.x(), 0.0);
  EXPECT_EQ(ActiveFaults(faults, 1.0).sensor(SensorKind::kBaro).bias.x(), 3.0);
  EXPECT_EQ(ActiveFaults(faults, 2.0).sensor(SensorKind::kBaro).bias.x(), 0.0);
  EXPECT_FALSE(ActiveFaults(faults, 4.9).lost);
  EXPECT_TRUE(ActiveFaults(faults, 100.0).lost);  // a loss has no end
}

TEST(Faults, StreamCutDeliversNothingDuringItsWindow) {
  World world = OneVehicle({Fault(FaultKind::kStreamCut, SensorKind::kGps, 2.0, 4.0)});
  int before = 0;
  int during = 0;
  int after = 0;
  int attitude_during = 0;
  for (int step = 0; step < 600; ++step) {
    world.Step();
    const SensorSample& s = world.Sensors(1);
    const double t = world.time_s();
    if (s.gps) (t < 2.0 ? before : t < 4.0 ? during : after) += 1;
    if (s.attitude && t >= 2.0 && t < 4.0) ++attitude_during;
  }
  EXPECT_EQ(during, 0);
  EXPECT_GE(before, 19);
  EXPECT_GE(after, 19);
  EXPECT_EQ(attitude_during, 200);  // the other sensors carry on
}

TEST(Faults, FrozenSensorRepeatsItsLastValue) {
  World world = OneVehicle({Fault(FaultKind::kFrozen, SensorKind::kBaro, 2.0, 4.0)});
  double last_before = 0.0;
  std::vector<double> during;
  std::vector<double> after;
  for (int step = 0; step < 600; ++step) {
    world.Step();
    const SensorSample& s = world.Sensors(1);
    if (!s.baro) continue;
    const double t = s.baro->time_s;
    if (t < 2.0)
      last_before = s.baro->altitude_m;
    else if (t < 4.0)
      during.push_back(s.baro->altitude_m);
    else
      after.push_back(s.baro->altitude_m);
  }
  ASSERT_EQ(during.size(), 50U);  // still at 25 Hz
  for (const double value : during) EXPECT_EQ(value, last_before);
  ASSERT_GE(after.size(), 2U);
  EXPECT_NE(after[0], after[1]);  // alive again
}

// The same world twice, one with a fault: same seed, so the same noise draws,
// and the readings differ by exactly what the fault does.
struct Twins {
  World clean;
  World faulty;
};

Twins MakeTwins(const FaultSpec& fault) {
  return Twins{OneVehicle({}), OneVehicle({fault})};
}

TEST(Faults, BiasShiftsTheReadingsByItsValue) {
  FaultSpec fault = Fault(FaultKind::kBias, SensorKind::kGps, 0.0, 100.0);
  fault.bias = Eigen::Vector3d(10.0, -4.0, 2.0);
  Twins twins = MakeTwins(fault);
  int compared = 0;
  for (int step = 0; step < 500; ++step) {
    twins.clean.Step();
    twins.faulty.Step();
    const auto& clean = twins.clean.Sensors(1).gps;
    const auto& faulty = twins.faulty.Sensors(1).gps;
    ASSERT_EQ(clean.has_value(), faulty.has_value());
    if (!clean) continue;
    const common::EastNorth a = twins.clean.frame().ToLocal(clean->position);
    const common::EastNorth b = twins.faulty.frame().ToLocal(faulty->position);
    EXPECT_NEAR(b.east_m - a.east_m, 10.0, 1e-6);
    EXPECT_NEAR(b.north_m - a.north_m, -4.0, 1e-6);
    EXPECT_NEAR(faulty->altitude_m - clean->altitude_m, 2.0, 1e-9);
    ++compared;
  }
  EXPECT_EQ(compared, 50);
}

TEST(Faults, ExtraNoiseScalesTheNoise) {
  FaultSpec fault = Fault(FaultKind::kExtraNoise, SensorKind::kAttitude, 0.0, 100.0);
  fault.noise_factor = 5.0;
  Twins twins = MakeTwins(fault);
  double clean_sq = 0.0;
  double faulty_sq = 0.0;
  for (int step = 0; step < 2000; ++step) {
    twins.clean.Step();
    twins.faulty.Step();
    const double truth = twins.clean.Truth(1).roll_rad;  // on the ground: 0
    const double clean = twins.clean.Sensors(1).attitude->roll_rad - truth;
    const double faulty = twins.faulty.Sensors(1).attitude->roll_rad - truth;
    clean_sq += clean * clean;
    faulty_sq += faulty * faulty;
  }
  const double clean_std = std::sqrt(clean_sq / 2000.0);
  EXPECT_NEAR(clean_std, 0.0087, 0.001);
  EXPECT_NEAR(std::sqrt(faulty_sq / 2000.0) / clean_std, 5.0, 1e-6);
}

TEST(Faults, BallastMakesTheAttitudeDriftFromTheCommand) {
  FaultSpec fault = Fault(FaultKind::kBallast, SensorKind::kGps, 30.0, 1000.0);
  fault.ballast_offset_m = Vec2(0.01, 0.0);  // 1 cm forward: nose down
  World world = OneVehicle({fault});
  testing::TakeOffTo(world, 1, 10.0);  // 15 s
  world.RunFor(30.0 - world.time_s());
  EXPECT_NEAR(world.Truth(1).pitch_rad, 0.0, 1e-9);
  world.RunFor(2.0);
  // m g d / (I / tau^2) = 1.2 * 9.81 * 0.01 / (0.015 / 0.0225) = 0.1765 rad.
  EXPECT_NEAR(world.Truth(1).pitch_rad, -0.1765, 0.002);
  EXPECT_GT(world.Truth(1).velocity_mps.y(), 1.0);  // drifting forward (north)
  // A controller that trims the offset holds the vehicle level again.
  ActuatorCommand trimmed = Hover();
  trimmed.pitch_rad = 0.1765;
  world.SetCommand(1, trimmed);
  world.RunFor(2.0);
  EXPECT_NEAR(world.Truth(1).pitch_rad, 0.0, 0.002);
}

TEST(Faults, TotalLossRemovesTheVehicleFromSensorsAndCollisions) {
  WorldConfig config;
  config.collision.near_miss_separation_m = 3.0;
  VehicleConfig lost;
  lost.id = 1;
  lost.faults.push_back(Fault(FaultKind::kTotalLoss, SensorKind::kGps, 15.0, 16.0));
  VehicleConfig other;
  other.id = 2;
  other.launch_position_m = Vec2(20.0, 0.0);
  config.vehicles = {lost, other};
  World world(config);
  RunWith(world, 15.0, [&] {
    world.SetCommand(1, FlyTo(world.Truth(1), Vec2(0.0, 0.0), 10.0));
    world.SetCommand(2, FlyTo(world.Truth(2), Vec2(20.0, 0.0), 10.0));
  });
  ASSERT_EQ(world.Truth(1).phase, FlightPhase::kLost);
  EXPECT_EQ(CountEvents(world, EventKind::kLoss), 1);
  const Vec2 lost_at = world.Truth(1).position_m;
  // Vehicle 2 flies straight through where vehicle 1 vanished, at its height.
  RunWith(world, 20.0, [&] {
    world.SetCommand(2, FlyTo(world.Truth(2), Vec2(-20.0, 0.0), 10.0));
    const SensorSample& s = world.Sensors(1);
    EXPECT_FALSE(s.gps || s.baro || s.attitude || s.battery);
  });
  EXPECT_LT(world.Truth(2).position_m.x(), -15.0);
  EXPECT_EQ(world.Truth(1).position_m, lost_at);  // no longer moves
  EXPECT_EQ(world.Truth(1).velocity_mps, Vec2::Zero());
  EXPECT_EQ(world.Truth(1).phase, FlightPhase::kLost);
  EXPECT_EQ(CountEvents(world, EventKind::kCollision), 0);
  EXPECT_EQ(CountEvents(world, EventKind::kNearMiss), 0);
}

}  // namespace
}  // namespace fireswarm::sim2d
