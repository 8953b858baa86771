#include "fireswarm/server/journal_format.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "fireswarm/planner/area_io.hpp"
#include "fireswarm/server/server.hpp"

namespace fireswarm::server {
namespace {

using Kind = OperatorCommand::Kind;

using ::testing::HasSubstr;

DroneMission MissionOf(std::uint8_t vehicle, std::uint16_t mission_id) {
  DroneMission m;
  m.vehicle = vehicle;
  m.mission_id = mission_id;
  m.waypoints.push_back({46.1, -74.4, 60.0, 10.0, 1});
  m.waypoints.push_back({46.2, -74.3, 60.0, 10.0, 0});
  return m;
}

FireObservation Observation() {
  FireObservation o;
  o.vehicle_id = 3;
  o.report_id = 17;
  o.detection_time_s = 123.456;
  o.position_en_m = {12.5, -40.25};
  o.covariance_en_m2 << 9.0, 1.5, 1.5, 4.0;
  o.observer_en_m = {2.0, -60.0};
  o.confidence = 0.8;
  return o;
}

// The entry read back from the record it is written as.
JournalEntry RoundTrip(const JournalEntry& entry, std::uint64_t seq = 1) {
  JournalRecord record;
  record.seq = seq;
  record.t_s = entry.t_s;
  record.kind = JournalKindOf(entry);
  record.data = JournalDataOf(entry);
  // Through text, as in the file.
  record.data = nlohmann::json::parse(record.data.dump());
  return JournalEntryOf(record);
}

TEST(JournalFormat, EveryEventComesBackAsItWasWritten) {
  const std::vector<JournalEntry> entries{
      {0.0, 1, VehicleAdded{4}},
      {0.5, 2, MissionLoaded{{MissionOf(4, 1), MissionOf(5, 1)}, std::nullopt}},
      {1.0, 3,
       CommandAccepted{OperatorCommand::Kind::kRetaskVehicle, 4, {46.0, -74.5}, "look again"}},
      {2.0, 4, PhaseChanged{4, DronePhase::kFlying, 0, std::nullopt}},
      {3.0, 5, LanesHandedOver{5, "lost: not heard for 20 s", {MissionOf(4, 2)}, 2}},
      {4.0, 6, MissionStateChanged{MissionState::kRunning}},
      {5.0, 7, ReportFused{Observation()}},
      {6.0, 8, TrackRejected{2, 4}},
      {7.0, 9, InvestigationOpened{4, 2, 99.5, {30.0, -10.0}}},
      {8.0, 10, InvestigationNotSent{3, "no searching vehicle with a working link"}},
      {9.0, std::nullopt, DroneRecalled{5, "heard again"}},
      {10.0, 11, CommandAccepted{OperatorCommand::Kind::kHold, 2, {}, "signed", 7, "ann", 123, -5}},
      {11.0, 12,
       CommandRefused{CommandVerdict::kStale, 6, 2, "ann", 1, -2, "stale: utime 1 is outside"}},
      {12.0, 13, JournalCompacted{42, 1'234, std::nullopt, {}}},
  };
  for (const JournalEntry& entry : entries) {
    const JournalEntry back = RoundTrip(entry);
    SCOPED_TRACE(JournalKindOf(entry));
    EXPECT_EQ(back.t_s, entry.t_s);
    EXPECT_EQ(back.radio_seq, entry.radio_seq);
    EXPECT_EQ(back.event.index(), entry.event.index());
    EXPECT_EQ(JournalDataOf(back), JournalDataOf(entry));
  }
  const JournalEntry report_back = RoundTrip(entries[6]);
  const auto& report = std::get<ReportFused>(report_back.event);
  EXPECT_EQ(report.observation, Observation());
  const JournalEntry opened_back = RoundTrip(entries[8]);
  const auto& opened = std::get<InvestigationOpened>(opened_back.event);
  EXPECT_EQ(opened.point_en_m, Eigen::Vector2d(30.0, -10.0));
  const JournalEntry handed_back = RoundTrip(entries[4]);
  const auto& handed = std::get<LanesHandedOver>(handed_back.event);
  EXPECT_EQ(handed.drones[0].waypoints, MissionOf(4, 2).waypoints);
  EXPECT_EQ(handed.straight_joins, 2);
  const JournalEntry signed_entry = RoundTrip(entries[11]);
  const auto& signed_back = std::get<CommandAccepted>(signed_entry.event);
  EXPECT_EQ(signed_back.operator_id, "ann");
  EXPECT_EQ(signed_back.nonce, -5);
  const JournalEntry refused_entry = RoundTrip(entries[12]);
  const auto& refused = std::get<CommandRefused>(refused_entry.event);
  EXPECT_EQ(refused.verdict, CommandVerdict::kStale);
  EXPECT_EQ(refused.why, "stale: utime 1 is outside");
}

// A compaction's snapshot: the tracks (their evidence to the last bit), the
// duplicate check and the report counts come back as they were; a snapshot
// whose counts disagree is refused naming the line.
TEST(JournalFormat, ACompactionsSnapshotComesBackToTheBit) {
  FireFusion fusion;
  ReportStats stats;
  for (int i = 0; i < 100; ++i) {
    FireObservation o = Observation();
    o.vehicle_id = static_cast<std::uint8_t>(1 + i % 3);
    o.report_id = static_cast<std::uint16_t>(i);
    o.detection_time_s = 10.0 * i;
    o.position_en_m +=
        Eigen::Vector2d(0.37 * (i % 7), -0.11 * (i % 5)) + (i % 2) * Eigen::Vector2d(500.0, 0.0);
    o.covariance_en_m2 << 9.0 + 0.1 * i, 1.5, 1.5, 4.0 + 0.01 * i;
    o.observer_en_m += Eigen::Vector2d(3.0 * i, 0.0);
    fusion.Add(o);
    stats.Add(o.detection_time_s + 0.013 * i, o.detection_time_s);
  }
  fusion.Reject(2);
  JournalCompacted compacted{42, 1'234, fusion.state(), stats};
  const JournalEntry back = RoundTrip({12.0, 13, compacted});
  const auto& read = std::get<JournalCompacted>(back.event);
  ASSERT_TRUE(read.fusion.has_value());
  // Positions, covariances and vehicle lists are not written: recomputed.
  EXPECT_EQ(read.fusion->seen, fusion.state().seen);
  EXPECT_EQ(FireFusion::Restore({}, *read.fusion).state(), fusion.state());
  EXPECT_EQ(read.reports, stats);

  JournalRecord spoilt{7, 12.0, "compacted", JournalDataOf({12.0, 13, compacted})};
  spoilt.data["reports"]["fused"] = 99;
  try {
    JournalEntryOf(spoilt);
    FAIL() << "a snapshot with 99 reports fused and 100 latencies was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("journal line 7 (compacted)"), std::string::npos)
        << e.what();
  }
}

TEST(JournalFormat, SortiesComeBackWithTheMissionAndEachPhase) {
  DroneMission mission = MissionOf(4, 1);
  mission.sortie_starts = {1};
  const JournalEntry loaded = RoundTrip({0.5, 2, MissionLoaded{{mission}, std::nullopt}});
  EXPECT_EQ(std::get<MissionLoaded>(loaded.event).drones.at(0).sortie_starts,
            (std::vector<std::size_t>{1}));
  const JournalEntry phase = RoundTrip(
      {9.0, 3, PhaseChanged{4, DronePhase::kSwapping, 2, std::vector<std::size_t>{3, 7, 9}}});
  const auto& changed = std::get<PhaseChanged>(phase.event);
  EXPECT_EQ(changed.phase, DronePhase::kSwapping);
  EXPECT_EQ(changed.sortie, 2U);
  EXPECT_EQ(changed.sortie_starts, (std::vector<std::size_t>{3, 7, 9}));
}

TEST(JournalFormat, ASortieMovedComesBackWithItsDonorAndTheTakersMission) {
  DroneMission taker = MissionOf(2, 3);
  taker.mission_id = 17;
  const JournalEntry entry{120.0, 5, SortieMoved{4, taker}};
  EXPECT_EQ(JournalKindOf(entry), "sortie_moved");
  const JournalEntry back = RoundTrip(entry);
  const auto& moved = std::get<SortieMoved>(back.event);
  EXPECT_EQ(moved.from, 4);
  EXPECT_EQ(moved.taker.vehicle, 2);
  EXPECT_EQ(moved.taker.mission_id, 17);
  EXPECT_EQ(moved.taker.waypoints, taker.waypoints);
}

TEST(JournalFormat, KeepsTheRecordNamesAndFieldsOfTheFormatBeforeTypes) {
  EXPECT_EQ(JournalKindOf({0.0, 1, CommandAccepted{OperatorCommand::Kind::kStart, 0, {}, "go"}}),
            "start");
  EXPECT_EQ(JournalKindOf({0.0, 1, CommandAccepted{OperatorCommand::Kind::kReturnAll, 0, {}, ""}}),
            "return_all");
  EXPECT_EQ(JournalDataOf({0.0, 7, PhaseChanged{4, DronePhase::kFlying, 0, std::nullopt}}),
            nlohmann::json({{"vehicle", 4}, {"phase", 2}, {"radio_seq", 7}}));
  // Positions and covariances stay (north, east) in the file.
  FireObservation o = Observation();
  o.position_en_m = {1.0, 2.0};
  o.covariance_en_m2 << 9.0, 1.5, 1.5, 4.0;
  const nlohmann::json report = JournalDataOf({0.0, 1, ReportFused{o}});
  EXPECT_EQ(report.at("position_ne_m"), nlohmann::json({2.0, 1.0}));
  EXPECT_EQ(report.at("covariance_ne_m2"), nlohmann::json({4.0, 1.5, 9.0}));
  // A hand-over whose joins were all routed says nothing of them.
  EXPECT_FALSE(
      JournalDataOf({0.0, 1, LanesHandedOver{5, "lost", {}, 0}}).contains("straight_joins"));
}

// The per-drone and fleet orders have records of their own, with the command's ID;
// a command record written before IDs existed reads as ID 0 (unknown).
TEST(JournalFormat, EveryCommandKindComesBackWithItsId) {
  const std::pair<Kind, const char*> kinds[] = {{Kind::kStart, "start"},
                                                {Kind::kAbort, "abort"},
                                                {Kind::kReturnAll, "return_all"},
                                                {Kind::kInvestigatePoint, "investigate_order"},
                                                {Kind::kRetaskVehicle, "investigate_order"},
                                                {Kind::kHold, "hold"},
                                                {Kind::kResume, "resume"},
                                                {Kind::kReturnVehicle, "return"},
                                                {Kind::kLand, "land"},
                                                {Kind::kHoldAll, "hold_all"},
                                                {Kind::kResumeAll, "resume_all"}};
  std::int32_t id = 0;
  for (const auto& [kind, name] : kinds) {
    const JournalEntry entry{1.0, 2, CommandAccepted{kind, 7, {46.0, -74.5}, "smoke", ++id}};
    SCOPED_TRACE(name);
    EXPECT_EQ(JournalKindOf(entry), name);
    EXPECT_EQ(JournalDataOf(entry).at("command_id"), id);
    const auto back = std::get<CommandAccepted>(RoundTrip(entry).event);
    EXPECT_EQ(back.command, kind);
    EXPECT_EQ(back.vehicle, 7);
    EXPECT_EQ(back.reason, "smoke");
    EXPECT_EQ(back.command_id, id);
  }
  const nlohmann::json before_ids = {
      {"command", 3}, {"vehicle", 0}, {"lat_deg", 0.0}, {"lon_deg", 0.0}, {"reason", ""}};
  const JournalEntry old = JournalEntryOf({9, 2.0, "return_all", before_ids});
  EXPECT_EQ(std::get<CommandAccepted>(old.event).command_id, 0);
  EXPECT_FALSE(
      JournalDataOf({0.0, 1, CommandAccepted{Kind::kAbort, 0, {}, "", 0}}).contains("command_id"));
}

TEST(JournalFormat, ABadRecordNamesItsLineKindAndProblem) {
  const auto error_of = [](const JournalRecord& record) -> std::string {
    try {
      (void)JournalEntryOf(record);
    } catch (const std::runtime_error& e) {
      return e.what();
    }
    return "no exception";
  };
  const std::string missing = error_of({12, 1.0, "report", {{"vehicle", 1}}});
  EXPECT_THAT(missing, HasSubstr("journal line 12 (report): "));
  EXPECT_THAT(missing, HasSubstr("report_id"));
  EXPECT_THAT(error_of({3, 1.0, "teleport", nlohmann::json::object()}),
              HasSubstr("journal line 3 (teleport): unknown kind"));
  EXPECT_THAT(error_of({4, 1.0, "vehicle", {{"id", "one"}}}),
              HasSubstr("journal line 4 (vehicle): "));
  EXPECT_THAT(error_of({5, 1.0, "state", nlohmann::json::array()}),
              HasSubstr("journal line 5 (state): data is not a JSON object"));
  const nlohmann::json start = {
      {"command", 1}, {"vehicle", 0}, {"lat_deg", 0.0}, {"lon_deg", 0.0}, {"reason", ""}};
  EXPECT_THAT(error_of({6, 1.0, "abort", start}),
              HasSubstr("journal line 6 (abort): kind abort holds command 1 (start)"));
  nlohmann::json hold = start;
  hold["command"] = 6;
  EXPECT_THAT(error_of({7, 1.0, "land", hold}),
              HasSubstr("journal line 7 (land): kind land holds command 6 (hold)"));
  hold["command"] = 12;
  EXPECT_THAT(error_of({8, 1.0, "hold", hold}),
              HasSubstr("journal line 8 (hold): unknown command 12"));
}

// tests/server/data/journal_v0.jsonl was written by `fireswarm serve --journal`
// before journal entries were typed and the format had a version (2 simulated
// drones over journal_v0_area.geojson, a fire 170 m east of the launch site; the
// server's last summary: both drones done, track 1 confirmed by both at
// 46.50002656298229, 7.502246609823232). It must still restore.
TEST(JournalFormat, AJournalOfTheFormatBeforeVersionsStillRestores) {
  const std::filesystem::path data = FIRESWARM_SERVER_TEST_DATA;
  // A copy: Open locks its file and would cut a torn line off it.
  const std::filesystem::path copy = std::filesystem::path(::testing::TempDir()) /
                                     ("journal_v0_" + std::to_string(::getpid()) + ".jsonl");
  std::filesystem::copy_file(data / "journal_v0.jsonl", copy,
                             std::filesystem::copy_options::overwrite_existing);
  std::vector<JournalEntry> entries;
  std::uint32_t newest_version = 0;
  {
    const Journal journal = Journal::Open(copy, [&](const JournalRecord& record) {
      newest_version = std::max(newest_version, record.version);
      entries.push_back(JournalEntryOf(record));
    });
    EXPECT_EQ(journal.recovery().dropped_lines, 0U);
  }
  std::filesystem::remove(copy);
  ASSERT_EQ(entries.size(), 18U);
  EXPECT_EQ(newest_version, 0U);

  const common::LocalFrame frame = planner::LoadSearchArea(data / "journal_v0_area.geojson").frame;
  const Server server = Server::Restore(ServerConfig{}, frame, entries);
  EXPECT_EQ(server.registry().ids(), (std::vector<std::uint8_t>{1, 2}));
  EXPECT_EQ(server.state(), MissionState::kComplete);
  EXPECT_EQ(server.mission_started_s(), 0.0);
  ASSERT_NE(server.mission(), nullptr);
  for (const std::uint8_t id : {std::uint8_t{1}, std::uint8_t{2}}) {
    EXPECT_EQ(server.mission()->progress(id).phase, DronePhase::kDone) << int{id};
    EXPECT_EQ(server.mission()->mission_of(id).waypoints.size(), 5U) << int{id};
  }
  // The track with its ID, confirmed by both drones, where the old server had it.
  ASSERT_EQ(server.fusion().tracks().size(), 1U);
  const FireTrack& track = server.fusion().tracks()[0];
  EXPECT_EQ(track.track_id, 1);
  EXPECT_EQ(server.fusion().next_track_id(), 2);
  EXPECT_EQ(track.status, FireTrackStatus::kConfirmed);
  EXPECT_EQ(track.report_count, 4);
  EXPECT_EQ(track.vehicle_ids, (std::vector<std::uint8_t>{1, 2}));
  const common::LatLon at = frame.ToGeodetic({track.position_en_m.x(), track.position_en_m.y()});
  EXPECT_NEAR(at.lat_deg, 46.50002656298229, 1e-12);
  EXPECT_NEAR(at.lon_deg, 7.502246609823232, 1e-12);
  EXPECT_EQ(server.report_stats().fused, 4U);
  // The investigation drone 1 was sent on, as it was ordered.
  ASSERT_EQ(server.investigations().size(), 1U);
  const Investigation& investigation = server.investigations()[0];
  EXPECT_EQ(investigation.vehicle, 1);
  EXPECT_EQ(investigation.track_id, 1);
  EXPECT_EQ(investigation.started_s, 2.7644084700000002);
  EXPECT_EQ(investigation.until_s, 82.76440847);
  EXPECT_EQ(investigation.point_en_m, Eigen::Vector2d(0.5894692185614455, 1.21165584297034));
  // The radio starts half its sequence space after the last journaled (64).
  EXPECT_EQ(server.scheduler().next_sequence(), 64 + 0x8000);
  // Its start had no ID yet but took one: the next command is 2.
  EXPECT_EQ(server.next_command_id(), 2);
}

}  // namespace
}  // namespace fireswarm::server
