// Server::RebalanceSorties (server_rebalance.cpp): a drone done with its sorties
// takes the last unstarted sortie of the busiest drone at its own site.
#include <gtest/gtest.h>

#include <algorithm>
#include <variant>
#include <vector>

#include "fireswarm/common/time.hpp"
#include "fireswarm/server/server.hpp"
#include "server/fake_fleet.hpp"
#include "server/server_fixture.hpp"

namespace fireswarm::server {
namespace {

using common::Nanos;
using testing::Air;
using testing::kFrame;
using testing::kSecond;

// Lane layers and ways home as the runner gives them: search at 60 + id, home
// at 70 + id.
double SearchM(std::uint8_t id) {
  return 60.0 + id;
}
double HomeM(std::uint8_t id) {
  return 70.0 + id;
}

// `sorties` sorties of two lane ends and a way home each, north of (east_m, 0).
DroneMission Sorties(std::uint8_t id, int sorties, double east_m) {
  DroneMission mission;
  mission.vehicle = id;
  mission.mission_id = 1;
  for (int k = 0; k < sorties; ++k) {
    if (k > 0) mission.sortie_starts.push_back(mission.waypoints.size());
    for (const double north : {100.0 * (k + 1), 100.0 * (k + 1) + 500.0}) {
      const common::LatLon p = kFrame.ToGeodetic({east_m + 10.0 * k, north});
      const bool lane_start = north < 500.0 * (k + 1);
      radio::Waypoint w{p.lat_deg, p.lon_deg, SearchM(id), 10.0,
                        static_cast<std::uint8_t>(lane_start ? 1 : 0)};
      mission.waypoints.push_back(w);
    }
    radio::Waypoint home = mission.waypoints.back();
    home.altitude_m = HomeM(id);
    home.flags = 0;
    mission.waypoints.push_back(home);
  }
  return mission;
}

radio::Telemetry At(double east_m, radio::FlightMode mode, std::uint16_t mission_id,
                    std::uint16_t waypoint, int battery_percent) {
  const common::LatLon where = kFrame.ToGeodetic({east_m, 0.0});
  radio::Telemetry telemetry;
  telemetry.time_ms = 1'000;
  telemetry.lat_deg = where.lat_deg;
  telemetry.lon_deg = where.lon_deg;
  telemetry.mode = mode;
  telemetry.flags = radio::telemetry_flags::kGpsFix | radio::telemetry_flags::kMissionValid;
  telemetry.battery_percent = static_cast<std::uint8_t>(battery_percent);
  telemetry.mission_id = mission_id;
  telemetry.waypoint_index = waypoint;
  return telemetry;
}

TEST(ServerRebalance, ADroneDoneTakesTheLastSortieNotStartedOfTheBusiestAtItsSite) {
  Air air(0.0);
  // The fake vehicles' telemetry stands still (2 "searches" next to 1's stand
  // for ever): take-off clearances would hold 1 for good. This is about who
  // flies what; the clearances have tests of their own (traffic_test.cpp).
  ServerConfig config;
  config.separation.sequence_takeoffs = false;
  Server server(config, kFrame);
  // 1 and 2 stand 20 m apart (one site), 3 two kilometres away (another). 3 has
  // the most sorties to come, but not at 1's site.
  const std::vector<DroneMission> missions = {Sorties(1, 1, 0.0), Sorties(2, 3, 20.0),
                                              Sorties(3, 4, 2'000.0)};
  const double stands_m[] = {0.0, 0.0, 20.0, 2'000.0};
  for (std::uint8_t id = 1; id <= 3; ++id) {
    air.Add(id);
    server.AddVehicle(id);
    air.vehicle(id).endpoint().SetTelemetry(At(stands_m[id], radio::FlightMode::kIdle, 0, 0, 100));
  }
  air.RunUntil(server, 5 * kSecond);  // each seen on its stand
  server.LoadMission(missions);
  ASSERT_TRUE(server.Handle({OperatorCommand::Kind::kStart, 0, {}, 0.0, "test"}, Nanos{0}));
  air.Run(server, air.channel().now() + 60 * kSecond,
          [&] { return server.state() == MissionState::kRunning; });
  ASSERT_EQ(server.state(), MissionState::kRunning);
  air.vehicle(2).endpoint().SetTelemetry(At(20.0, radio::FlightMode::kSearch, 1, 1, 80));
  air.vehicle(3).endpoint().SetTelemetry(At(2'000.0, radio::FlightMode::kSearch, 1, 1, 80));

  // 1 lands from its only sortie and gets a fresh pack.
  air.vehicle(1).endpoint().SetTelemetry(At(0.0, radio::FlightMode::kLanded, 1, 2, 100));
  air.Run(server, air.channel().now() + 60 * kSecond, [&] {
    return server.mission()->mission_of(1).mission_id != 1 &&
           server.mission()->progress(1).phase == DronePhase::kFlying;
  });
  ASSERT_EQ(server.mission()->progress(1).phase, DronePhase::kFlying);

  // It flies 2's third sortie, at its own layer and way home; 2 keeps two.
  const DroneMission& taken = server.mission()->mission_of(1);
  std::vector<radio::Waypoint> expected(missions[1].waypoints.begin() + 6,
                                        missions[1].waypoints.end());
  for (radio::Waypoint& w : expected)
    w.altitude_m = w.altitude_m == SearchM(2) ? SearchM(1) : HomeM(1);
  EXPECT_EQ(taken.waypoints, expected);
  EXPECT_GT(taken.mission_id, 4) << "above every mission ID in use";
  EXPECT_EQ(air.vehicle(1).waypoints().size(), expected.size()) << "uploaded to vehicle 1";
  const radio::Command* start = testing::LastOf(air.vehicle(1), radio::CommandType::kStartMission);
  ASSERT_NE(start, nullptr);
  EXPECT_EQ(start->mission_id, taken.mission_id);
  EXPECT_EQ(server.mission()->progress(2).sortie_count, 2U);
  EXPECT_EQ(server.mission()->progress(3).sortie_count, 4U) << "another site's";

  // Done with that, nothing is left at its site to take but 2's second sortie,
  // which 1 takes too (2 still flies its first).
  air.vehicle(1).endpoint().SetTelemetry(
      At(0.0, radio::FlightMode::kLanded, taken.mission_id, 2, 100));
  const std::uint16_t first_taken = taken.mission_id;
  air.Run(server, air.channel().now() + 60 * kSecond, [&] {
    return server.mission()->mission_of(1).mission_id != first_taken &&
           server.mission()->progress(1).phase == DronePhase::kFlying;
  });
  EXPECT_EQ(server.mission()->progress(2).sortie_count, 1U) << "its only sortie stays";

  // A restarted server knows who flies what, and uploads nothing again.
  std::vector<JournalEntry> journal = server.TakeJournalEntries();
  EXPECT_EQ(std::ranges::count_if(
                journal,
                [](const JournalEntry& e) { return std::holds_alternative<SortieMoved>(e.event); }),
            2);
  const Server restored = Server::Restore(ServerConfig{}, kFrame, journal);
  for (std::uint8_t id = 1; id <= 3; ++id) {
    EXPECT_EQ(restored.mission()->mission_of(id).waypoints,
              server.mission()->mission_of(id).waypoints)
        << int{id};
    EXPECT_EQ(restored.mission()->progress(id).phase, server.mission()->progress(id).phase)
        << int{id};
  }
  EXPECT_EQ(restored.scheduler().stats().requests_sent, 0U);
}

TEST(ServerRebalance, NothingMovesWhenTurnedOff) {
  Air air(0.0);
  ServerConfig config;
  config.rebalance_sorties = false;
  Server server(config, kFrame);
  for (std::uint8_t id = 1; id <= 2; ++id) {
    air.Add(id);
    server.AddVehicle(id);
    air.vehicle(id).endpoint().SetTelemetry(At(10.0 * id, radio::FlightMode::kIdle, 0, 0, 100));
  }
  air.RunUntil(server, 5 * kSecond);
  server.LoadMission({Sorties(1, 1, 0.0), Sorties(2, 3, 20.0)});
  ASSERT_TRUE(server.Handle({OperatorCommand::Kind::kStart, 0, {}, 0.0, "test"}, Nanos{0}));
  air.Run(server, air.channel().now() + 60 * kSecond,
          [&] { return server.state() == MissionState::kRunning; });
  air.vehicle(2).endpoint().SetTelemetry(At(20.0, radio::FlightMode::kSearch, 1, 1, 80));
  air.vehicle(1).endpoint().SetTelemetry(At(10.0, radio::FlightMode::kLanded, 1, 2, 100));
  air.Run(server, air.channel().now() + 30 * kSecond,
          [&] { return server.mission()->progress(1).phase == DronePhase::kDone; });
  air.RunUntil(server, air.channel().now() + 20 * kSecond);
  EXPECT_EQ(server.mission()->progress(1).phase, DronePhase::kDone);
  EXPECT_EQ(server.mission()->progress(2).sortie_count, 3U);
}

}  // namespace
}  // namespace fireswarm::server
