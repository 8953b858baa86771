// The server's avoid order (CommandType::kAvoid) as the vehicle flies it, and the
// vehicle's own last line: home at its mission's way-home layer when the link is
// lost. Closed loop: the real vehicle over the radio, sim2d underneath.
#include <gtest/gtest.h>

#include <algorithm>

#include "hil_test_helpers.hpp"

namespace fireswarm::hil {
namespace {

using radio::FlightMode;
using sim2d::Vec2;
using testing::Mission;
using testing::OneVehicleWorld;
using testing::RunUntilOr;
using testing::WaypointAt;

// The altitude hold settles within this of its target (baro noise, gusts).
constexpr double kHoldToleranceM = 2.5;

radio::Command Avoid(double altitude_m, std::uint16_t duration_s) {
  radio::Command command;
  command.type = radio::CommandType::kAvoid;
  command.altitude_m = altitude_m;
  command.duration_s = duration_s;
  return command;
}

// A vehicle searching a 3 km lane north at 60 m, ending with a way home at 105 m.
agents::Vehicle& StartLane(Mission& mission) {
  agents::Vehicle& vehicle = mission.AddVehicle(agents::VehicleConfig{});
  mission.RunUntil(1.0);
  mission.link.UploadAndStart(1, 5,
                              {WaypointAt(mission, Vec2(0.0, 0.0), 60.0, /*lane_start=*/true),
                               WaypointAt(mission, Vec2(0.0, 3000.0), 60.0),
                               WaypointAt(mission, Vec2(0.0, 3000.0), 105.0)});
  RunUntilOr(mission, 90.0, [&] { return vehicle.mode() == FlightMode::kSearch; });
  return vehicle;
}

TEST(VehicleAvoid, ClimbsToTheOrderedAltitudeKeepsSearchingAndComesBackWhenItEnds) {
  Mission mission(OneVehicleWorld());
  agents::Vehicle& vehicle = StartLane(mission);
  ASSERT_EQ(vehicle.mode(), FlightMode::kSearch);
  RunUntilOr(mission, 200.0, [&] { return mission.Truth(1).altitude_m > 58.0; });
  const double ordered_s = mission.simulation.time_s();
  const double north_before_m = mission.Truth(1).position_m.y();
  mission.link.server().SendCommand(1, Avoid(80.0, 30), /*urgent=*/true);
  // 20 m at the vehicles' climb rate, after the radio: well inside 15 s.
  RunUntilOr(mission, ordered_s + 15.0,
             [&] { return mission.Truth(1).altitude_m > 80.0 - kHoldToleranceM; });
  EXPECT_GT(mission.Truth(1).altitude_m, 80.0 - kHoldToleranceM);
  EXPECT_EQ(vehicle.mode(), FlightMode::kSearch);
  EXPECT_EQ(vehicle.stats().avoid_orders, 1U);
  mission.RunUntil(ordered_s + 25.0);
  EXPECT_NEAR(mission.Truth(1).altitude_m, 80.0, kHoldToleranceM);
  EXPECT_GT(mission.Truth(1).position_m.y(), north_before_m + 150.0) << "kept flying its lane";
  // The order over, back to the lane's altitude.
  mission.RunUntil(ordered_s + 50.0);
  EXPECT_NEAR(mission.Truth(1).altitude_m, 60.0, kHoldToleranceM);
}

TEST(VehicleAvoid, ALandingWaitsLevelUntilTheOrderEnds) {
  Mission mission(OneVehicleWorld());
  agents::Vehicle& vehicle = StartLane(mission);
  RunUntilOr(mission, 200.0, [&] { return mission.Truth(1).altitude_m > 58.0; });
  radio::Command land;
  land.type = radio::CommandType::kLand;
  mission.link.server().SendCommand(1, land);
  RunUntilOr(mission, 300.0, [&] { return vehicle.mode() == FlightMode::kLand; });
  RunUntilOr(mission, 300.0, [&] { return mission.Truth(1).altitude_m < 45.0; });
  const double ordered_s = mission.simulation.time_s();
  mission.link.server().SendCommand(1, Avoid(45.0, 20), /*urgent=*/true);
  mission.RunUntil(ordered_s + 18.0);
  EXPECT_EQ(vehicle.mode(), FlightMode::kLand);
  EXPECT_GT(mission.Truth(1).altitude_m, 45.0 - 2.0 * kHoldToleranceM) << "it waited";
  RunUntilOr(mission, ordered_s + 200.0, [&] { return vehicle.mode() == FlightMode::kLanded; });
  EXPECT_EQ(vehicle.mode(), FlightMode::kLanded);
}

TEST(VehicleAvoid, IsRefusedOnTheGroundAndWithoutADuration) {
  Mission mission(OneVehicleWorld());
  agents::Vehicle& vehicle = mission.AddVehicle(agents::VehicleConfig{});
  mission.RunUntil(1.0);
  mission.link.server().SendCommand(1, Avoid(80.0, 30));
  mission.RunUntil(4.0);
  EXPECT_EQ(vehicle.stats().commands_rejected, 1U);
  EXPECT_EQ(vehicle.stats().avoid_orders, 0U);
  EXPECT_EQ(vehicle.mode(), FlightMode::kIdle);
  mission.link.server().SendCommand(1, Avoid(80.0, 0));
  mission.RunUntil(7.0);
  EXPECT_EQ(vehicle.stats().commands_rejected, 2U);
}

TEST(VehicleAvoid, WithTheLinkLostItFliesHomeAtItsMissionsWayHomeLayer) {
  Mission mission(OneVehicleWorld());
  agents::Vehicle& vehicle = StartLane(mission);
  RunUntilOr(mission, 200.0, [&] { return mission.Truth(1).position_m.y() > 400.0; });
  mission.radio_on = false;
  RunUntilOr(mission, 400.0, [&] { return vehicle.mode() == FlightMode::kReturnToLaunch; });
  ASSERT_EQ(vehicle.mode(), FlightMode::kReturnToLaunch);
  double highest_m = 0.0;
  double lowest_far_m = 1e9;  // lowest while still 150 m or more from home
  RunUntilOr(mission, 900.0, [&] {
    const sim2d::VehicleTruth& truth = mission.Truth(1);
    highest_m = std::max(highest_m, truth.altitude_m);
    if (truth.position_m.norm() > 150.0 && truth.position_m.y() < 250.0) {
      lowest_far_m = std::min(lowest_far_m, truth.altitude_m);
    }
    return vehicle.mode() == FlightMode::kLanded;
  });
  EXPECT_EQ(vehicle.mode(), FlightMode::kLanded);
  EXPECT_NEAR(highest_m, 105.0, kHoldToleranceM);
  // Near home it has long reached the layer: it flew home in it.
  EXPECT_GT(lowest_far_m, 105.0 - kHoldToleranceM);
}

TEST(VehicleAvoid, AnOrderHeldWhenTheLinkIsLostIsDroppedForTheWayHomeLayer) {
  // Ordered to 80 m for 10 minutes, then never heard again: a release could not
  // reach it, and the server predicts it home in its own layer.
  Mission mission(OneVehicleWorld());
  agents::Vehicle& vehicle = StartLane(mission);
  RunUntilOr(mission, 200.0, [&] { return mission.Truth(1).altitude_m > 58.0; });
  const double ordered_s = mission.simulation.time_s();
  mission.link.server().SendCommand(1, Avoid(80.0, 600), /*urgent=*/true);
  RunUntilOr(mission, ordered_s + 15.0,
             [&] { return mission.Truth(1).altitude_m > 80.0 - kHoldToleranceM; });
  ASSERT_EQ(vehicle.stats().avoid_orders, 1U);
  mission.radio_on = false;
  RunUntilOr(mission, ordered_s + 200.0,
             [&] { return vehicle.mode() == FlightMode::kReturnToLaunch; });
  ASSERT_EQ(vehicle.mode(), FlightMode::kReturnToLaunch);
  const double turned_s = mission.simulation.time_s();
  EXPECT_NEAR(mission.Truth(1).altitude_m, 80.0, kHoldToleranceM) << "held until it turned";
  // 25 m at the vehicles' climb rate: well inside 20 s, far from home still.
  mission.RunUntil(turned_s + 20.0);
  EXPECT_EQ(vehicle.mode(), FlightMode::kReturnToLaunch);
  EXPECT_NEAR(mission.Truth(1).altitude_m, 105.0, kHoldToleranceM);
}

}  // namespace
}  // namespace fireswarm::hil
