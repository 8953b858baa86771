#include "fireswarm/server/mission_manager.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <span>
#include <vector>

#include "fireswarm/common/time.hpp"
#include "server/fake_fleet.hpp"

namespace fireswarm::server {
namespace {

using common::Nanos;
using testing::Air;
using testing::FakeVehicle;

// The scheduler with the manager fed by its events: the server end of Air.
struct ManagedScheduler {
  explicit ManagedScheduler(radio::LinkMode mode) {
    radio::SchedulerConfig config;
    config.mode = mode;
    scheduler = std::make_unique<radio::MasterScheduler>(config);
  }
  std::vector<radio::Burst> Step(Nanos now, std::span<const std::uint8_t> bytes) {
    manager->Step(now);
    std::vector<radio::Burst> bursts = scheduler->Step(now, bytes);
    for (const radio::SchedulerEvent& event : scheduler->TakeEvents()) manager->OnEvent(event);
    return bursts;
  }
  Nanos NextWakeup() const { return std::min(scheduler->NextWakeup(), manager->NextWakeup()); }
  std::unique_ptr<radio::MasterScheduler> scheduler;
  std::unique_ptr<MissionManager> manager;
};

DroneMission Mission(std::uint8_t vehicle, std::size_t waypoints) {
  DroneMission mission;
  mission.vehicle = vehicle;
  mission.mission_id = 42;
  for (std::size_t i = 0; i < waypoints; ++i) {
    radio::Waypoint waypoint;
    waypoint.lat_deg = 46.0 + 1e-4 * static_cast<double>(i);
    waypoint.lon_deg = -74.5 + 1e-4 * static_cast<double>(vehicle);
    waypoint.altitude_m = 60.0;
    waypoint.speed_mps = 10.0;
    waypoint.flags = static_cast<std::uint8_t>(i % 2);
    mission.waypoints.push_back(waypoint);
  }
  return mission;
}

constexpr Nanos kLimit = std::chrono::seconds(600);

// A scheduler knowing `ids` (telemetry at 1 Hz) and a manager for `missions`.
ManagedScheduler Manage(radio::LinkMode mode, const std::vector<std::uint8_t>& ids,
                        std::vector<DroneMission> missions) {
  ManagedScheduler server(mode);
  for (const std::uint8_t id : ids) server.scheduler->AddVehicle(id, 1.0);
  server.manager = std::make_unique<MissionManager>(*server.scheduler, std::move(missions));
  server.manager->Begin();
  return server;
}

TEST(MissionManager, UploadsEveryDroneAndStartsIt) {
  Air air(0.0, radio::LinkMode::kSlots);
  std::vector<DroneMission> missions;
  std::vector<std::uint8_t> ids;
  for (std::uint8_t id = 1; id <= 4; ++id) {
    air.Add(id);
    ids.push_back(id);
    missions.push_back(Mission(id, 45));  // 3 chunks each
  }
  ManagedScheduler server = Manage(air.mode, ids, missions);
  const MissionManager& manager = *server.manager;
  air.Run(server, kLimit, [&] { return manager.AllStarted(); });
  for (std::uint8_t id = 1; id <= 4; ++id) {
    const DroneProgress& progress = manager.progress(id);
    EXPECT_EQ(progress.phase, DronePhase::kFlying) << int{id} << ": " << progress.failure;
    EXPECT_EQ(progress.chunk_count, 3u);
    EXPECT_EQ(progress.chunks_acked, 3u);
    const FakeVehicle& vehicle = air.vehicle(id);
    EXPECT_EQ(vehicle.waypoints(), missions[id - 1u].waypoints) << "vehicle " << int{id};
    EXPECT_EQ(vehicle.starts_accepted(), 1);
  }
}

TEST(MissionManager, AsksARefusedStartAgainUntilTheVehicleAccepts) {
  Air air(0.0, radio::LinkMode::kPoll);
  air.Add(3, /*refusals=*/2);
  ManagedScheduler server = Manage(air.mode, {3}, {Mission(3, 10)});
  const MissionManager& manager = *server.manager;
  const Nanos end = air.Run(server, kLimit, [&] { return manager.AllStarted(); });
  EXPECT_EQ(manager.progress(3).phase, DronePhase::kFlying);
  EXPECT_EQ(manager.progress(3).start_refusals, 2);
  // Two refusals, each followed by the configured wait before asking again.
  EXPECT_GE(end, 2 * common::FromSeconds(MissionManagerConfig{}.start_retry_s));
}

TEST(MissionManager, CompletesTheUploadOnALossyChannel) {
  Air air(0.2, radio::LinkMode::kSlots);
  std::vector<DroneMission> missions;
  std::vector<std::uint8_t> ids;
  for (std::uint8_t id = 10; id < 16; ++id) {
    air.Add(id);
    ids.push_back(id);
    missions.push_back(Mission(id, 70));
  }
  ManagedScheduler server = Manage(air.mode, ids, missions);
  const MissionManager& manager = *server.manager;
  air.Run(server, kLimit, [&] { return manager.AllStarted(); });
  EXPECT_GT(server.scheduler->stats().retries, 0u) << "20 % loss must have cost resends";
  for (const DroneMission& mission : missions) {
    const std::uint8_t id = mission.vehicle;
    EXPECT_EQ(manager.progress(id).phase, DronePhase::kFlying) << manager.progress(id).failure;
    EXPECT_EQ(air.vehicle(id).waypoints(), mission.waypoints);
  }
}

TEST(MissionManager, GivesUpOnASilentVehicleAndSaysWhy) {
  Air air(0.0, radio::LinkMode::kPoll);
  air.Add(1);  // no radio answers as 2
  ManagedScheduler server = Manage(air.mode, {1, 2}, {Mission(1, 5), Mission(2, 5)});
  const MissionManager& manager = *server.manager;
  air.Run(server, kLimit, [&] { return manager.AllStarted(); });
  EXPECT_EQ(manager.progress(1).phase, DronePhase::kFlying);
  EXPECT_EQ(manager.progress(2).phase, DronePhase::kFailed);
  EXPECT_NE(manager.progress(2).failure.find("unanswered"), std::string::npos)
      << manager.progress(2).failure;
}

TEST(MissionManager, RefusesTwoMissionsForOneVehicle) {
  radio::MasterScheduler scheduler(radio::SchedulerConfig{});
  scheduler.AddVehicle(1, 1.0);
  EXPECT_THROW(MissionManager(scheduler, {Mission(1, 5), Mission(1, 6)}), std::invalid_argument);
}

TEST(ToDroneMissions, CarriesEveryWaypointWithLaneFlagsAltitudeAndSpeed) {
  planner::Plan plan;
  planner::DronePlan drone;
  drone.receiver_id = 7;
  drone.waypoints.push_back({{0, 0}, {46.0, -74.0}, false, false});
  drone.waypoints.push_back({{100, 0}, {46.0, -73.99}, false, true});
  drone.waypoints.push_back({{100, 80}, {46.001, -73.99}, false, false});
  plan.drones.push_back(drone);
  const std::vector<DroneMission> missions = ToDroneMissions(plan, 9, 60.0, 8.0);
  ASSERT_EQ(missions.size(), 1u);
  EXPECT_EQ(missions[0].vehicle, 7);
  EXPECT_EQ(missions[0].mission_id, 9);
  ASSERT_EQ(missions[0].waypoints.size(), 3u);
  EXPECT_EQ(missions[0].waypoints[1].flags, 1);
  EXPECT_EQ(missions[0].waypoints[0].flags, 0);
  EXPECT_DOUBLE_EQ(missions[0].waypoints[2].lat_deg, 46.001);
  EXPECT_DOUBLE_EQ(missions[0].waypoints[2].altitude_m, 60.0);
  EXPECT_DOUBLE_EQ(missions[0].waypoints[2].speed_mps, 8.0);

  plan.drones[0].receiver_id = 255;
  EXPECT_THROW(ToDroneMissions(plan, 9, 60.0, 8.0), std::invalid_argument);
}

TEST(WithoutLaunchSite, DropsTheLaunchAtEitherEndAndKeepsReturnsBetweenSorties) {
  const common::LocalFrame frame{common::LatLon{46.0, -74.5}};
  const common::EastNorth launch{10.0, 20.0};
  const auto at = [&](double east_m, double north_m) {
    const common::LatLon p = frame.ToGeodetic({east_m, north_m});
    radio::Waypoint w;
    w.lat_deg = p.lat_deg;
    w.lon_deg = p.lon_deg;
    return w;
  };
  DroneMission mission;
  mission.vehicle = 1;
  // launch, lane, return between sorties, lane, launch, launch again
  mission.waypoints = {at(10, 20),   at(300, 20), at(10.2, 20),
                       at(300, 100), at(10, 20),  at(10, 20.5)};
  DroneMission idle;
  idle.vehicle = 2;
  idle.waypoints = {at(10, 20), at(10, 20)};
  const std::vector<DroneMission> out = WithoutLaunchSite({mission, idle}, frame, launch);
  ASSERT_EQ(out[0].waypoints.size(), 3u);
  EXPECT_EQ(out[0].waypoints[0], mission.waypoints[1]);
  EXPECT_EQ(out[0].waypoints[1], mission.waypoints[2]) << "the return between sorties stays";
  EXPECT_EQ(out[0].waypoints[2], mission.waypoints[3]);
  EXPECT_EQ(out[1].waypoints.size(), 1u) << "a route of only the launch keeps one waypoint";
}

}  // namespace
}  // namespace fireswarm::server
