// The WebSocket deltas: only what changed since the last one; trails bounded.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <optional>
#include <string>

#include "command_center_messages.hpp"
#include "fireswarm/server/command_center.hpp"

namespace fireswarm::server {
namespace {

using test::Flying;
using test::Track;
using test::Tracks;

TEST(CommandCenterDelta, NothingChangedGivesNoDelta) {
  CommandCenter center({});
  EXPECT_FALSE(center.TakeDelta());
  const vehicle_state_t m = Flying(1, {0.0, 0.0}, 50.0, 1'000'000);
  center.OnVehicleState(m);
  ASSERT_TRUE(center.TakeDelta());
  center.OnVehicleState(m);  // the same message again
  EXPECT_FALSE(center.TakeDelta());
}

// States go out at the web rate, telemetry comes at 1-2 Hz: a state that only
// repeats the telemetry before, older, changes no row (the page ages heard_s
// against time_s itself); the next telemetry does.
TEST(CommandCenterDelta, ARepeatedTelemetrySampleChangesNoRow) {
  CommandCenter center({});
  vehicle_state_t m = Flying(1, {0.0, 0.0}, 50.0, 1'000'000);
  center.OnVehicleState(m);
  ASSERT_TRUE(center.TakeDelta());
  m.utime += 200'000;
  m.telemetry_age_s += 0.2;
  center.OnVehicleState(m);
  const std::optional<nlohmann::json> later = center.TakeDelta();
  ASSERT_TRUE(later) << "the time moved on";
  EXPECT_DOUBLE_EQ((*later)["time_s"].get<double>(), 1.2);
  EXPECT_FALSE(later->contains("vehicles"));
  EXPECT_DOUBLE_EQ(center.State()["vehicles"][0]["heard_s"].get<double>(), 0.8);

  m.utime += 300'000;
  m.telemetry_age_s = 0.1;  // a new sample, heard at 1.4 s
  center.OnVehicleState(m);
  const std::optional<nlohmann::json> heard = center.TakeDelta();
  ASSERT_TRUE(heard);
  ASSERT_EQ((*heard)["vehicles"].size(), 1U);
  EXPECT_DOUBLE_EQ((*heard)["vehicles"][0]["heard_s"].get<double>(), 1.4);
}

// A row in a delta carries the fields that changed since the last delta's row,
// which the page merges into the row it has: applied to the state before, the
// delta gives the state after.
TEST(CommandCenterDelta, ARowCarriesOnlyItsChangedFieldsAndMergesIntoTheWholeRow) {
  CommandCenter center({});
  vehicle_state_t m = Flying(4, {0.0, 0.0}, 50.0, 1'000'000);
  center.OnVehicleState(m);
  const std::optional<nlohmann::json> first = center.TakeDelta();
  ASSERT_TRUE(first);
  nlohmann::json row = center.State()["vehicles"][0];
  EXPECT_EQ((*first)["vehicles"][0], row) << "a new vehicle's row is whole";

  m.utime = 2'000'000;
  m.vehicle_time_ms = 2'000;
  m.battery_percent = 79.0;  // and a new heard_s
  center.OnVehicleState(m);
  std::optional<nlohmann::json> delta = center.TakeDelta();
  ASSERT_TRUE(delta);
  nlohmann::json changed = (*delta)["vehicles"][0];
  EXPECT_EQ(changed, nlohmann::json({{"id", 4}, {"battery_percent", 79.0}, {"heard_s", 1.8}}));
  row.merge_patch(changed);
  EXPECT_EQ(row, center.State()["vehicles"][0]);

  // Task fields go together; a move brings the position and its trail point.
  m.utime = 3'000'000;
  m.telemetry_age_s = 1.2;  // no new telemetry: heard_s stays
  m.lane_index = 2;
  m.lat_deg += 0.001;
  center.OnVehicleState(m);
  delta = center.TakeDelta();
  ASSERT_TRUE(delta);
  changed = (*delta)["vehicles"][0];
  EXPECT_EQ(changed["task_text"], "lane 2 of 3");
  EXPECT_EQ(changed["task"], "lane");
  EXPECT_TRUE(changed.contains("track_id"));
  EXPECT_EQ(changed["trail"].size(), 1U);
  EXPECT_FALSE(changed.contains("heard_s"));
  EXPECT_FALSE(changed.contains("battery_percent"));
  changed.erase("trail");
  row.merge_patch(changed);
  nlohmann::json after = center.State()["vehicles"][0];
  EXPECT_EQ(after["trail"].size(), 2U);
  after.erase("trail");
  row.erase("trail");
  EXPECT_EQ(row, after);
}

TEST(CommandCenterDelta, CarriesOnlyTheChangedRowsAndTheNewTrailPoints) {
  CommandCenter center({});
  center.OnVehicleState(Flying(1, {0.0, 0.0}, 50.0, 1'000'000));
  center.OnVehicleState(Flying(2, {100.0, 0.0}, 50.0, 1'000'000));
  center.OnFireTracks(Tracks(1'000'000, {Track(2, fire_track_t::STATUS_TENTATIVE, {1}),
                                         Track(3, fire_track_t::STATUS_TENTATIVE, {2})}));
  mission_status_t mission{};
  mission.utime = 1'000'000;
  mission.state = mission_status_t::STATE_RUNNING;
  center.OnMissionStatus(mission);
  const std::optional<nlohmann::json> first = center.TakeDelta();
  ASSERT_TRUE(first);
  EXPECT_EQ((*first)["type"], "delta");
  EXPECT_EQ((*first)["vehicles"].size(), 2U);
  EXPECT_EQ((*first)["tracks"].size(), 2U);
  EXPECT_EQ((*first)["alerts"].size(), 2U);  // two new fires
  EXPECT_EQ((*first)["mission"]["state"], "running");

  // Drone 2 moves 10 m, drone 1 says the same; track 3 is confirmed; mission unchanged.
  center.OnVehicleState(Flying(1, {0.0, 0.0}, 50.0, 1'000'000));
  center.OnVehicleState(Flying(2, {110.0, 0.0}, 50.0, 2'000'000));
  center.OnFireTracks(Tracks(2'000'000, {Track(2, fire_track_t::STATUS_TENTATIVE, {1}),
                                         Track(3, fire_track_t::STATUS_CONFIRMED, {2})}));
  mission.utime = 2'000'000;
  center.OnMissionStatus(mission);
  const std::optional<nlohmann::json> second = center.TakeDelta();
  ASSERT_TRUE(second);
  EXPECT_DOUBLE_EQ((*second)["time_s"].get<double>(), 2.0);
  ASSERT_EQ((*second)["vehicles"].size(), 1U);
  const nlohmann::json& row = (*second)["vehicles"][0];
  EXPECT_EQ(row["id"], 2);
  ASSERT_EQ(row["trail"].size(), 1U) << "only the point since the last delta";
  EXPECT_EQ(row["trail"][0], row["position"]);
  ASSERT_EQ((*second)["tracks"].size(), 1U);
  EXPECT_EQ((*second)["tracks"][0]["id"], 3);
  EXPECT_EQ((*second)["alerts"].size(), 1U);
  EXPECT_EQ((*second)["alerts"][0]["kind"], "fire_confirmed");
  EXPECT_FALSE(second->contains("mission"));
  EXPECT_FALSE(second->contains("radio"));
  EXPECT_FALSE(second->contains("commands"));
  // The snapshot still has the whole trail.
  EXPECT_EQ(center.State()["vehicles"][1]["trail"].size(), 2U);

  // Track 2 is gone from the server's list.
  center.OnFireTracks(Tracks(3'000'000, {Track(3, fire_track_t::STATUS_CONFIRMED, {2})}));
  const std::optional<nlohmann::json> third = center.TakeDelta();
  ASSERT_TRUE(third);
  EXPECT_EQ((*third)["removed_tracks"], nlohmann::json({2}));
  EXPECT_FALSE(third->contains("tracks"));
  EXPECT_EQ(center.State()["tracks"].size(), 1U);
}

TEST(CommandCenterDelta, TrailIsBoundedAndSkipsJitter) {
  CommandCenterConfig config;
  config.trail_points = 5;
  CommandCenter center(config);
  center.OnVehicleState(Flying(1, {0.0, 0.0}, 50.0, 1));
  center.OnVehicleState(Flying(1, {1.0, 1.0}, 50.0, 2));  // 1.4 m: jitter
  EXPECT_EQ(center.State()["vehicles"][0]["trail"].size(), 1U);
  for (int i = 1; i <= 10; ++i) {
    center.OnVehicleState(Flying(1, {10.0 * i, 0.0}, 50.0, 2 + i));
  }
  const nlohmann::json v = center.State()["vehicles"][0];
  ASSERT_EQ(v["trail"].size(), 5U);
  EXPECT_EQ(v["trail"][4], v["position"]) << "newest last";
  const std::optional<nlohmann::json> delta = center.TakeDelta();
  ASSERT_TRUE(delta);
  EXPECT_EQ((*delta)["vehicles"][0]["trail"].size(), 5U) << "never more than is kept";
}

TEST(CommandCenterDelta, CommandsAndRadioWhenChanged) {
  CommandCenter center({});
  command_status_t status;
  status.utime = 1;
  status.command_id = 1;
  status.command = operator_command_t::HOLD;
  status.target_ids = {3};
  status.target_states = {command_status_t::STATE_QUEUED};
  status.target_count = 1;
  center.OnCommandStatus(status);
  radio_stats_t radio{};
  radio.utime = 1;
  center.OnRadioStats(radio);
  std::optional<nlohmann::json> delta = center.TakeDelta();
  ASSERT_TRUE(delta);
  EXPECT_EQ((*delta)["commands"][0]["state"], "queued");
  EXPECT_TRUE(delta->contains("radio"));
  center.OnCommandStatus(status);
  center.OnRadioStats(radio);
  EXPECT_FALSE(center.TakeDelta());
  status.target_states = {command_status_t::STATE_SENT};
  center.OnCommandStatus(status);
  delta = center.TakeDelta();
  ASSERT_TRUE(delta);
  EXPECT_EQ((*delta)["commands"][0]["state"], "sent");
  EXPECT_FALSE(delta->contains("radio"));
}

}  // namespace
}  // namespace fireswarm::server
