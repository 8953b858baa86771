#include "fireswarm/agents/mission_store.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "radio/sim_net.hpp"

namespace fireswarm::agents {
namespace {

using radio::MissionAckStatus;
using radio::MissionChunk;
using radio::Waypoint;

constexpr double kBaseLatDeg = 45.2;
constexpr double kBaseLonDeg = 7.6;
constexpr double kStepDeg = 3.3e-4;  // ~35 m between waypoints
constexpr double kStoredAltitudeM = 60.3;
constexpr double kSpeedMps = 8.4;

std::vector<Waypoint> MakeWaypoints(std::size_t count, double offset_deg = 0.0) {
  std::vector<Waypoint> waypoints(count);
  for (std::size_t i = 0; i < count; ++i) {
    const auto step = static_cast<double>(i);
    waypoints[i].lat_deg = kBaseLatDeg + offset_deg + kStepDeg * step;
    waypoints[i].lon_deg = kBaseLonDeg - kStepDeg * step * step / 50.0;
    waypoints[i].altitude_m = kStoredAltitudeM;
    waypoints[i].speed_mps = kSpeedMps;
    waypoints[i].flags = static_cast<std::uint8_t>(i % 2);
  }
  return waypoints;
}

// --- reassembly

TEST(MissionStore, CompletesInOrder) {
  const std::vector<Waypoint> waypoints = MakeWaypoints(45);
  const std::vector<MissionChunk> chunks = radio::SplitMission(3, waypoints);
  ASSERT_EQ(chunks.size(), 3U);
  MissionStore store;
  EXPECT_EQ(store.complete(), nullptr);
  EXPECT_EQ(store.OnChunk(chunks[0]), MissionAckStatus::kAccepted);
  ASSERT_TRUE(store.upload().has_value());
  EXPECT_EQ(store.upload()->mission_id, 3);
  EXPECT_EQ(store.upload()->chunks_received, 1U);
  EXPECT_EQ(store.upload()->chunk_count, 3U);
  EXPECT_EQ(store.upload()->waypoints_received, 20U);
  EXPECT_EQ(store.upload()->total_waypoints, 45U);
  EXPECT_EQ(store.OnChunk(chunks[1]), MissionAckStatus::kAccepted);
  EXPECT_FALSE(store.IsComplete(3));
  EXPECT_EQ(store.OnChunk(chunks[2]), MissionAckStatus::kComplete);
  EXPECT_TRUE(store.IsComplete(3));
  ASSERT_NE(store.complete(), nullptr);
  EXPECT_EQ(store.complete()->id, 3);
  EXPECT_EQ(store.complete()->waypoints, waypoints);
  EXPECT_FALSE(store.upload().has_value());
  EXPECT_EQ(store.rejected_chunks(), 0U);
}

TEST(MissionStore, CompletesOutOfOrder) {
  const std::vector<Waypoint> waypoints = MakeWaypoints(70);
  std::vector<MissionChunk> chunks = radio::SplitMission(4, waypoints);
  std::swap(chunks[0], chunks[2]);
  std::reverse(chunks.begin() + 1, chunks.end());
  MissionStore store;
  for (std::size_t c = 0; c + 1 < chunks.size(); ++c) {
    EXPECT_EQ(store.OnChunk(chunks[c]), MissionAckStatus::kAccepted) << c;
  }
  EXPECT_EQ(store.OnChunk(chunks.back()), MissionAckStatus::kComplete);
  ASSERT_NE(store.complete(), nullptr);
  EXPECT_EQ(store.complete()->waypoints, waypoints);
}

TEST(MissionStore, SingleChunkMissionCompletesAtOnce) {
  MissionStore store;
  EXPECT_EQ(store.OnChunk(radio::SplitMission(1, MakeWaypoints(1)).at(0)),
            MissionAckStatus::kComplete);
  EXPECT_TRUE(store.IsComplete(1));
}

TEST(MissionStore, ResentChunksAreIdempotent) {
  const std::vector<MissionChunk> chunks = radio::SplitMission(5, MakeWaypoints(30));
  MissionStore store;
  EXPECT_EQ(store.OnChunk(chunks[0]), MissionAckStatus::kAccepted);
  EXPECT_EQ(store.OnChunk(chunks[0]), MissionAckStatus::kAccepted);
  EXPECT_EQ(store.upload()->chunks_received, 1U);
  EXPECT_EQ(store.upload()->waypoints_received, 20U);
  EXPECT_EQ(store.OnChunk(chunks[1]), MissionAckStatus::kComplete);
  // Retries after completion (the ack was lost) get the same answer.
  EXPECT_EQ(store.OnChunk(chunks[1]), MissionAckStatus::kComplete);
  EXPECT_EQ(store.OnChunk(chunks[0]), MissionAckStatus::kComplete);
  EXPECT_FALSE(store.upload().has_value());
  EXPECT_EQ(store.complete()->waypoints, MakeWaypoints(30));
}

TEST(MissionStore, ChunksMayOverlapWhenTheyAgree) {
  const std::vector<Waypoint> waypoints = MakeWaypoints(30);
  std::vector<MissionChunk> chunks = radio::SplitMission(6, waypoints);
  // Chunk 1 re-covers waypoints 15..19 of chunk 0, with the same values.
  chunks[1].first_waypoint = 15;
  chunks[1].waypoint_count = 15;
  std::copy_n(waypoints.begin() + 15, 15, chunks[1].waypoints.begin());
  MissionStore store;
  EXPECT_EQ(store.OnChunk(chunks[0]), MissionAckStatus::kAccepted);
  EXPECT_EQ(store.OnChunk(chunks[1]), MissionAckStatus::kComplete);
  EXPECT_EQ(store.complete()->waypoints, waypoints);
}

// Every chunk index arrived but a waypoint index did not: not complete.
TEST(MissionStore, AllChunksWithAGapIsNotComplete) {
  std::vector<MissionChunk> chunks = radio::SplitMission(6, MakeWaypoints(30));
  chunks[1].first_waypoint = 21;  // waypoint 20 never arrives
  chunks[1].waypoint_count = 9;
  MissionStore store;
  EXPECT_EQ(store.OnChunk(chunks[0]), MissionAckStatus::kAccepted);
  EXPECT_EQ(store.OnChunk(chunks[1]), MissionAckStatus::kAccepted);
  EXPECT_FALSE(store.IsComplete(6));
  EXPECT_EQ(store.upload()->chunks_received, 2U);
  EXPECT_EQ(store.upload()->waypoints_received, 29U);
}

// --- inconsistent chunks: rejected, nothing changes

struct BadChunk {
  std::string name;
  std::function<void(MissionChunk&)> spoil;
};

class MissionStoreRejects : public ::testing::TestWithParam<BadChunk> {};

TEST_P(MissionStoreRejects, InconsistentChunkChangesNothing) {
  MissionStore store;
  // A complete mission 1, and mission 2 under way with chunk 0 of 3 stored.
  ASSERT_EQ(store.OnChunk(radio::SplitMission(1, MakeWaypoints(5, 0.1)).at(0)),
            MissionAckStatus::kComplete);
  const std::vector<MissionChunk> chunks = radio::SplitMission(2, MakeWaypoints(45));
  ASSERT_EQ(store.OnChunk(chunks[0]), MissionAckStatus::kAccepted);

  MissionChunk bad = chunks[1];
  GetParam().spoil(bad);
  EXPECT_EQ(store.OnChunk(bad), MissionAckStatus::kRejected);
  EXPECT_EQ(store.rejected_chunks(), 1U);
  ASSERT_TRUE(store.upload().has_value());
  EXPECT_EQ(store.upload()->mission_id, 2);
  EXPECT_EQ(store.upload()->chunks_received, 1U);
  EXPECT_EQ(store.upload()->waypoints_received, 20U);
  EXPECT_TRUE(store.IsComplete(1));
  EXPECT_EQ(store.complete()->waypoints, MakeWaypoints(5, 0.1));
  // The upload goes on as if the bad chunk never came.
  EXPECT_EQ(store.OnChunk(chunks[1]), MissionAckStatus::kAccepted);
  EXPECT_EQ(store.OnChunk(chunks[2]), MissionAckStatus::kComplete);
  EXPECT_EQ(store.complete()->waypoints, MakeWaypoints(45));
}

INSTANTIATE_TEST_SUITE_P(
    Cases, MissionStoreRejects,
    ::testing::Values(
        BadChunk{"OtherChunkCount", [](MissionChunk& c) { c.chunk_count = 4; }},
        BadChunk{"OtherTotalWaypoints", [](MissionChunk& c) { c.total_waypoints = 46; }},
        BadChunk{"ChunkIndexBeyondCount", [](MissionChunk& c) { c.chunk_index = 3; }},
        BadChunk{"ZeroChunkCount",
                 [](MissionChunk& c) {
                   c.chunk_count = 0;
                   c.chunk_index = 0;
                 }},
        BadChunk{"WaypointsBeyondTotal", [](MissionChunk& c) { c.first_waypoint = 30; }},
        BadChunk{"NoWaypoints", [](MissionChunk& c) { c.waypoint_count = 0; }},
        BadChunk{"MoreWaypointsThanAChunkHolds", [](MissionChunk& c) { c.waypoint_count = 21; }},
        BadChunk{"ZeroTotalWaypoints",
                 [](MissionChunk& c) {
                   c.mission_id = 9;  // even as a new mission
                   c.total_waypoints = 0;
                   c.waypoint_count = 0;
                 }},
        BadChunk{"LatitudeNaN",
                 [](MissionChunk& c) {
                   c.waypoints[3].lat_deg = std::numeric_limits<double>::quiet_NaN();
                 }},
        BadChunk{"LatitudeBeyondPole", [](MissionChunk& c) { c.waypoints[0].lat_deg = 90.5; }},
        BadChunk{"LongitudeBeyondRange", [](MissionChunk& c) { c.waypoints[19].lon_deg = -180.5; }},
        BadChunk{"LongitudeInfinite",
                 [](MissionChunk& c) {
                   c.waypoints[2].lon_deg = std::numeric_limits<double>::infinity();
                 }},
        BadChunk{"NegativeAltitude", [](MissionChunk& c) { c.waypoints[1].altitude_m = -1.0; }},
        BadChunk{"SpeedNaN",
                 [](MissionChunk& c) {
                   c.waypoints[1].speed_mps = std::numeric_limits<double>::quiet_NaN();
                 }},
        BadChunk{"InvalidChunkOfANewMission",
                 [](MissionChunk& c) {
                   c.mission_id = 9;  // would start a new upload, if it were valid
                   c.waypoints[0].lat_deg = 91.0;
                 }},
        BadChunk{"ResentChunkWithOtherWaypoints",
                 [](MissionChunk& c) {
                   c = radio::SplitMission(2, MakeWaypoints(45)).at(0);
                   c.waypoints[4].lat_deg += 1e-5;
                 }},
        BadChunk{"ResentChunkIndexWithOtherRange",
                 [](MissionChunk& c) {
                   c = radio::SplitMission(2, MakeWaypoints(45)).at(0);
                   c.first_waypoint = 25;  // chunk 0 covered 0..19; 25..44 are free
                 }},
        BadChunk{"CompleteMissionIdWithOtherWaypoints",
                 [](MissionChunk& c) {
                   c.mission_id = 1;  // the complete mission: a retry must agree with it
                   c.chunk_index = 0;
                   c.chunk_count = 1;
                   c.total_waypoints = 5;
                   c.first_waypoint = 0;
                   c.waypoint_count = 5;
                 }}),
    [](const auto& param_info) { return param_info.param.name; });

// --- a new upload and the complete mission

TEST(MissionStore, NewUploadReplacesTheCompleteMissionOnlyWhenItCompletes) {
  const std::vector<Waypoint> first = MakeWaypoints(25);
  const std::vector<Waypoint> second = MakeWaypoints(50, 0.01);
  const std::vector<Waypoint> third = MakeWaypoints(30, 0.02);
  MissionStore store;
  for (const MissionChunk& chunk : radio::SplitMission(1, first)) store.OnChunk(chunk);
  ASSERT_TRUE(store.IsComplete(1));

  const std::vector<MissionChunk> second_chunks = radio::SplitMission(2, second);
  EXPECT_EQ(store.OnChunk(second_chunks[0]), MissionAckStatus::kAccepted);
  EXPECT_EQ(store.OnChunk(second_chunks[1]), MissionAckStatus::kAccepted);
  EXPECT_TRUE(store.IsComplete(1));  // the half-uploaded mission does not fly
  EXPECT_FALSE(store.IsComplete(2));
  EXPECT_EQ(store.complete()->waypoints, first);

  // A late retry of mission 1 is answered without disturbing mission 2.
  EXPECT_EQ(store.OnChunk(radio::SplitMission(1, first).at(1)), MissionAckStatus::kComplete);
  EXPECT_EQ(store.upload()->mission_id, 2);
  EXPECT_EQ(store.upload()->chunks_received, 2U);

  // Mission 3 starts: the partial mission 2 is dropped, mission 1 still flies.
  const std::vector<MissionChunk> third_chunks = radio::SplitMission(3, third);
  EXPECT_EQ(store.OnChunk(third_chunks[1]), MissionAckStatus::kAccepted);
  EXPECT_EQ(store.upload()->mission_id, 3);
  EXPECT_EQ(store.upload()->chunks_received, 1U);
  EXPECT_TRUE(store.IsComplete(1));
  // Mission 2's last chunk now starts mission 2 over; it cannot complete alone.
  EXPECT_EQ(store.OnChunk(second_chunks[2]), MissionAckStatus::kAccepted);
  EXPECT_EQ(store.upload()->mission_id, 2);
  EXPECT_EQ(store.upload()->chunks_received, 1U);
  EXPECT_TRUE(store.IsComplete(1));

  for (const MissionChunk& chunk : third_chunks) store.OnChunk(chunk);
  EXPECT_TRUE(store.IsComplete(3));
  EXPECT_FALSE(store.IsComplete(1));
  EXPECT_EQ(store.complete()->waypoints, third);
}

// --- over the radio: server -> lossy shared channel -> vehicle endpoint -> MissionStore

class MissionHandler final : public radio::VehicleRequestHandler {
 public:
  explicit MissionHandler(MissionStore& store) : store_(store) {}
  radio::CommandResult OnCommand(const radio::Command& /*command*/) override {
    return radio::CommandResult::kUnsupported;
  }
  MissionAckStatus OnMissionChunk(const MissionChunk& chunk) override {
    return store_.OnChunk(chunk);
  }
  radio::ParamValue OnParamRead(const radio::ParamRead& /*read*/) override {
    return {{}, 0, 0.0F, radio::ParamStatus::kUnknownParam};
  }
  radio::ParamValue OnParamWrite(const radio::ParamWrite& /*write*/) override {
    return {{}, 0, 0.0F, radio::ParamStatus::kUnknownParam};
  }

 private:
  MissionStore& store_;
};

// Half of the wire's fixed-point steps (messages.hpp), plus double rounding room.
constexpr double kLatLonToleranceDeg = 0.51e-7;
constexpr double kAltitudeToleranceM = 0.051;
constexpr double kSpeedToleranceMps = 0.051;

struct Upload {
  std::vector<radio::RequestFinished> finished;
  radio::SchedulerStats stats;
};

Upload UploadOverLossyRadio(MissionStore& store, const std::vector<Waypoint>& waypoints,
                            double loss, int max_retries) {
  MissionHandler handler(store);
  std::vector<radio::VehicleRequestHandler*> handlers{&handler};
  radio::SchedulerConfig config = radio::sim_test::ServerConfig(radio::LinkMode::kSlots);
  config.max_retries = max_retries;
  radio::sim_test::SimNet net(config, 1, loss, handlers);
  net.server().AddVehicle(1);
  const std::vector<MissionChunk> chunks = radio::SplitMission(11, waypoints);
  for (const MissionChunk& chunk : chunks) net.server().SendMissionChunk(1, chunk);
  net.RunUntil(std::chrono::seconds(60));
  Upload upload;
  upload.finished = net.EventsOf<radio::RequestFinished>();
  upload.stats = net.server().stats();
  EXPECT_EQ(upload.finished.size(), chunks.size());
  return upload;
}

TEST(MissionStoreOverRadio, RetriesCompleteAnUploadDespiteLostChunks) {
  const std::vector<Waypoint> sent = MakeWaypoints(100);
  MissionStore store;
  const Upload upload = UploadOverLossyRadio(store, sent, /*loss=*/0.3, /*max_retries=*/10);
  EXPECT_GT(upload.stats.retries, 0U);  // the loss did bite
  for (const auto& f : upload.finished) EXPECT_EQ(f.status, radio::RequestStatus::kCompleted);
  const auto& last_ack = std::get<radio::MissionAck>(upload.finished.back().ack.value());
  EXPECT_EQ(last_ack.status, MissionAckStatus::kComplete);
  ASSERT_TRUE(store.IsComplete(11));
  const std::vector<Waypoint>& stored = store.complete()->waypoints;
  ASSERT_EQ(stored.size(), sent.size());
  for (std::size_t i = 0; i < sent.size(); ++i) {
    EXPECT_NEAR(stored[i].lat_deg, sent[i].lat_deg, kLatLonToleranceDeg) << i;
    EXPECT_NEAR(stored[i].lon_deg, sent[i].lon_deg, kLatLonToleranceDeg) << i;
    EXPECT_NEAR(stored[i].altitude_m, sent[i].altitude_m, kAltitudeToleranceM) << i;
    EXPECT_NEAR(stored[i].speed_mps, sent[i].speed_mps, kSpeedToleranceMps) << i;
    EXPECT_EQ(stored[i].flags, sent[i].flags) << i;
  }
}

TEST(MissionStoreOverRadio, ChunkFailingAfterMaxRetriesLeavesTheMissionIncomplete) {
  MissionStore store;
  const Upload upload = UploadOverLossyRadio(store, MakeWaypoints(100), /*loss=*/0.9,
                                             /*max_retries=*/2);
  const auto failed =
      std::count_if(upload.finished.begin(), upload.finished.end(),
                    [](const auto& f) { return f.status == radio::RequestStatus::kFailed; });
  EXPECT_GT(failed, 0);
  EXPECT_FALSE(store.IsComplete(11));
  EXPECT_EQ(store.complete(), nullptr);
}

}  // namespace
}  // namespace fireswarm::agents
