// What the server has each vehicle doing (TaskOf) and where its lanes are
// (LaneOf), through a server that talks to fake vehicles over the air.
#include "fireswarm/server/vehicle_task.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "fireswarm/server/server.hpp"
#include "server/fake_fleet.hpp"
#include "server/server_fixture.hpp"

namespace fireswarm::server {
namespace {

using common::Nanos;
using testing::Air;
using testing::kFrame;
using testing::kSecond;
using testing::LaneMissions;
using testing::Searching;
using testing::StartLaneMission;

radio::Waypoint Point(bool starts_lane) {
  radio::Waypoint w;
  w.flags = starts_lane ? 1 : 0;
  return w;
}

TEST(LaneOf, ALaneIsAFlaggedWaypointAndTheNextOne) {
  // Transit, lane 1 (1-2), transit, lane 2 (3-4), home. A flag on the last
  // waypoint starts no lane.
  const std::vector<radio::Waypoint> route{Point(false), Point(true),  Point(false),
                                           Point(true),  Point(false), Point(true)};
  const int expected_index[] = {1, 1, 1, 2, 2, 0, 0};  // flying to waypoint 0..6
  for (std::size_t to = 0; to <= route.size(); ++to) {
    const LanePosition lanes = LaneOf(route, to);
    EXPECT_EQ(lanes.count, 2);
    EXPECT_EQ(lanes.index, expected_index[to]) << "flying to " << to;
  }
  EXPECT_EQ(LaneOf({}, 0).count, 0);
  EXPECT_EQ(LaneOf({Point(false), Point(false)}, 1).index, 0);
}

// A started lane mission (2 lanes each, 4 waypoints) with vehicle 1 told where it is.
struct LaneFleet {
  LaneFleet() : air(0.0), server(Config(), kFrame) { StartLaneMission(air, server); }
  static ServerConfig Config() {
    ServerConfig config;
    config.telemetry_hz = 2.0;
    return config;
  }
  void Tell(std::uint8_t vehicle, radio::FlightMode mode, std::uint16_t waypoint_index) {
    radio::Telemetry telemetry = Searching(0, 0, ++time_ms);
    telemetry.mode = mode;
    telemetry.waypoint_index = waypoint_index;
    air.vehicle(vehicle).endpoint().SetTelemetry(telemetry);
    air.RunUntil(server, air.channel().now() + 2 * kSecond);
  }
  TaskView Task(std::uint8_t vehicle) {
    return TaskOf(server, vehicle, common::ToSeconds(air.channel().now()));
  }
  Air air;
  Server server;
  std::uint32_t time_ms = 10'000;
};

TEST(VehicleTask, ADroneOnItsLanesSaysWhichLaneAndHowFarAlong) {
  LaneFleet fleet;
  const std::uint16_t flying_to[] = {1, 2, 3, 4};
  const int lane[] = {1, 2, 2, 0};
  const double progress[] = {0.25, 0.5, 0.75, 1.0};
  for (int i = 0; i < 4; ++i) {
    fleet.Tell(1, radio::FlightMode::kSearch, flying_to[i]);
    const TaskView view = fleet.Task(1);
    EXPECT_EQ(view.task, VehicleTask::kLane);
    EXPECT_EQ(view.lane_index, lane[i]) << "flying to " << flying_to[i];
    EXPECT_EQ(view.lane_count, 2);
    EXPECT_DOUBLE_EQ(view.progress_fraction, progress[i]);
  }
}

TEST(VehicleTask, TheVehiclesModeSaysHoldingReturningLandingLanded) {
  LaneFleet fleet;
  const std::pair<radio::FlightMode, VehicleTask> modes[] = {
      {radio::FlightMode::kHold, VehicleTask::kHolding},
      {radio::FlightMode::kReturnToLaunch, VehicleTask::kReturning},
      {radio::FlightMode::kLand, VehicleTask::kLanding},
      {radio::FlightMode::kLanded, VehicleTask::kLanded}};
  for (const auto& [mode, task] : modes) {
    fleet.Tell(2, mode, 1);
    const TaskView view = fleet.Task(2);
    EXPECT_EQ(view.task, task) << ToString(task);
    EXPECT_EQ(view.lane_index, 0) << "a lane only while flying one";
    EXPECT_EQ(view.lane_count, 2);
  }
}

TEST(VehicleTask, AnInvestigatorSaysWhichTrackAndAHoldEndsIt) {
  LaneFleet fleet;
  const Nanos now = fleet.air.channel().now();
  const common::LatLon point = kFrame.ToGeodetic({100.0, 100.0});
  ASSERT_TRUE(fleet.server.Handle({OperatorCommand::Kind::kRetaskVehicle, 3, point, 0.0, ""}, now));
  TaskView view = fleet.Task(3);
  EXPECT_EQ(view.task, VehicleTask::kInvestigating) << "ordered, before its telemetry says so";
  EXPECT_EQ(view.track_id, 0) << "an operator's point";
  ASSERT_TRUE(fleet.server.Handle({OperatorCommand::Kind::kHold, 3, {}, 0.0, ""}, now));
  EXPECT_EQ(fleet.Task(3).task, VehicleTask::kLane) << "called off; its telemetry not in yet";
}

TEST(VehicleTask, BeforeTheStartIdleThenUploading) {
  Air air(0.0);
  Server server(ServerConfig{}, kFrame);
  air.Add(1);
  server.AddVehicle(1);
  EXPECT_EQ(TaskOf(server, 1, 0.0).task, VehicleTask::kIdle);
  EXPECT_EQ(TaskOf(server, 1, 0.0).lane_count, 0);
  server.LoadMission(LaneMissions({1}, 3));
  EXPECT_EQ(TaskOf(server, 1, 0.0).task, VehicleTask::kIdle) << "loaded, not started";
  EXPECT_EQ(TaskOf(server, 1, 0.0).lane_count, 3);
  ASSERT_TRUE(server.Handle({OperatorCommand::Kind::kStart, 0, {}, 0.0, ""}, Nanos{0}));
  EXPECT_EQ(TaskOf(server, 1, 0.0).task, VehicleTask::kUploading);
  EXPECT_DOUBLE_EQ(TaskOf(server, 1, 0.0).progress_fraction, 0.0);
}

TEST(VehicleTask, ALostDroneWhoseLanesWentToOthersIsGivenUp) {
  Air air(0.0);
  Server server(ServerConfig{}, kFrame);
  StartLaneMission(air, server);
  air.silent.insert(2);
  air.Run(server, air.channel().now() + 120 * kSecond,
          [&] { return server.handed_over().contains(2); });
  ASSERT_TRUE(server.handed_over().contains(2));
  EXPECT_EQ(TaskOf(server, 2, common::ToSeconds(air.channel().now())).task, VehicleTask::kGivenUp);
}

}  // namespace
}  // namespace fireswarm::server
