// Alerts raised by transitions between consecutive LCM messages.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "command_center_messages.hpp"
#include "fireswarm/server/command_center.hpp"

namespace fireswarm::server {
namespace {

using test::Flying;
using test::Track;
using test::Tracks;
using ::testing::ElementsAre;

std::vector<std::string> Kinds(const CommandCenter& center) {
  std::vector<std::string> kinds;
  const nlohmann::json state = center.State();
  for (const nlohmann::json& alert : state["alerts"]) {
    kinds.push_back(alert["kind"].get<std::string>());
  }
  return kinds;
}

TEST(CommandCenterAlerts, LinkDegradedThenLostOnceEach) {
  CommandCenter center({});
  vehicle_state_t m = Flying(3, {0.0, 0.0}, 50.0, 1'000'000);
  center.OnVehicleState(m);
  EXPECT_TRUE(Kinds(center).empty());
  m.link_state = vehicle_state_t::LINK_DEGRADED;
  m.utime = 95'000'000;
  center.OnVehicleState(m);
  center.OnVehicleState(m);  // still degraded: nothing new
  m.link_state = vehicle_state_t::LINK_LOST;
  center.OnVehicleState(m);
  center.OnVehicleState(m);
  m.link_state = vehicle_state_t::LINK_DEGRADED;  // recovering: no news
  center.OnVehicleState(m);
  EXPECT_THAT(Kinds(center), ElementsAre("link_degraded", "link_lost"));
  const nlohmann::json first = center.State()["alerts"][0];
  EXPECT_EQ(first["id"], 1);
  EXPECT_DOUBLE_EQ(first["time_s"].get<double>(), 95.0);
  EXPECT_EQ(first["level"], "warning");
  EXPECT_EQ(first["vehicle"], 3);
  EXPECT_EQ(first["track"], 0);
  EXPECT_EQ(first["text"], "drone 3: link degraded");
  EXPECT_EQ(center.State()["alerts"][1]["level"], "critical");
}

TEST(CommandCenterAlerts, BatteryLowFromTheFlagOrAReturnOnALowBattery) {
  CommandCenter center({});
  vehicle_state_t m = Flying(2, {0.0, 0.0}, 50.0, 1);
  center.OnVehicleState(m);
  m.flags |= vehicle_state_t::FLAG_LOW_BATTERY;
  m.battery_percent = 18.0;
  center.OnVehicleState(m);
  center.OnVehicleState(m);
  EXPECT_THAT(Kinds(center), ElementsAre("battery_low"));
  EXPECT_EQ(center.State()["alerts"][0]["text"], "drone 2: battery low (18 %)");

  // Another drone whose flag was lost on the way: it turned home with 15 % left.
  vehicle_state_t other = Flying(5, {100.0, 0.0}, 50.0, 2);
  other.battery_percent = 15.0;
  center.OnVehicleState(other);
  EXPECT_EQ(Kinds(center).size(), 1U) << "15 % while searching is the server's business";
  other.flight_mode = vehicle_state_t::MODE_RETURN_TO_LAUNCH;
  center.OnVehicleState(other);
  EXPECT_THAT(Kinds(center), ElementsAre("battery_low", "battery_low"));
}

TEST(CommandCenterAlerts, VehicleGivenUpOnce) {
  CommandCenter center({});
  vehicle_state_t m = Flying(9, {0.0, 0.0}, 50.0, 1);
  center.OnVehicleState(m);
  m.task = vehicle_state_t::TASK_GIVEN_UP;
  center.OnVehicleState(m);
  center.OnVehicleState(m);
  EXPECT_THAT(Kinds(center), ElementsAre("vehicle_given_up"));
  EXPECT_EQ(center.State()["alerts"][0]["vehicle"], 9);
}

TEST(CommandCenterAlerts, NewFireOnceAndConfirmedOnce) {
  CommandCenter center({});
  center.OnFireTracks(Tracks(50'000'000, {Track(2, fire_track_t::STATUS_TENTATIVE, {1})}));
  center.OnFireTracks(Tracks(51'000'000, {Track(2, fire_track_t::STATUS_TENTATIVE, {1})}));
  center.OnFireTracks(Tracks(52'000'000, {Track(2, fire_track_t::STATUS_CONFIRMED, {1, 4})}));
  center.OnFireTracks(Tracks(53'000'000, {Track(2, fire_track_t::STATUS_CONFIRMED, {1, 4}),
                                          Track(3, fire_track_t::STATUS_REJECTED, {4})}));
  EXPECT_THAT(Kinds(center), ElementsAre("new_fire", "fire_confirmed"));
  const nlohmann::json alerts = center.State()["alerts"];
  EXPECT_EQ(alerts[0]["track"], 2);
  EXPECT_EQ(alerts[0]["vehicle"], 1);
  EXPECT_DOUBLE_EQ(alerts[0]["time_s"].get<double>(), 50.0);
  EXPECT_EQ(alerts[1]["track"], 2);
  EXPECT_EQ(alerts[1]["level"], "critical");
}

TEST(CommandCenterAlerts, SeparationOncePerPairUntilTheyPart) {
  CommandCenterConfig config;
  config.separation_m = 15.0;
  CommandCenter center(config);
  center.OnVehicleState(Flying(1, {0.0, 0.0}, 50.0, 1));
  center.OnVehicleState(Flying(2, {40.0, 0.0}, 50.0, 1));
  EXPECT_TRUE(Kinds(center).empty());
  // 10 m apart horizontally, 50 m vs 45 m up: 11.2 m in 3-D.
  center.OnVehicleState(Flying(2, {10.0, 0.0}, 45.0, 2));
  EXPECT_THAT(Kinds(center), ElementsAre("separation"));
  EXPECT_EQ(center.State()["alerts"][0]["text"], "drones 1 and 2: 11.2 m apart");
  center.OnVehicleState(Flying(2, {12.0, 0.0}, 50.0, 3));
  center.OnVehicleState(Flying(2, {20.0, 0.0}, 50.0, 4));  // under 1.5 x 15 m: not parted
  center.OnVehicleState(Flying(2, {5.0, 0.0}, 50.0, 5));
  EXPECT_EQ(Kinds(center).size(), 1U);
  center.OnVehicleState(Flying(2, {30.0, 0.0}, 50.0, 6));  // parted
  center.OnVehicleState(Flying(2, {5.0, 0.0}, 50.0, 7));
  EXPECT_EQ(Kinds(center).size(), 2U);
  // Vertically apart by more than the separation: no alert.
  center.OnVehicleState(Flying(3, {100.0, 0.0}, 30.0, 8));
  center.OnVehicleState(Flying(4, {100.0, 0.0}, 60.0, 8));
  EXPECT_EQ(Kinds(center).size(), 2U);
}

TEST(CommandCenterAlerts, NoSeparationAlertOnTheGround) {
  CommandCenter center({});
  vehicle_state_t a = Flying(1, {0.0, 0.0}, 0.0, 1);
  vehicle_state_t b = Flying(2, {4.0, 0.0}, 0.0, 1);
  a.flight_mode = b.flight_mode = vehicle_state_t::MODE_IDLE;
  center.OnVehicleState(a);
  center.OnVehicleState(b);
  // Lifting off side by side at 1 m: still below the airborne altitude.
  a.flight_mode = b.flight_mode = vehicle_state_t::MODE_TAKEOFF;
  a.altitude_m = b.altitude_m = 1.0;
  center.OnVehicleState(a);
  center.OnVehicleState(b);
  EXPECT_TRUE(Kinds(center).empty());
}

TEST(CommandCenterAlerts, AlertsAreBoundedNewestKept) {
  CommandCenterConfig config;
  config.alerts_kept = 3;
  CommandCenter center(config);
  for (int id = 1; id <= 5; ++id) {
    vehicle_state_t m = Flying(id, {100.0 * id, 0.0}, 50.0, 1);
    m.link_state = vehicle_state_t::LINK_LOST;
    center.OnVehicleState(m);
  }
  const nlohmann::json alerts = center.State()["alerts"];
  ASSERT_EQ(alerts.size(), 3U);
  EXPECT_EQ(alerts[0]["id"], 3);
  EXPECT_EQ(alerts[2]["id"], 5);
  const std::optional<nlohmann::json> delta = center.TakeDelta();
  ASSERT_TRUE(delta);
  EXPECT_EQ((*delta)["alerts"].size(), 3U) << "a delta carries only the alerts still kept";
}

// Two radio channels, the second turning silent then heard again (issue 21).
radio_stats_t TwoChannels(std::int64_t utime, bool second_silent) {
  radio_stats_t m{};
  m.utime = utime;
  m.vehicle_ids = {1, 2};
  m.telemetry_age_s = {0.5, 12.0};
  m.vehicle_count = 2;
  m.auth_failures = {0, 0};
  m.replays = {0, 0};
  m.vehicle_channel = {0, 1};
  m.channel_count = 2;
  m.channel_busy_fraction = {0.5, 0.2};
  m.channel_payload_bytes_per_s = {900.0, 0.0};
  m.channel_frames_sent = {100, 80};
  m.channel_frames_received = {90, 10};
  m.channel_retries = {0, 4};
  m.channel_timeouts = {0, 30};
  m.channel_vehicles = {1, 1};
  m.channel_silent = {false, second_silent};
  return m;
}

TEST(CommandCenterAlerts, AChannelTurningSilentAndHeardAgain) {
  CommandCenter center({});
  center.OnRadioStats(TwoChannels(1'000'000, false));
  center.OnRadioStats(TwoChannels(3'000'000, true));
  center.OnRadioStats(TwoChannels(5'000'000, true));  // still silent: nothing new
  center.OnRadioStats(TwoChannels(7'000'000, false));
  EXPECT_THAT(Kinds(center), ElementsAre("channel_silent", "channel_heard"));
  const nlohmann::json state = center.State();
  EXPECT_EQ(state["alerts"][0]["level"], "critical");
  EXPECT_DOUBLE_EQ(state["alerts"][0]["time_s"].get<double>(), 3.0);
  EXPECT_EQ(state["alerts"][0]["text"],
            "radio channel 1: silent, none of its 1 vehicles answers (modem or link down?)");
  const nlohmann::json& channels = state["radio"]["channels"];
  ASSERT_EQ(channels.size(), 2U);
  EXPECT_EQ(channels[1]["vehicles"], nlohmann::json::array({2}));
  EXPECT_EQ(channels[1]["retries"], 4);
  EXPECT_EQ(channels[0]["silent"], false);
}

}  // namespace
}  // namespace fireswarm::server
