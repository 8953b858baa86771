#include "fireswarm/server/server.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <boost/geometry/algorithms/correct.hpp>
#include <cmath>
#include <set>
#include <string>
#include <variant>
#include <vector>

#include "fireswarm/common/time.hpp"
#include "fireswarm/radio/parser.hpp"
#include "fireswarm/server/journal_format.hpp"
#include "server/fake_fleet.hpp"
#include "server/server_fixture.hpp"

namespace fireswarm::server {
namespace {

using Kind = OperatorCommand::Kind;

using common::Nanos;
using testing::Air;
using testing::FakeVehicle;
using testing::Fleet;
using testing::kFrame;
using testing::kSecond;
using testing::LaneMissions;
using testing::LastOf;
using testing::Missions;
using testing::ReportAt;
using testing::Searching;
using testing::StartLaneMission;

TEST(Server, UploadsStartsAndRunsTheMission) {
  Fleet fleet;
  EXPECT_EQ(fleet.server.state(), MissionState::kRunning);
  for (std::uint8_t id = 1; id <= 3; ++id) {
    EXPECT_EQ(fleet.server.mission()->progress(id).phase, DronePhase::kFlying);
    EXPECT_EQ(fleet.air.vehicle(id).starts_accepted(), 1);
  }
  fleet.RunFor(5 * kSecond);
  EXPECT_EQ(fleet.server.registry().LinkAt(2, common::ToSeconds(fleet.air.channel().now())),
            LinkState::kOk);
}

// mission_status_t said "running" while every drone flew home or had landed: the
// mission is returning once no drone searches, and complete when all are down.
TEST(Server, TheMissionIsReturningOnceNoDroneSearchesAndCompleteWhenAllHaveLanded) {
  Fleet fleet;
  const auto set_mode = [&](std::uint8_t id, radio::FlightMode mode, std::uint32_t time_ms) {
    radio::Telemetry telemetry = Searching(0, 0, time_ms);
    telemetry.mode = mode;
    fleet.air.vehicle(id).endpoint().SetTelemetry(telemetry);
  };
  set_mode(1, radio::FlightMode::kReturnToLaunch, 2'000);
  set_mode(2, radio::FlightMode::kLand, 2'000);
  fleet.RunFor(10 * kSecond);
  EXPECT_EQ(fleet.server.state(), MissionState::kRunning) << "vehicle 3 still searches";

  set_mode(3, radio::FlightMode::kReturnToLaunch, 12'000);
  fleet.air.Run(fleet.server, fleet.air.channel().now() + 10 * kSecond,
                [&] { return fleet.server.state() != MissionState::kRunning; });
  EXPECT_EQ(fleet.server.state(), MissionState::kReturning);

  for (std::uint8_t id = 1; id <= 3; ++id) set_mode(id, radio::FlightMode::kLanded, 30'000);
  fleet.air.Run(fleet.server, fleet.air.channel().now() + 10 * kSecond,
                [&] { return fleet.server.state() == MissionState::kComplete; });
  EXPECT_EQ(fleet.server.state(), MissionState::kComplete);
}

TEST(Server, SendsTheNearestOtherVehicleToANewFireAndResumesItOnConfirmation) {
  Fleet fleet;
  // Vehicle 1 sees a fire 150 m east of the origin; 2 is nearer than 3.
  fleet.air.vehicle(1).endpoint().QueueFireReport(ReportAt(150, 0, 0, 2'000));
  fleet.RunFor(5 * kSecond);
  ASSERT_EQ(fleet.server.fusion().tracks().size(), 1u);
  const FireTrack& track = fleet.server.fusion().tracks()[0];
  EXPECT_EQ(track.status, FireTrackStatus::kTentative);
  const radio::Command* order = LastOf(fleet.air.vehicle(2), radio::CommandType::kInvestigate);
  ASSERT_NE(order, nullptr) << "vehicle 2 was not sent to investigate";
  EXPECT_EQ(LastOf(fleet.air.vehicle(3), radio::CommandType::kInvestigate), nullptr);
  EXPECT_EQ(LastOf(fleet.air.vehicle(1), radio::CommandType::kInvestigate), nullptr);
  const common::EastNorth ordered = kFrame.ToLocal({order->lat_deg, order->lon_deg});
  EXPECT_NEAR(ordered.east_m, 150.0, 0.5);
  EXPECT_NEAR(ordered.north_m, 0.0, 0.5);
  // 60 s around it after the 150 m transit at 8 m/s, counted from the order.
  EXPECT_EQ(order->duration_s, 79);

  // Vehicle 2 sees it too: confirmed by two vehicles, and 2 goes back to its lanes.
  fleet.air.vehicle(2).endpoint().QueueFireReport(ReportAt(152, 0, 300, 9'000));
  fleet.RunFor(5 * kSecond);
  EXPECT_EQ(fleet.server.fusion().tracks()[0].status, FireTrackStatus::kConfirmed);
  EXPECT_NE(LastOf(fleet.air.vehicle(2), radio::CommandType::kResume), nullptr);
}

// A no-fly zone: the rectangle [east0, east1] x [north0, north1] m of the frame.
planner::MultiPolygon Zone(double east0, double north0, double east1, double north1) {
  planner::Polygon zone{{{east0, north0}, {east0, north1}, {east1, north1}, {east1, north0}}};
  boost::geometry::correct(zone);
  return {zone};
}

ServerConfig WithNoFly(planner::MultiPolygon zones) {
  ServerConfig config;
  config.no_fly = std::move(zones);
  return config;
}

bool Journaled(const std::vector<JournalEntry>& journal, const std::string& kind,
               const std::string& why_part) {
  return std::ranges::any_of(journal, [&](const JournalEntry& e) {
    return JournalKindOf(e) == kind &&
           JournalDataOf(e).value("why", std::string()).find(why_part) != std::string::npos;
  });
}

TEST(Server, SendsNoInvestigatorWhoseStraightApproachCrossesANoFlyZone) {
  // A zone 50 m wide between the fire (150 m east) and vehicle 2 (300 m east),
  // the nearest other vehicle; vehicle 3 is 1.5 km north of the fire, its way clear.
  Fleet fleet(WithNoFly(Zone(200, -100, 250, 100)));
  fleet.air.vehicle(3).endpoint().SetTelemetry(Searching(150, 1'500, 2'000));
  fleet.RunFor(3 * kSecond);
  fleet.air.vehicle(1).endpoint().QueueFireReport(ReportAt(150, 0, 0, 4'000));
  fleet.RunFor(5 * kSecond);
  ASSERT_EQ(fleet.server.fusion().tracks().size(), 1u);
  EXPECT_EQ(LastOf(fleet.air.vehicle(2), radio::CommandType::kInvestigate), nullptr)
      << "vehicle 2 was sent through the zone";
  EXPECT_NE(LastOf(fleet.air.vehicle(3), radio::CommandType::kInvestigate), nullptr);
  EXPECT_EQ(LastOf(fleet.air.vehicle(1), radio::CommandType::kInvestigate), nullptr);
}

TEST(Server, SendsNoInvestigatorWhoseWayBackToItsLaneCrossesANoFlyZone) {
  // Vehicle 1 at the origin, points 200 m north and south of it. Its way north
  // is clear, but a zone 3 to 9 m east of that line lies where it flies back
  // from the east side of the circle to where it left its lane.
  Fleet fleet(WithNoFly(Zone(3, 90, 9, 110)));
  fleet.RunFor(3 * kSecond);  // every vehicle's position in
  const auto retask = [&](double north_m, std::string* why) {
    const OperatorCommand command{OperatorCommand::Kind::kRetaskVehicle, 1,
                                  kFrame.ToGeodetic({0.0, north_m}), 0.0, ""};
    return fleet.server.Handle(command, fleet.air.channel().now(), why);
  };
  std::string why;
  EXPECT_FALSE(retask(200.0, &why));
  EXPECT_EQ(why,
            "vehicle 1's straight way to the circle or back to its lane crosses a no-fly zone");
  EXPECT_TRUE(retask(-200.0, &why)) << why;
}

TEST(Server, SendsNobodyToCircleIntoANoFlyZoneAndJournalsWhy) {
  // The fire is 10 m from a zone: the vehicles' 20 m circle around it would enter it.
  Fleet fleet(WithNoFly(Zone(160, -100, 200, 100)));
  fleet.air.vehicle(1).endpoint().QueueFireReport(ReportAt(150, 0, 0, 2'000));
  fleet.RunFor(5 * kSecond);
  ASSERT_EQ(fleet.server.fusion().tracks().size(), 1u);
  for (std::uint8_t id = 1; id <= 3; ++id) {
    EXPECT_EQ(LastOf(fleet.air.vehicle(id), radio::CommandType::kInvestigate), nullptr)
        << "vehicle " << int{id} << " was sent";
  }
  EXPECT_TRUE(fleet.server.investigations().empty());
  EXPECT_TRUE(Journaled(fleet.server.TakeJournalEntries(), "no_investigation",
                        "the 20 m circle around the point enters a no-fly zone"));
}

TEST(Server, RefusesAnOperatorInvestigationIntoANoFlyZoneWithTheReason) {
  // Vehicles at 0, 300 and 2,000 m east; the zone between 1 and the others.
  Fleet fleet(WithNoFly(Zone(100, -100, 200, 100)));
  fleet.RunFor(3 * kSecond);  // every vehicle's position in
  const auto order = [&](OperatorCommand::Kind kind, std::uint8_t vehicle, double east_m,
                         double north_m, std::string* why) {
    const OperatorCommand command{kind, vehicle, kFrame.ToGeodetic({east_m, north_m}), 0.0, ""};
    return fleet.server.Handle(command, fleet.air.channel().now(), why);
  };
  std::string why;
  EXPECT_FALSE(order(Kind::kInvestigatePoint, 0, 150, 0, &why));
  EXPECT_EQ(why, "the point is inside a no-fly zone");
  EXPECT_FALSE(order(Kind::kInvestigatePoint, 0, 90, 0, &why));
  EXPECT_EQ(why, "the 20 m circle around the point enters a no-fly zone");
  EXPECT_FALSE(order(Kind::kRetaskVehicle, 2, 50, 0, &why));
  EXPECT_EQ(why,
            "vehicle 2's straight way to the circle or back to its lane crosses a no-fly zone");
  // West of the zone only vehicle 1 can go.
  EXPECT_TRUE(order(Kind::kInvestigatePoint, 0, 50, 0, &why)) << why;
  ASSERT_EQ(fleet.server.investigations().size(), 1u);
  EXPECT_EQ(fleet.server.investigations().back().vehicle, 1);
  // With 1 busy, nobody has a clear way there.
  EXPECT_FALSE(order(Kind::kInvestigatePoint, 0, 40, 50, &why));
  EXPECT_EQ(why,
            "no searching vehicle has a straight way there and back clear of the no-fly zones (2 "
            "would cross one)");
}

TEST(Server, RejectsATrackTheInvestigatorDidNotSeeAgain) {
  Fleet fleet;
  fleet.air.vehicle(3).endpoint().QueueFireReport(ReportAt(1'900, 0, 2'000, 2'000));
  fleet.RunFor(5 * kSecond);
  ASSERT_EQ(fleet.server.fusion().tracks().size(), 1u);
  const radio::Command* order = LastOf(fleet.air.vehicle(2), radio::CommandType::kInvestigate);
  ASSERT_NE(order, nullptr);
  EXPECT_EQ(order->duration_s, 260) << "1,600 m at 8 m/s, then 60 s around the point";
  // Vehicle 2 gets there and circles, and reports nothing.
  fleet.air.vehicle(2).endpoint().SetTelemetry(Searching(1'880, 0, 60'000));
  fleet.RunFor(200 * kSecond);
  EXPECT_EQ(fleet.server.fusion().tracks()[0].status, FireTrackStatus::kTentative)
      << "judged before the investigation was over";
  fleet.RunFor(80 * kSecond);
  EXPECT_EQ(fleet.server.fusion().tracks()[0].status, FireTrackStatus::kRejected);
}

// An investigator that never came near the point (called away, slow, lost) says
// nothing about the track: rejecting it would lose a real fire for good, since a
// rejected track absorbs every later report.
TEST(Server, AnInvestigatorThatNeverGotNearRejectsNothing) {
  Fleet fleet;
  fleet.air.vehicle(3).endpoint().QueueFireReport(ReportAt(1'900, 0, 2'000, 2'000));
  fleet.RunFor(300 * kSecond);  // vehicle 2's telemetry stays 1.6 km away
  ASSERT_EQ(fleet.server.investigations().size(), 1u);
  EXPECT_TRUE(fleet.server.investigations()[0].judged);
  EXPECT_EQ(fleet.server.fusion().tracks()[0].status, FireTrackStatus::kTentative);
}

// The reporter is the only searching vehicle, so it investigates its own track and
// sees it again on the same pass: the track stays tentative (no independent view),
// is not rejected, and the server stops waiting for the verdict (a wake-up stuck in
// the past would spin a lockstep loop forever).
TEST(Server, AnInvestigationSeenAgainIsJudgedOnceAndNotWaitedForAgain) {
  Air air(0.0);
  Server server(ServerConfig{}, kFrame);
  air.Add(1);
  server.AddVehicle(1);
  server.LoadMission(Missions({1}));
  air.vehicle(1).endpoint().SetTelemetry(Searching(0, 0, 1'000));
  ASSERT_TRUE(server.Handle({OperatorCommand::Kind::kStart, 0, {}, 0.0, ""}, Nanos{0}));
  air.Run(server, 60 * kSecond, [&] { return server.state() == MissionState::kRunning; });
  air.vehicle(1).endpoint().QueueFireReport(ReportAt(50, 0, 0, 2'000));
  air.RunUntil(server, air.channel().now() + 5 * kSecond);
  ASSERT_EQ(server.investigations().size(), 1u);
  EXPECT_EQ(server.investigations()[0].vehicle, 1);
  air.vehicle(1).endpoint().QueueFireReport(ReportAt(51, 0, 0, 9'000));
  air.RunUntil(server, air.channel().now() + 90 * kSecond);
  ASSERT_EQ(server.fusion().tracks().size(), 1u);
  EXPECT_EQ(server.fusion().tracks()[0].status, FireTrackStatus::kTentative);
  EXPECT_TRUE(server.investigations()[0].judged);
  EXPECT_GT(server.NextWakeup(), air.channel().now());
}

TEST(Server, RestoredFromItsJournalKeepsTracksAndPhasesAndUploadsNothingAgain) {
  Fleet fleet;
  fleet.air.vehicle(1).endpoint().QueueFireReport(ReportAt(150, 0, 0, 2'000));
  fleet.air.vehicle(3).endpoint().QueueFireReport(ReportAt(1'800, 40, 2'000, 2'500));
  fleet.RunFor(10 * kSecond);
  std::vector<JournalEntry> journal = fleet.server.TakeJournalEntries();
  ASSERT_FALSE(journal.empty());

  const Server restored = Server::Restore(ServerConfig{}, kFrame, journal);
  EXPECT_EQ(restored.state(), fleet.server.state());
  EXPECT_EQ(restored.fusion().tracks(), fleet.server.fusion().tracks());
  EXPECT_EQ(restored.fusion().next_track_id(), fleet.server.fusion().next_track_id());
  EXPECT_EQ(restored.investigations().size(), fleet.server.investigations().size());
  for (std::uint8_t id = 1; id <= 3; ++id) {
    EXPECT_EQ(restored.mission()->progress(id).phase, DronePhase::kFlying);
  }
  EXPECT_EQ(restored.scheduler().stats().requests_sent, 0u);
  // Far from the sequence numbers the vehicles last answered: a new request is not
  // mistaken for a resend of an old one.
  const int gap =
      (restored.scheduler().next_sequence() - fleet.server.scheduler().next_sequence() + 65'536) %
      65'536;
  EXPECT_GT(gap, 30'000);
  EXPECT_LT(gap, 35'536);
  EXPECT_EQ(restored.registry().ids(), fleet.server.registry().ids());
}

// A patrol: the server flies the next mission once the one before is complete,
// under IDs none of the vehicles has flown, keeps the fire tracks, and a restart
// from the journal of both comes back flying the second.
TEST(Server, FliesMissionAfterMissionOnceTheOneBeforeIsOver) {
  Fleet fleet;
  fleet.air.vehicle(1).endpoint().QueueFireReport(ReportAt(150, 0, 0, 2'000));
  fleet.RunFor(10 * kSecond);
  ASSERT_EQ(fleet.server.fusion().tracks().size(), 1u);
  const auto next_missions = [&] {
    std::vector<DroneMission> missions = Missions({1, 2, 3});
    for (DroneMission& m : missions) m.mission_id = fleet.server.NextMissionId();
    return missions;
  };
  EXPECT_FALSE(fleet.server.MissionOver());
  EXPECT_THROW(fleet.server.LoadMission(next_missions()), std::invalid_argument)
      << "the first is still running";

  for (std::uint8_t id = 1; id <= 3; ++id) {
    radio::Telemetry landed = Searching(0, 0, 20'000);
    landed.mode = radio::FlightMode::kLanded;
    fleet.air.vehicle(id).endpoint().SetTelemetry(landed);
  }
  fleet.air.Run(fleet.server, fleet.air.channel().now() + 20 * kSecond,
                [&] { return fleet.server.state() == MissionState::kComplete; });
  ASSERT_EQ(fleet.server.state(), MissionState::kComplete);
  ASSERT_TRUE(fleet.server.MissionOver());
  EXPECT_THROW(fleet.server.LoadMission(Missions({1, 2, 3})), std::invalid_argument)
      << "ID 1 is the first mission's: a vehicle would take it for a resend";

  const std::uint16_t second_id = fleet.server.NextMissionId();
  EXPECT_GT(second_id, 1);
  fleet.server.LoadMission(next_missions());
  EXPECT_EQ(fleet.server.state(), MissionState::kIdle);
  ASSERT_TRUE(fleet.server.Handle({Kind::kStart, 0, {}, 0.0, "test"}, fleet.air.channel().now()));
  for (std::uint8_t id = 1; id <= 3; ++id) {
    radio::Telemetry searching = Searching(0, 0, 40'000);
    searching.mission_id = second_id;
    fleet.air.vehicle(id).endpoint().SetTelemetry(searching);
  }
  fleet.air.Run(fleet.server, fleet.air.channel().now() + 60 * kSecond,
                [&] { return fleet.server.state() == MissionState::kRunning; });
  ASSERT_EQ(fleet.server.state(), MissionState::kRunning);
  for (std::uint8_t id = 1; id <= 3; ++id) {
    EXPECT_EQ(fleet.air.vehicle(id).starts_accepted(), 2) << "vehicle " << int{id};
    EXPECT_EQ(LastOf(fleet.air.vehicle(id), radio::CommandType::kStartMission)->mission_id,
              second_id);
  }
  EXPECT_EQ(fleet.server.fusion().tracks().size(), 1u) << "the tracks outlive the mission";

  const std::vector<JournalEntry> journal = fleet.server.TakeJournalEntries();
  const std::vector<JournalEntry> compacted = CompactJournal(journal, FireFusionConfig{});
  EXPECT_LT(compacted.size(), journal.size());
  EXPECT_EQ(std::ranges::count_if(
                compacted,
                [](const JournalEntry& e) { return std::holds_alternative<ReportFused>(e.event); }),
            0)
      << "the first mission's report is in the snapshot";
  EXPECT_EQ(std::ranges::count_if(compacted,
                                  [](const JournalEntry& e) {
                                    return std::holds_alternative<MissionLoaded>(e.event);
                                  }),
            1)
      << "only the second mission";
  EXPECT_EQ(CompactJournal(compacted, FireFusionConfig{}).size(), compacted.size())
      << "compacting twice changes nothing";
  // Both the whole journal and the compacted one, through the file's record format.
  for (const std::vector<JournalEntry>* entries : {&journal, &compacted}) {
    std::vector<JournalEntry> read;
    std::uint64_t seq = 0;
    for (const JournalEntry& entry : *entries) {
      read.push_back(JournalEntryOf(
          JournalRecord{++seq, entry.t_s, JournalKindOf(entry), JournalDataOf(entry)}));
    }
    const Server restored = Server::Restore(ServerConfig{}, kFrame, read);
    EXPECT_EQ(restored.state(), MissionState::kRunning);
    EXPECT_EQ(restored.NextMissionId(), fleet.server.NextMissionId());
    EXPECT_EQ(restored.mission()->mission_of(2).mission_id, second_id);
    EXPECT_EQ(restored.mission()->progress(2).phase, DronePhase::kFlying);
    EXPECT_EQ(restored.fusion().state(), fleet.server.fusion().state());
    EXPECT_EQ(restored.report_stats(), fleet.server.report_stats());
    EXPECT_EQ(restored.next_command_id(), fleet.server.next_command_id())
        << "no command ID given twice";
  }
}

TEST(Server, ADroneGivenUpAsLostIsSentHomeWhenHeardAgain) {
  Air air(0.0);
  Server server(ServerConfig{}, kFrame);
  StartLaneMission(air, server);
  air.silent.insert(2);
  air.Run(server, air.channel().now() + 30 * kSecond,
          [&] { return server.mission()->progress(2).phase == DronePhase::kFailed; });
  ASSERT_EQ(server.mission()->progress(2).phase, DronePhase::kFailed);
  ASSERT_EQ(LastOf(air.vehicle(2), radio::CommandType::kReturnToLaunch), nullptr);

  // Only out of reach: it is heard again, still searching its old lanes, which
  // 1 and 3 now fly. It is ordered home, once.
  air.silent.erase(2);
  air.Run(server, air.channel().now() + 30 * kSecond,
          [&] { return LastOf(air.vehicle(2), radio::CommandType::kReturnToLaunch) != nullptr; });
  EXPECT_NE(LastOf(air.vehicle(2), radio::CommandType::kReturnToLaunch), nullptr);
  EXPECT_EQ(LastOf(air.vehicle(1), radio::CommandType::kReturnToLaunch), nullptr);
  air.Run(server, air.channel().now() + 10 * kSecond, [] { return false; });
  std::vector<JournalEntry> journal = server.TakeJournalEntries();
  EXPECT_EQ(std::ranges::count_if(journal,
                                  [](const JournalEntry& e) {
                                    return std::holds_alternative<DroneRecalled>(e.event);
                                  }),
            1);
  EXPECT_TRUE(Journaled(journal, "recall", "heard again after its lanes were handed over"));
  // A restarted server knows it was recalled and leaves it be.
  Server restored = Server::Restore(ServerConfig{}, kFrame, journal);
  EXPECT_EQ(restored.mission()->progress(2).phase, DronePhase::kFailed);
}

TEST(Server, ALostDronesLanesGoToTheOthersAsNewMissions) {
  Air air(0.0);
  Server server(ServerConfig{}, kFrame);
  StartLaneMission(air, server);
  ASSERT_EQ(server.state(), MissionState::kRunning);

  const std::uint64_t missions_version = server.mission()->missions_version();
  // Vehicle 2 is gone: after the registry's lost time its two lanes are flown by 1 and 3.
  air.silent.insert(2);
  const Nanos gone_at = air.channel().now();
  air.Run(server, gone_at + 30 * kSecond, [&] {
    return server.mission()->progress(2).phase == DronePhase::kFailed &&
           server.mission()->progress(1).phase == DronePhase::kFlying &&
           server.mission()->progress(3).phase == DronePhase::kFlying &&
           server.mission()->mission_of(1).mission_id != 1 &&
           server.mission()->mission_of(3).mission_id != 1;
  });
  const double lost_after_s = ServerConfig{}.link.lost_after_s;
  EXPECT_GE(common::ToSeconds(air.channel().now() - gone_at), lost_after_s);
  ASSERT_EQ(server.mission()->progress(2).phase, DronePhase::kFailed);
  EXPECT_NE(server.mission()->progress(2).failure.find("lost"), std::string::npos);
  EXPECT_EQ(server.mission()->missions_version(), missions_version + 2)
      << "two missions replaced: the plan's lanes changed";
  // Each of the others stores and started its new mission: its own lanes, then one of 2's.
  std::set<std::uint16_t> ids;
  int lanes_given = 0;
  for (const std::uint8_t id : {std::uint8_t{1}, std::uint8_t{3}}) {
    const FakeVehicle& vehicle = air.vehicle(id);
    const DroneMission& mission = server.mission()->mission_of(id);
    ids.insert(mission.mission_id);
    EXPECT_TRUE(vehicle.complete());
    // As the wire carries them (1e-7 deg).
    ASSERT_EQ(vehicle.waypoints().size(), mission.waypoints.size());
    for (std::size_t i = 0; i < mission.waypoints.size(); ++i) {
      EXPECT_NEAR(vehicle.waypoints()[i].lat_deg, mission.waypoints[i].lat_deg, 1e-6);
      EXPECT_NEAR(vehicle.waypoints()[i].lon_deg, mission.waypoints[i].lon_deg, 1e-6);
      EXPECT_EQ(vehicle.waypoints()[i].flags, mission.waypoints[i].flags);
    }
    const radio::Command* start = LastOf(vehicle, radio::CommandType::kStartMission);
    ASSERT_NE(start, nullptr);
    EXPECT_EQ(start->mission_id, mission.mission_id);
    ASSERT_EQ(mission.waypoints.size(), 7U)
        << "own 2 lanes, one of vehicle 2's, back to where its own route ended";
    const common::EastNorth given =
        kFrame.ToLocal({mission.waypoints[4].lat_deg, mission.waypoints[4].lon_deg});
    EXPECT_TRUE(std::abs(given.east_m - 400.0) < 1.0 || std::abs(given.east_m - 600.0) < 1.0)
        << given.east_m;
    EXPECT_DOUBLE_EQ(mission.waypoints[4].altitude_m, 60.0 + id);  // its own layer
    lanes_given += 1;
  }
  EXPECT_EQ(ids.size(), 2U);
  EXPECT_EQ(ids.count(1), 0U);
  EXPECT_EQ(lanes_given, 2);

  // A restarted server knows: 2 lost, the new missions; it uploads nothing again.
  std::vector<JournalEntry> journal = server.TakeJournalEntries();
  Server restored = Server::Restore(ServerConfig{}, kFrame, journal);
  EXPECT_EQ(restored.mission()->progress(2).phase, DronePhase::kFailed);
  for (const std::uint8_t id : {std::uint8_t{1}, std::uint8_t{3}}) {
    EXPECT_EQ(restored.mission()->mission_of(id).waypoints,
              server.mission()->mission_of(id).waypoints);
    EXPECT_EQ(restored.mission()->progress(id).phase, DronePhase::kFlying);
  }
}

TEST(Server, AHandedOverLaneIsJoinedAroundANoFlyZone) {
  // As above, with a zone across vehicle 1's straight way from the end of its own
  // lanes (200 m east, 1 km north) to the nearer end of 2's first lane (400 m east).
  const planner::MultiPolygon zones = Zone(250, 900, 350, 1'100);
  Air air(0.0);
  Server server(WithNoFly(zones), kFrame);
  StartLaneMission(air, server);
  ASSERT_EQ(server.state(), MissionState::kRunning);
  air.silent.insert(2);
  air.Run(server, air.channel().now() + 30 * kSecond, [&] {
    return server.mission()->mission_of(1).mission_id != 1 &&
           server.mission()->mission_of(3).mission_id != 1;
  });
  for (const std::uint8_t id : {std::uint8_t{1}, std::uint8_t{3}}) {
    const DroneMission& mission = server.mission()->mission_of(id);
    ASSERT_NE(mission.mission_id, 1) << "vehicle " << int{id} << " got no lane";
    // From where it is, through its new mission.
    planner::Path flown{{400.0 * (id - 1), 0.0}};
    for (const radio::Waypoint& w : mission.waypoints) {
      const common::EastNorth p = kFrame.ToLocal({w.lat_deg, w.lon_deg});
      flown.emplace_back(p.east_m, p.north_m);
    }
    EXPECT_EQ(planner::InteriorLengthM(flown, zones), 0.0) << "vehicle " << int{id};
  }
  // Vehicle 1's join turns at the zone's corners: more than its 2 lanes and one of 2's.
  EXPECT_GT(server.mission()->mission_of(1).waypoints.size(), 6U);
}

TEST(Server, RestoreNamesTheBadEntry) {
  const std::vector<JournalEntry> journal{
      {0.0, 1, VehicleAdded{1}}, {1.0, 1, PhaseChanged{1, DronePhase::kFlying, 0, std::nullopt}}};
  try {
    (void)Server::Restore(ServerConfig{}, kFrame, journal);
    FAIL() << "a phase before any mission was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("journal entry 1 (phase): phase before any mission"),
              std::string::npos)
        << e.what();
  }
}

TEST(Server, OperatorCommandsAreCarriedOutOrRefusedWithAReason) {
  Air air(0.0);
  Server server(ServerConfig{}, kFrame);
  air.Add(1);
  server.AddVehicle(1);
  std::string why;
  EXPECT_FALSE(server.Handle({OperatorCommand::Kind::kStart, 0, {}, 0.0, ""}, Nanos{0}, &why));
  EXPECT_EQ(why, "no mission is loaded");
  EXPECT_FALSE(server.Handle({OperatorCommand::Kind::kRetaskVehicle, 9, {46.0, -74.5}, 0.0, ""},
                             Nanos{0}, &why));
  EXPECT_EQ(why, "vehicle 9 is not registered");
  EXPECT_FALSE(server.Handle({OperatorCommand::Kind::kRetaskVehicle, 1, {91.0, -74.5}, 0.0, ""},
                             Nanos{0}, &why));
  EXPECT_THROW(server.AddVehicle(1), std::invalid_argument);

  EXPECT_TRUE(server.Handle({OperatorCommand::Kind::kRetaskVehicle, 1, {46.001, -74.5}, 80.0, ""},
                            Nanos{0}, &why));
  EXPECT_TRUE(server.Handle({OperatorCommand::Kind::kReturnAll, 0, {}, 0.0, ""}, Nanos{0}));
  air.RunUntil(server, 5 * kSecond);
  const radio::Command* retask = LastOf(air.vehicle(1), radio::CommandType::kInvestigate);
  ASSERT_NE(retask, nullptr);
  EXPECT_NEAR(retask->lat_deg, 46.001, 1e-7);
  EXPECT_DOUBLE_EQ(retask->radius_m, 80.0);
  EXPECT_NE(LastOf(air.vehicle(1), radio::CommandType::kReturnToLaunch), nullptr);
}

// Issue 17, turn discipline as a defence: 80 fire reports forged as vehicles 1 and
// 2 (once enough for a confirmed track), each sent while the other vehicle held the
// turn, never reach fusion.
TEST(Server, ForgedFireReportsOutsideTheSendersTurnNeverReachFusion) {
  ServerConfig config;
  config.radio.mode = radio::LinkMode::kPoll;  // one vehicle's turn at a time
  config.radio.checksum = radio::ChecksumMode::kCrc16;
  Server server(config, kFrame);
  server.AddVehicle(1);
  server.AddVehicle(2);
  Nanos t{0};
  int forged_count = 0;
  for (int cycle = 0; cycle < 200 && forged_count < 80; ++cycle) {
    std::uint8_t granted = 0;
    for (const radio::Burst& burst : server.Step(t, {})) {
      radio::FrameParser parser(radio::ChecksumMode::kCrc16);
      parser.Feed(burst.bytes, [&](const radio::FrameView& frame) {
        if (frame.message_id == static_cast<std::uint8_t>(radio::MessageId::kPoll)) {
          granted = frame.receiver;
        }
      });
    }
    if (const std::optional<radio::ExchangeTiming> exchange = server.scheduler().exchange()) {
      if (granted == 1 || granted == 2) {
        const auto sender = static_cast<std::uint8_t>(3 - granted);
        radio::FireReport report = testing::ReportAt(150, 0, 0, 2'000U);
        report.header = radio::MessageHeader{sender, static_cast<std::uint16_t>(forged_count)};
        report.report_id = static_cast<std::uint16_t>(forged_count);
        std::vector<std::uint8_t> forged;
        radio::AppendMessageFrame(forged, radio::kServerId, report, radio::ChecksumMode::kCrc16);
        server.Step(exchange->burst_end + std::chrono::milliseconds(1), forged);
        ++forged_count;
      }
      t = std::max(t, exchange->deadline);
    } else {
      t = std::max(t + std::chrono::milliseconds(1), server.NextWakeup());
    }
  }
  ASSERT_EQ(forged_count, 80);
  EXPECT_TRUE(server.fusion().tracks().empty());
  EXPECT_EQ(server.scheduler().stats().out_of_turn, 80U);
}

}  // namespace
}  // namespace fireswarm::server
