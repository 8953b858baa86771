// The vehicle's safety behaviours in closed loop: return to launch and land when
// the server falls silent or the battery runs low.
#include <gtest/gtest.h>

#include "hil_test_helpers.hpp"

namespace fireswarm::hil {
namespace {

using radio::FlightMode;
using sim2d::Vec2;
using testing::Mission;
using testing::OneVehicleWorld;
using testing::RunUntilOr;
using testing::WaypointAt;

constexpr double kHomeToleranceM = 8.0;

// A vehicle flying a 2 km lane north of its launch point.
Mission& StartLongLane(Mission& mission) {
  mission.AddVehicle(agents::VehicleConfig{});
  mission.RunUntil(1.0);
  mission.link.UploadAndStart(1, 5,
                              {WaypointAt(mission, Vec2(0.0, 0.0), 60.0, /*lane_start=*/true),
                               WaypointAt(mission, Vec2(0.0, 2000.0), 60.0)});
  agents::Vehicle& vehicle = *mission.vehicles[0];
  RunUntilOr(mission, 60.0, [&] { return vehicle.mode() == FlightMode::kSearch; });
  return mission;
}

TEST(VehicleSafety, ReturnsAndLandsWhenTheServerFallsSilent) {
  Mission mission(OneVehicleWorld());
  StartLongLane(mission);
  agents::Vehicle& vehicle = *mission.vehicles[0];
  ASSERT_EQ(vehicle.mode(), FlightMode::kSearch);
  mission.RunUntil(mission.simulation.time_s() + 20.0);
  const double silent_from_s = mission.simulation.time_s();
  mission.radio_on = false;
  const double timeout_s = vehicle.params().Get(agents::ParamId::kLinkLostTimeoutS);
  // Still searching just before the timeout, returning just after it.
  mission.RunUntil(silent_from_s + timeout_s - 1.0);
  EXPECT_EQ(vehicle.mode(), FlightMode::kSearch);
  mission.RunUntil(silent_from_s + timeout_s + 1.0);
  EXPECT_EQ(vehicle.mode(), FlightMode::kReturnToLaunch);
  EXPECT_EQ(vehicle.stats().link_lost_returns, 1U);
  RunUntilOr(mission, 600.0, [&] { return vehicle.mode() == FlightMode::kLanded; });
  EXPECT_EQ(vehicle.mode(), FlightMode::kLanded);
  // Home, to GPS accuracy: home is where GPS said at take-off, and the receiver's
  // bias (1.8 m per axis, 60 s correlation) has moved on since.
  EXPECT_LT(mission.Truth(1).position_m.norm(), kHomeToleranceM);
  EXPECT_EQ(mission.Truth(1).phase, sim2d::FlightPhase::kOnGround);
}

TEST(VehicleSafety, ReturnsAndLandsOnLowBattery) {
  sim2d::SimulationConfig config = OneVehicleWorld();
  config.world.vehicles[0].multirotor.battery.initial_fraction = 0.3;
  Mission mission(config);
  StartLongLane(mission);
  agents::Vehicle& vehicle = *mission.vehicles[0];
  ASSERT_EQ(vehicle.mode(), FlightMode::kSearch);
  const double threshold = vehicle.params().Get(agents::ParamId::kRtlBatteryFraction);
  RunUntilOr(mission, 600.0, [&] { return vehicle.mode() != FlightMode::kSearch; });
  EXPECT_EQ(vehicle.mode(), FlightMode::kReturnToLaunch);
  EXPECT_EQ(vehicle.stats().low_battery_returns, 1U);
  EXPECT_LT(mission.Truth(1).battery_fraction, threshold + 0.01);
  // Nothing sends it away again on that battery: resume, investigate, a mission.
  radio::Command command;
  command.type = radio::CommandType::kInvestigate;
  command.lat_deg = mission.ToLatLon(Vec2(0.0, 500.0)).lat_deg;
  command.lon_deg = mission.ToLatLon(Vec2(0.0, 500.0)).lon_deg;
  mission.link.server().SendCommand(1, command);
  command.type = radio::CommandType::kStartMission;
  command.mission_id = 5;
  mission.link.server().SendCommand(1, command);
  mission.RunUntil(mission.simulation.time_s() + 3.0);
  EXPECT_EQ(vehicle.mode(), FlightMode::kReturnToLaunch);
  EXPECT_EQ(vehicle.stats().commands_rejected, 2U);
  RunUntilOr(mission, 900.0, [&] { return vehicle.mode() == FlightMode::kLanded; });
  EXPECT_EQ(vehicle.mode(), FlightMode::kLanded);
  EXPECT_LT(mission.Truth(1).position_m.norm(), kHomeToleranceM);
  EXPECT_GT(mission.Truth(1).battery_fraction, 0.0);  // landed with charge left
}

TEST(VehicleSafety, AFreshPackAfterTheCrewsSwapLetsTheNextSortieStart) {
  constexpr double kSwapS = 60.0;
  sim2d::SimulationConfig config = OneVehicleWorld();
  config.world.vehicles[0].multirotor.battery.initial_fraction = 0.3;
  config.world.battery_swap_s = kSwapS;
  Mission mission(config);
  StartLongLane(mission);
  agents::Vehicle& vehicle = *mission.vehicles[0];
  RunUntilOr(mission, 900.0, [&] { return vehicle.mode() == FlightMode::kLanded; });
  ASSERT_EQ(vehicle.mode(), FlightMode::kLanded);
  ASSERT_EQ(vehicle.stats().low_battery_returns, 1U);
  const double landed_s = mission.simulation.time_s();
  // The next sortie, stored while it waits: refused on the low pack...
  mission.link.UploadAndStart(1, 6,
                              {WaypointAt(mission, Vec2(0.0, 300.0), 60.0, /*lane_start=*/true),
                               WaypointAt(mission, Vec2(0.0, 600.0), 60.0)});
  mission.RunUntil(landed_s + 10.0);
  EXPECT_EQ(vehicle.mode(), FlightMode::kLanded);
  EXPECT_GE(vehicle.stats().commands_rejected, 1U);
  // ...accepted on the crew's fresh one, and flown.
  mission.RunUntil(landed_s + kSwapS + 1.0);
  EXPECT_GT(mission.Truth(1).battery_fraction, 0.99);
  radio::Command start;
  start.type = radio::CommandType::kStartMission;
  start.mission_id = 6;
  mission.link.server().SendCommand(1, start);
  RunUntilOr(mission, landed_s + kSwapS + 60.0,
             [&] { return vehicle.mode() == FlightMode::kSearch; });
  EXPECT_EQ(vehicle.mode(), FlightMode::kSearch);
  EXPECT_EQ(vehicle.active_mission(), 6);
}

}  // namespace
}  // namespace fireswarm::hil
