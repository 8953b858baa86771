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
    scheduler = std::make_unique<radio::ChannelRouter>(std::vector{config});
  }
  std::vector<radio::Burst> Step(Nanos now, std::span<const std::uint8_t> bytes) {
    manager->Step(now, gate);
    std::vector<radio::Burst> bursts = scheduler->Step(now, 0, bytes);
    for (const radio::SchedulerEvent& event : scheduler->TakeEvents()) manager->OnEvent(event, gate);
    return bursts;
  }
  Nanos NextWakeup() const { return std::min(scheduler->NextWakeup(), manager->NextWakeup()); }
  std::unique_ptr<radio::ChannelRouter> scheduler;
  std::unique_ptr<MissionManager> manager;
  StartGate gate;  // none unless a test sets one
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

TEST(MissionManager, AStartTheGateHoldsGoesOutWhenTheGateSaysYes) {
  Air air(0.0, radio::LinkMode::kPoll);
  air.Add(3);
  air.Add(4);
  ManagedScheduler server(air.mode);
  for (const std::uint8_t id : {std::uint8_t{3}, std::uint8_t{4}}) server.scheduler->AddVehicle(id, 1.0);
  server.manager = std::make_unique<MissionManager>(
      *server.scheduler, std::vector{Mission(3, 10), Mission(4, 10)});
  // Vehicle 3 may go from 20 s on; vehicle 4 at once.
  const Nanos opens = std::chrono::seconds(20);
  std::vector<std::pair<int, Nanos>> asked;
  server.gate = [&](std::uint8_t vehicle, Nanos now) {
    asked.emplace_back(vehicle, now);
    return vehicle == 4 || now >= opens;
  };
  server.manager->Begin();
  const MissionManager& manager = *server.manager;
  air.Run(server, kLimit, [&] { return manager.AllStarted(); });
  EXPECT_EQ(manager.progress(3).phase, DronePhase::kFlying);
  EXPECT_EQ(manager.progress(4).phase, DronePhase::kFlying);
  EXPECT_EQ(manager.progress(4).start_holds, 0);
  EXPECT_GT(manager.progress(3).start_holds, 10);  // asked every gate_retry_s
  EXPECT_EQ(air.vehicle(3).starts_accepted(), 1) << "no start went out while held";
  // Held, it was asked again about once a second until the gate opened.
  Nanos last_3 = Nanos::min();
  for (const auto& [vehicle, at] : asked) {
    if (vehicle == 3) last_3 = at;
  }
  EXPECT_GE(last_3, opens);
  EXPECT_LT(last_3, opens + common::FromSeconds(MissionManagerConfig{}.gate_retry_s) +
                        std::chrono::milliseconds(100));
}

TEST(MissionManager, ADroneWithoutWaypointsIsDoneAtOnceAndNothingIsSent) {
  Air air(0.0, radio::LinkMode::kPoll);
  air.Add(1);
  air.Add(2);
  DroneMission idle;
  idle.vehicle = 2;
  idle.mission_id = 42;
  ManagedScheduler server = Manage(air.mode, {1, 2}, {Mission(1, 10), idle});
  const MissionManager& manager = *server.manager;
  EXPECT_EQ(manager.progress(2).phase, DronePhase::kDone);
  air.Run(server, kLimit, [&] { return manager.AllStarted(); });
  EXPECT_EQ(manager.progress(1).phase, DronePhase::kFlying);
  EXPECT_EQ(manager.progress(2).phase, DronePhase::kDone);
  EXPECT_EQ(air.vehicle(2).starts_accepted(), 0);
  EXPECT_TRUE(air.vehicle(2).waypoints().empty());
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
  radio::ChannelRouter scheduler({radio::SchedulerConfig{}});
  scheduler.AddVehicle(1, 1.0);
  EXPECT_THROW(MissionManager(scheduler, {Mission(1, 5), Mission(1, 6)}), std::invalid_argument);
}

// What a vehicle's telemetry says about its sortie: the radio mission it flies,
// the waypoint, the mode and the battery.
void Report(FakeVehicle& vehicle, std::uint16_t mission_id, std::uint16_t waypoint,
            radio::FlightMode mode, int battery_percent, bool low_battery = false) {
  radio::Telemetry telemetry;
  telemetry.mission_id = mission_id;
  telemetry.waypoint_index = waypoint;
  telemetry.mode = mode;
  telemetry.battery_percent = static_cast<std::uint8_t>(battery_percent);
  if (low_battery) telemetry.flags = radio::telemetry_flags::kLowBattery;
  vehicle.endpoint().SetTelemetry(telemetry);
}

// 12 waypoints in three sorties of 4 (radio missions 42, 43, 44).
DroneMission ThreeSorties(std::uint8_t vehicle) {
  DroneMission mission = Mission(vehicle, 12);
  mission.sortie_starts = {4, 8};
  return mission;
}

TEST(MissionManager, UploadsTheNextSortieOnlyOnceTheLandedVehicleHasAFreshPack) {
  Air air(0.0, radio::LinkMode::kSlots);
  air.Add(1);
  const DroneMission mission = ThreeSorties(1);
  ManagedScheduler server = Manage(air.mode, {1}, {mission});
  const MissionManager& manager = *server.manager;
  FakeVehicle& vehicle = air.vehicle(1);
  air.Run(server, kLimit, [&] { return manager.AllStarted(); });
  ASSERT_EQ(manager.progress(1).phase, DronePhase::kFlying);
  // Only the first sortie went up, as mission 42.
  EXPECT_EQ(vehicle.waypoints(),
            std::vector<radio::Waypoint>(mission.waypoints.begin(), mission.waypoints.begin() + 4));
  EXPECT_EQ(manager.progress(1).sortie_count, 3U);

  // Landed after it, the pack nearly empty: it waits for the swap.
  Report(vehicle, 42, 3, radio::FlightMode::kLanded, 30);
  Nanos now = air.Run(server, air.channel().now() + kLimit,
                      [&] { return manager.progress(1).phase == DronePhase::kSwapping; });
  EXPECT_EQ(manager.progress(1).sorties_flown, 1U);
  EXPECT_EQ(manager.progress(1).waypoint_index, 3U);
  // Still landed with a low pack a minute later: nothing goes up.
  const Nanos swap_start = now;
  now = air.Run(server, swap_start + std::chrono::seconds(60), [] { return false; });
  EXPECT_EQ(manager.progress(1).phase, DronePhase::kSwapping);
  EXPECT_EQ(vehicle.starts_accepted(), 1);

  // A fresh pack: the second sortie goes up as mission 43 and starts.
  Report(vehicle, 42, 3, radio::FlightMode::kLanded, 100);
  air.Run(server, now + kLimit, [&] {
    return manager.progress(1).phase == DronePhase::kFlying && manager.progress(1).sortie == 1;
  });
  ASSERT_EQ(manager.progress(1).sortie, 1U);
  EXPECT_EQ(vehicle.starts_accepted(), 2);
  EXPECT_EQ(vehicle.commands().back().mission_id, 43);
  EXPECT_EQ(vehicle.waypoints(), std::vector<radio::Waypoint>(mission.waypoints.begin() + 4,
                                                              mission.waypoints.begin() + 8));
  // Its telemetry indexes the sortie; progress counts the whole route.
  Report(vehicle, 43, 2, radio::FlightMode::kSearch, 80);
  air.Run(server, air.channel().now() + kLimit,
          [&] { return manager.progress(1).waypoint_index == 6; });
  EXPECT_EQ(manager.progress(1).waypoint_index, 6U);
  EXPECT_EQ(manager.Remaining(1, /*from_leg_start=*/false).size(), 6U)
      << "this sortie and the next";
  EXPECT_EQ(manager.LastMissionId(), 44);
}

TEST(MissionManager, TheLastSortiesLandingIsDoneAndStopSortiesEndsTheWait) {
  Air air(0.0, radio::LinkMode::kSlots);
  air.Add(1);
  air.Add(2);
  DroneMission one = Mission(1, 4);  // one sortie
  ManagedScheduler server = Manage(air.mode, {1, 2}, {one, ThreeSorties(2)});
  MissionManager& manager = *server.manager;
  air.Run(server, kLimit, [&] { return manager.AllStarted(); });
  Report(air.vehicle(1), 42, 3, radio::FlightMode::kLanded, 30);
  Report(air.vehicle(2), 42, 3, radio::FlightMode::kLanded, 30);
  air.Run(server, air.channel().now() + kLimit, [&] {
    return manager.progress(1).phase == DronePhase::kDone &&
           manager.progress(2).phase == DronePhase::kSwapping;
  });
  EXPECT_EQ(manager.progress(1).phase, DronePhase::kDone);
  ASSERT_EQ(manager.progress(2).phase, DronePhase::kSwapping);
  // Recalled (return all, abort): no next sortie, even on a fresh pack.
  manager.StopSorties();
  EXPECT_EQ(manager.progress(2).phase, DronePhase::kDone);
  Report(air.vehicle(2), 42, 3, radio::FlightMode::kLanded, 100);
  air.Run(server, air.channel().now() + std::chrono::seconds(30), [] { return false; });
  EXPECT_EQ(air.vehicle(2).starts_accepted(), 1);
}

TEST(MissionManager, ASortieCutShortByALowBatteryIsResumedFromTheLegItWasOn) {
  Air air(0.0, radio::LinkMode::kSlots);
  air.Add(1);
  DroneMission mission = Mission(1, 10);
  mission.sortie_starts = {6};  // sorties of 6 and 4
  ManagedScheduler server = Manage(air.mode, {1}, {mission});
  const MissionManager& manager = *server.manager;
  air.Run(server, kLimit, [&] { return manager.AllStarted(); });
  // Home on a low battery while flying to waypoint 3 of 6.
  Report(air.vehicle(1), 42, 3, radio::FlightMode::kLanded, 22, /*low_battery=*/true);
  air.Run(server, air.channel().now() + kLimit,
          [&] { return manager.progress(1).phase == DronePhase::kSwapping; });
  EXPECT_EQ(manager.progress(1).sortie_count, 3U) << "the rest is a sortie of its own";
  EXPECT_EQ(manager.mission_of(1).sortie_starts, (std::vector<std::size_t>{2, 6}));
  // After the swap: from waypoint 2 (the leg 2 -> 3 it was on) to 5, then the old second.
  Report(air.vehicle(1), 42, 3, radio::FlightMode::kLanded, 100);
  air.Run(server, air.channel().now() + kLimit, [&] {
    return manager.progress(1).phase == DronePhase::kFlying && manager.progress(1).sortie == 1;
  });
  EXPECT_EQ(
      air.vehicle(1).waypoints(),
      std::vector<radio::Waypoint>(mission.waypoints.begin() + 2, mission.waypoints.begin() + 6));
}

TEST(MissionManager, ASortieCutShortIsASortieOfItsOwnAsSoonAsTheReturnIsSeen) {
  Air air(0.0, radio::LinkMode::kSlots);
  air.Add(1);
  DroneMission mission = Mission(1, 10);
  mission.sortie_starts = {6};
  ManagedScheduler server = Manage(air.mode, {1}, {mission});
  const MissionManager& manager = *server.manager;
  air.Run(server, kLimit, [&] { return manager.AllStarted(); });
  // On its way home on a low battery, still in the air: its rest can go to
  // another drone already (the last sortie is the old second, unstarted).
  Report(air.vehicle(1), 42, 3, radio::FlightMode::kReturnToLaunch, 24, /*low_battery=*/true);
  air.Run(server, air.channel().now() + kLimit,
          [&] { return manager.progress(1).sortie_count == 3; });
  EXPECT_EQ(manager.progress(1).phase, DronePhase::kFlying);
  EXPECT_EQ(manager.mission_of(1).sortie_starts, (std::vector<std::size_t>{2, 6}));
  EXPECT_EQ(manager.UnstartedSorties(1), 2U);
  // Landing does not cut it again.
  Report(air.vehicle(1), 42, 3, radio::FlightMode::kLanded, 22, /*low_battery=*/true);
  air.Run(server, air.channel().now() + kLimit,
          [&] { return manager.progress(1).phase == DronePhase::kSwapping; });
  EXPECT_EQ(manager.mission_of(1).sortie_starts, (std::vector<std::size_t>{2, 6}));
}

TEST(MissionManager, GivesAwayOnlyALastSortieThatHasNotStarted) {
  Air air(0.0, radio::LinkMode::kSlots);
  air.Add(1);
  air.Add(2);
  const DroneMission three = ThreeSorties(1);
  ManagedScheduler server = Manage(air.mode, {1, 2}, {three, Mission(2, 4)});
  MissionManager& manager = *server.manager;
  air.Run(server, kLimit, [&] { return manager.AllStarted(); });
  // Flying its first of three: the third goes, whole, and nothing is sent.
  EXPECT_EQ(manager.UnstartedSorties(1), 2U);
  const std::uint64_t sent = server.scheduler->stats().requests_sent;
  const std::optional<std::vector<radio::Waypoint>> third = manager.TakeLastSortie(1);
  ASSERT_TRUE(third);
  EXPECT_EQ(*third,
            std::vector<radio::Waypoint>(three.waypoints.begin() + 8, three.waypoints.end()));
  EXPECT_EQ(server.scheduler->stats().requests_sent, sent);
  EXPECT_EQ(manager.progress(1).sortie_count, 2U);
  EXPECT_EQ(manager.progress(1).waypoint_count, 8U);
  EXPECT_EQ(manager.UnstartedSorties(1), 1U);
  // A mission's only sortie stays, flying or not.
  EXPECT_EQ(manager.UnstartedSorties(2), 0U);
  EXPECT_FALSE(manager.TakeLastSortie(2));
  // Landed for its pack with one sortie to come: taking it leaves the drone done.
  Report(air.vehicle(1), 42, 3, radio::FlightMode::kLanded, 30);
  air.Run(server, air.channel().now() + kLimit,
          [&] { return manager.progress(1).phase == DronePhase::kSwapping; });
  EXPECT_EQ(manager.UnstartedSorties(1), 1U);
  ASSERT_TRUE(manager.TakeLastSortie(1));
  EXPECT_EQ(manager.progress(1).phase, DronePhase::kDone);
  EXPECT_EQ(manager.UnstartedSorties(1), 0U);
  EXPECT_FALSE(manager.TakeLastSortie(1));
  Report(air.vehicle(1), 42, 3, radio::FlightMode::kLanded, 100);
  air.Run(server, air.channel().now() + std::chrono::seconds(30), [] { return false; });
  EXPECT_EQ(air.vehicle(1).starts_accepted(), 1) << "a fresh pack starts nothing";
}

TEST(MissionManager, AMissionHandedToADroneBetweenSortiesWaitsForItsPack) {
  Air air(0.0, radio::LinkMode::kSlots);
  air.Add(1);
  ManagedScheduler server = Manage(air.mode, {1}, {ThreeSorties(1)});
  MissionManager& manager = *server.manager;
  FakeVehicle& vehicle = air.vehicle(1);
  air.Run(server, kLimit, [&] { return manager.AllStarted(); });
  Report(vehicle, 42, 3, radio::FlightMode::kLanded, 30);
  air.Run(server, air.channel().now() + kLimit,
          [&] { return manager.progress(1).phase == DronePhase::kSwapping; });
  // Its two sorties to come plus handed-over lanes, as the handover builds it.
  DroneMission more = Mission(1, 10);
  more.mission_id = 50;
  more.sortie_starts = {4};
  manager.Replace(more);
  EXPECT_EQ(manager.progress(1).phase, DronePhase::kSwapping);
  EXPECT_EQ(manager.progress(1).sorties_flown, 1U);
  EXPECT_EQ(manager.Remaining(1, /*from_leg_start=*/false), more.waypoints);
  air.Run(server, air.channel().now() + std::chrono::seconds(30), [] { return false; });
  EXPECT_EQ(vehicle.starts_accepted(), 1) << "nothing starts on the old pack";
  Report(vehicle, 42, 3, radio::FlightMode::kLanded, 100);
  air.Run(server, air.channel().now() + kLimit,
          [&] { return manager.progress(1).phase == DronePhase::kFlying; });
  EXPECT_EQ(vehicle.commands().back().mission_id, 50);
  EXPECT_EQ(vehicle.waypoints(),
            std::vector<radio::Waypoint>(more.waypoints.begin(), more.waypoints.begin() + 4));
}

TEST(MissionManager, RestoresADroneBetweenSortiesWithoutUploadingAgain) {
  radio::ChannelRouter scheduler({radio::SchedulerConfig{}});
  scheduler.AddVehicle(1, 1.0);
  MissionManager manager(scheduler, {ThreeSorties(1)});
  manager.RestorePhase(1, DronePhase::kSwapping, 1, std::vector<std::size_t>{4, 6, 8});
  manager.Begin();
  const DroneProgress& progress = manager.progress(1);
  EXPECT_EQ(progress.phase, DronePhase::kSwapping);
  EXPECT_EQ(progress.sortie, 1U);
  EXPECT_EQ(progress.sorties_flown, 2U);
  EXPECT_EQ(progress.sortie_count, 4U);
  EXPECT_EQ(progress.waypoint_index, 4U);
  EXPECT_EQ(scheduler.stats().requests_sent, 0U);
  EXPECT_THROW(manager.RestorePhase(1, DronePhase::kFlying, 9), std::out_of_range);
  EXPECT_THROW(manager.RestorePhase(1, DronePhase::kFlying, 1, std::vector<std::size_t>{4, 40}),
               std::invalid_argument);
}

}  // namespace
}  // namespace fireswarm::server
