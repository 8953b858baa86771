// The vehicle's radio side in closed loop: missions fly only when whole,
// parameters persist across a restart, fire reports survive a lossy link, and
// every command is answered.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <string>

#include "hil_test_helpers.hpp"

namespace fireswarm::hil {
namespace {

using radio::FlightMode;
using sim2d::Vec2;
using testing::Mission;
using testing::OneVehicleWorld;
using testing::RunUntilOr;
using testing::WaypointAt;

std::vector<radio::Waypoint> Lane(const Mission& mission, int waypoints) {
  std::vector<radio::Waypoint> lane;
  for (int i = 0; i < waypoints; ++i) {
    lane.push_back(WaypointAt(mission, Vec2(0.0, 20.0 * i), 60.0, i == 0));
  }
  return lane;
}

// The ack of the request `id`, once it finished.
std::optional<radio::RequestFinished> Finished(const Mission& mission, radio::RequestId id) {
  for (const auto& finished : mission.link.EventsOf<radio::RequestFinished>()) {
    if (finished.id == id) return finished;
  }
  return std::nullopt;
}

radio::CommandResult CommandResultOf(const radio::RequestFinished& finished) {
  return std::get<radio::CommandAck>(*finished.ack).result;
}

TEST(VehicleRadio, AHalfUploadedMissionNeverFlies) {
  Mission mission(OneVehicleWorld());
  agents::Vehicle& vehicle = mission.AddVehicle(agents::VehicleConfig{});
  mission.RunUntil(1.0);
  const std::vector<radio::MissionChunk> chunks =
      radio::SplitMission(9, Lane(mission, 2 * static_cast<int>(radio::kMaxWaypointsPerChunk)));
  ASSERT_EQ(chunks.size(), 2U);
  mission.link.server().SendMissionChunk(1, chunks[0]);  // the second never goes out
  radio::Command start;
  start.type = radio::CommandType::kStartMission;
  start.mission_id = 9;
  const radio::RequestId refused = mission.link.server().SendCommand(1, start);
  mission.RunUntil(5.0);
  const auto refusal = Finished(mission, refused);
  ASSERT_TRUE(refusal.has_value());
  ASSERT_EQ(refusal->status, radio::RequestStatus::kCompleted);
  EXPECT_EQ(CommandResultOf(*refusal), radio::CommandResult::kRejected);
  EXPECT_EQ(vehicle.mode(), FlightMode::kIdle);
  EXPECT_EQ(mission.Truth(1).altitude_m, 0.0);

  mission.link.server().SendMissionChunk(1, chunks[1]);
  const radio::RequestId accepted = mission.link.server().SendCommand(1, start);
  mission.RunUntil(10.0);
  ASSERT_TRUE(Finished(mission, accepted).has_value());
  EXPECT_EQ(CommandResultOf(*Finished(mission, accepted)), radio::CommandResult::kAccepted);
  EXPECT_EQ(vehicle.mode(), FlightMode::kTakeoff);
  EXPECT_GT(mission.Truth(1).altitude_m, 1.0);
}

TEST(VehicleRadio, CommandsThatMakeNoSenseOnTheGroundAreRejected) {
  Mission mission(OneVehicleWorld());
  mission.AddVehicle(agents::VehicleConfig{});
  mission.RunUntil(1.0);
  std::map<radio::CommandType, radio::RequestId> sent;
  for (const radio::CommandType type :
       {radio::CommandType::kHold, radio::CommandType::kResume, radio::CommandType::kReturnToLaunch,
        radio::CommandType::kLand, radio::CommandType::kInvestigate}) {
    radio::Command command;
    command.type = type;
    command.lat_deg = 45.0;
    command.lon_deg = 7.0;
    sent[type] = mission.link.server().SendCommand(1, command);
  }
  mission.RunUntil(5.0);
  for (const auto& [type, id] : sent) {
    const auto finished = Finished(mission, id);
    ASSERT_TRUE(finished.has_value()) << static_cast<int>(type);
    EXPECT_EQ(CommandResultOf(*finished), radio::CommandResult::kRejected)
        << static_cast<int>(type);
  }
}

TEST(VehicleRadio, ParametersWrittenOverTheRadioSurviveARestart) {
  const std::filesystem::path dir =
      std::filesystem::path(::testing::TempDir()) / "fireswarm_vehicle_params";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  agents::VehicleConfig config;
  config.param_file = dir / "vehicle_1.json";
  const auto cruise = static_cast<std::uint16_t>(agents::ParamId::kCruiseSpeedMps);
  {
    Mission mission(OneVehicleWorld());
    agents::Vehicle& vehicle = mission.AddVehicle(config);
    const radio::RequestId written = mission.link.server().WriteParam(1, cruise, 5.5F);
    const radio::RequestId refused = mission.link.server().WriteParam(1, cruise, 99.0F);
    mission.RunUntil(3.0);
    ASSERT_TRUE(Finished(mission, written).has_value());
    const auto value = std::get<radio::ParamValue>(*Finished(mission, written)->ack);
    EXPECT_EQ(value.status, radio::ParamStatus::kOk);
    EXPECT_FLOAT_EQ(value.value, 5.5F);
    const auto refusal = std::get<radio::ParamValue>(*Finished(mission, refused)->ack);
    EXPECT_EQ(refusal.status, radio::ParamStatus::kOutOfRange);
    EXPECT_FLOAT_EQ(refusal.value, 5.5F);
    ASSERT_NE(vehicle.navigator(), nullptr);
    EXPECT_DOUBLE_EQ(vehicle.navigator()->config().cruise_speed_mps, 5.5);
  }
  // The vehicle restarts: the value is back from its file and in use.
  Mission mission(OneVehicleWorld());
  agents::Vehicle& vehicle = mission.AddVehicle(config);
  const radio::RequestId read = mission.link.server().ReadParam(1, cruise);
  mission.RunUntil(3.0);
  EXPECT_FLOAT_EQ(vehicle.params().Get(agents::ParamId::kCruiseSpeedMps), 5.5F);
  ASSERT_NE(vehicle.navigator(), nullptr);
  EXPECT_DOUBLE_EQ(vehicle.navigator()->config().cruise_speed_mps, 5.5);
  ASSERT_TRUE(Finished(mission, read).has_value());
  EXPECT_FLOAT_EQ(std::get<radio::ParamValue>(*Finished(mission, read)->ack).value, 5.5F);
  std::filesystem::remove_all(dir);
}

TEST(VehicleRadio, FireReportsSurviveALossyLinkAndArriveOnce) {
  sim2d::SimulationConfig config = OneVehicleWorld();
  // Three fires under the lane.
  for (const double north : {150.0, 400.0, 650.0})
    config.ignitions.push_back({Vec2(0.0, north), 0.0});
  radio::ChannelConfig channel;
  channel.loss = 0.3;
  radio::SchedulerConfig server;
  server.max_retries = 10;
  Mission mission(config, channel, server);
  agents::Vehicle& vehicle = mission.AddVehicle(agents::VehicleConfig{});
  mission.RunUntil(1.0);
  mission.link.UploadAndStart(1, 4,
                              {WaypointAt(mission, Vec2(0.0, 0.0), 60.0, /*lane_start=*/true),
                               WaypointAt(mission, Vec2(0.0, 800.0), 60.0)});
  RunUntilOr(mission, 400.0, [&] { return vehicle.mode() == FlightMode::kReturnToLaunch; });
  // Give the link time to hand over the last reports (it loses 30 % of frames).
  const double limit_s = mission.simulation.time_s() + 120.0;
  RunUntilOr(mission, limit_s, [&] { return vehicle.endpoint().pending_reports() == 0; });
  const radio::VehicleEndpointStats& stats = vehicle.endpoint().stats();
  const auto received = mission.link.EventsOf<radio::FireReportReceived>();
  EXPECT_GE(vehicle.stats().fires_detected, 3U);
  EXPECT_EQ(received.size(), vehicle.stats().fires_detected);  // each once, none lost
  EXPECT_EQ(stats.reports_acked, stats.reports_queued);
  EXPECT_EQ(vehicle.endpoint().pending_reports(), 0U);
  EXPECT_GT(mission.link.channel().stats().receptions_lost, 0U);  // the link did lose frames
}

// The telemetry's latitude and longitude are worked out only when a reply is
// sent, from the position of the vehicle's latest telemetry update: each reply
// puts the drone where its estimate was at the telemetry's time, in flight too.
TEST(VehicleRadio, TelemetryPutsTheDroneWhereItsEstimateWasAtTheTelemetrysTime) {
  Mission mission(OneVehicleWorld(Vec2(300.0, -200.0)));
  // Refreshed once a second and asked for twice: every other reply carries a
  // telemetry half a second old, position and all.
  agents::VehicleConfig config;
  config.telemetry_hz = 1.0;
  agents::Vehicle& vehicle = mission.AddVehicle(config);
  mission.RunUntil(1.0);  // a GPS fix first: without one the start is refused
  const auto first = mission.link.EventsOf<radio::TelemetryReceived>();
  ASSERT_FALSE(first.empty());
  EXPECT_EQ(first.front().telemetry.flags & radio::telemetry_flags::kGpsFix, 0);
  EXPECT_EQ(first.front().telemetry.lat_deg, 0.0) << "no fix yet, no position";
  mission.link.UploadAndStart(1, 4,
                              {WaypointAt(mission, Vec2(300.0, -100.0), 40.0, true),
                               WaypointAt(mission, Vec2(300.0, 400.0), 40.0)});
  // The estimate (in the vehicle's own frame) and the truth at every step.
  std::map<std::int64_t, std::pair<Vec2, Vec2>> at_ms;
  mission.RunUntil(60.0, [&] {
    const common::EastNorth estimate = vehicle.estimate().position_local;
    at_ms[std::llround(mission.simulation.time_s() * 1000.0)] = {
        Vec2(estimate.east_m, estimate.north_m), mission.Truth(1).position_m};
  });
  std::vector<std::pair<Vec2, Vec2>> reported_and_estimate;
  double worst_from_truth_m = 0.0;
  double fastest_mps = 0.0;
  for (const radio::TelemetryReceived& event : mission.link.EventsOf<radio::TelemetryReceived>()) {
    const radio::Telemetry& telemetry = event.telemetry;
    const auto at = at_ms.find(telemetry.time_ms);
    if (at == at_ms.end()) continue;  // before the first second
    ASSERT_NE(telemetry.flags & radio::telemetry_flags::kGpsFix, 0) << telemetry.time_ms;
    const common::EastNorth reported =
        mission.simulation.world().frame().ToLocal({telemetry.lat_deg, telemetry.lon_deg});
    const Vec2 reported_m(reported.east_m, reported.north_m);
    reported_and_estimate.emplace_back(reported_m, at->second.first);
    worst_from_truth_m = std::max(worst_from_truth_m, (reported_m - at->second.second).norm());
    fastest_mps = std::max(fastest_mps,
                           std::hypot(telemetry.velocity_east_mps, telemetry.velocity_north_mps));
  }
  ASSERT_GE(reported_and_estimate.size(), 100U);  // 2 Hz for 59 s
  EXPECT_GT(fastest_mps, 8.0) << "the drone must have flown its lane";
  EXPECT_LT(worst_from_truth_m, 10.0) << "GPS noise and bias only";
  // The two frames have different origins; how far the drone moved between two
  // replies is the same in both (a position from another time would differ by
  // the distance flown in between: 5 m at 10 m/s in half a second).
  for (std::size_t i = 1; i < reported_and_estimate.size(); ++i) {
    const auto& [reported_a, estimate_a] = reported_and_estimate[i - 1];
    const auto& [reported_b, estimate_b] = reported_and_estimate[i];
    EXPECT_NEAR((reported_b - reported_a).norm(), (estimate_b - estimate_a).norm(), 0.05) << i;
  }
}

}  // namespace
}  // namespace fireswarm::hil
