#include "fireswarm/server/command_center.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "command_center_messages.hpp"
#include "command_center_rows.hpp"

namespace fireswarm::server {
namespace {

using test::Flying;
using test::kOrigin;
using test::NeverHeard;
using test::Track;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

std::string ValidateMessage(CommandCenterConfig config) {
  try {
    config.Validate();
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

TEST(CommandCenterConfig, ValidateNamesTheBadField) {
  EXPECT_EQ(ValidateMessage({}), "");
  CommandCenterConfig config;
  config.source = "tape";
  EXPECT_THAT(ValidateMessage(config), HasSubstr("source"));
  config = {};
  config.trail_points = 0;
  EXPECT_THAT(ValidateMessage(config), HasSubstr("trail_points"));
  config = {};
  config.alerts_kept = 0;
  EXPECT_THAT(ValidateMessage(config), HasSubstr("alerts_kept"));
  config = {};
  config.commands_kept = 0;
  EXPECT_THAT(ValidateMessage(config), HasSubstr("commands_kept"));
  config = {};
  config.separation_m = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT(ValidateMessage(config), HasSubstr("separation_m"));
  config.separation_m = 0.0;
  EXPECT_THAT(ValidateMessage(config), HasSubstr("separation_m"));
  EXPECT_THROW(CommandCenter{config}, std::invalid_argument);
}

TEST(CommandCenter, StateBeforeAnyMessageSaysNothingIsKnown) {
  CommandCenterConfig config;
  config.source = "replay";
  config.read_only = true;
  const CommandCenter center(config);
  const nlohmann::json state = center.State();
  EXPECT_EQ(state["source"], "replay");
  EXPECT_EQ(state["read_only"], true);
  EXPECT_TRUE(state["time_s"].is_null());
  EXPECT_TRUE(state["mission"].is_null());
  EXPECT_TRUE(state["radio"].is_null());
  EXPECT_EQ(state["vehicles"], nlohmann::json::array());
  EXPECT_EQ(state["tracks"], nlohmann::json::array());
  EXPECT_EQ(state["alerts"], nlohmann::json::array());
  EXPECT_EQ(state["commands"], nlohmann::json::array());
  EXPECT_EQ(state["refused"], 0);
  EXPECT_EQ(state["plan"], (nlohmann::json{{"mission_id", 0}, {"version", 0}}));
  EXPECT_EQ(center.Plan()["type"], "FeatureCollection");
  EXPECT_EQ(center.Plan()["features"], nlohmann::json::array());
  EXPECT_EQ(center.Coverage()["rows"], 0);
}

TEST(CommandCenter, VehicleRowCarriesTheTelemetryInEngineeringNames) {
  CommandCenter center({});
  vehicle_state_t m = Flying(3, {100.0, 200.0}, 60.0, 5'000'000);
  m.velocity_north_mps = 3.0;
  m.velocity_east_mps = 4.0;
  m.heading_deg = 53.0;
  m.battery_percent = 71.0;
  m.telemetry_age_s = 0.4;
  m.telemetry_hz = 1.0;
  m.progress_fraction = 0.35;
  m.task = vehicle_state_t::TASK_LANE;
  m.lane_index = 4;
  m.lane_count = 12;
  center.OnVehicleState(m);
  const nlohmann::json state = center.State();
  EXPECT_DOUBLE_EQ(state["time_s"].get<double>(), 5.0);
  ASSERT_EQ(state["vehicles"].size(), 1U);
  const nlohmann::json& v = state["vehicles"][0];
  EXPECT_EQ(v["id"], 3);
  EXPECT_EQ(v["colour"], internal::VehicleColour(3));
  EXPECT_EQ(v["mode"], "search");
  EXPECT_DOUBLE_EQ(v["position"][0].get<double>(), m.lat_deg);
  EXPECT_DOUBLE_EQ(v["position"][1].get<double>(), m.lon_deg);
  EXPECT_DOUBLE_EQ(v["altitude_m"].get<double>(), 60.0);
  EXPECT_DOUBLE_EQ(v["speed_mps"].get<double>(), 5.0);
  EXPECT_DOUBLE_EQ(v["heading_deg"].get<double>(), 53.0);
  EXPECT_DOUBLE_EQ(v["battery_percent"].get<double>(), 71.0);
  EXPECT_EQ(v["link"], "ok");
  EXPECT_DOUBLE_EQ(v["heard_s"].get<double>(), 4.6) << "5 s, telemetry 0.4 s old";
  EXPECT_DOUBLE_EQ(v["telemetry_hz"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(v["progress"].get<double>(), 0.35);
  EXPECT_EQ(v["task"], "lane");
  EXPECT_EQ(v["task_text"], "lane 4 of 12");
  EXPECT_EQ(v["track_id"], 0);
  EXPECT_EQ(v["trail"].size(), 1U);
}

TEST(CommandCenter, PositionIsNullBeforeTelemetryAndWithoutAFix) {
  CommandCenter center({});
  center.OnVehicleState(NeverHeard(4, 1'000'000));
  nlohmann::json v = center.State()["vehicles"][0];
  EXPECT_TRUE(v["position"].is_null());
  EXPECT_TRUE(v["altitude_m"].is_null());
  EXPECT_TRUE(v["heard_s"].is_null());
  EXPECT_TRUE(v["mode"].is_null());
  EXPECT_EQ(v["link"], "never");
  EXPECT_EQ(v["trail"], nlohmann::json::array());

  // Heard, but without a GPS fix: the vehicle sends 0, 0, the server NaN; never drawn.
  vehicle_state_t no_fix = Flying(4, {0.0, 0.0}, 0.0, 2'000'000);
  no_fix.has_position = false;
  no_fix.lat_deg = std::numeric_limits<double>::quiet_NaN();
  no_fix.lon_deg = std::numeric_limits<double>::quiet_NaN();
  center.OnVehicleState(no_fix);
  v = center.State()["vehicles"][0];
  EXPECT_TRUE(v["position"].is_null());
  EXPECT_DOUBLE_EQ(v["altitude_m"].get<double>(), 0.0);
  EXPECT_EQ(v["trail"], nlohmann::json::array());
  // The state dumps as JSON (no NaN in it).
  EXPECT_THAT(center.State().dump(), ::testing::Not(HasSubstr("NaN")));
}

TEST(CommandCenter, VehiclesAreSortedByReceiverIdWithStableColours) {
  CommandCenter center({});
  for (const int id : {7, 2, 5}) center.OnVehicleState(Flying(id, {10.0 * id, 0.0}, 50.0, 1));
  std::vector<int> ids;
  const nlohmann::json state = center.State();
  for (const nlohmann::json& v : state["vehicles"]) ids.push_back(v["id"].get<int>());
  EXPECT_THAT(ids, ElementsAre(2, 5, 7));
  std::set<std::string> colours;
  for (int id = 1; id <= 12; ++id) colours.insert(std::string(internal::VehicleColour(id)));
  EXPECT_EQ(colours.size(), 12U) << "twelve neighbouring IDs get twelve colours";
  EXPECT_EQ(internal::VehicleColour(13), internal::VehicleColour(1));
  EXPECT_FALSE(colours.contains("#d62728")) << "red is the fires'";
}

TEST(CommandCenterRows, TaskTextSaysWhatTheDroneDoes) {
  vehicle_state_t m = Flying(1, {0.0, 0.0}, 50.0, 1);
  m.task = vehicle_state_t::TASK_INVESTIGATING;
  m.task_track_id = 2;
  EXPECT_EQ(internal::TaskText(internal::FieldsOf(m)), "investigating fire 2");
  m.task_track_id = 0;
  EXPECT_EQ(internal::TaskText(internal::FieldsOf(m)), "investigating a point");
  m.task = vehicle_state_t::TASK_RETURNING;
  EXPECT_EQ(internal::TaskText(internal::FieldsOf(m)), "returning");
  m.task = vehicle_state_t::TASK_GIVEN_UP;
  EXPECT_EQ(internal::TaskName(m.task), "given_up");
  m.task = vehicle_state_t::TASK_HOLDING;
  EXPECT_EQ(internal::TaskText(internal::FieldsOf(m)), "holding");
  m.task = 42;
  EXPECT_EQ(internal::TaskName(m.task), "unknown");
}

struct EllipseCase {
  double nn, ne, ee;
  double major_m, minor_m, bearing_deg;
};

TEST(CommandCenterRows, EllipseIsTheTwoSigmaEllipseWithItsBearingFromNorth) {
  // Index 0 = north, 1 = east (fire_track_t.covariance_m2).
  const EllipseCase cases[] = {
      {4.0, 0.0, 1.0, 4.0, 2.0, 0.0},     // long north-south
      {1.0, 0.0, 9.0, 6.0, 2.0, 90.0},    // long east-west
      {2.5, 1.5, 2.5, 4.0, 2.0, 45.0},    // eigenvalues 4 and 1, north-east axis
      {2.5, -1.5, 2.5, 4.0, 2.0, 135.0},  // north-west / south-east axis
  };
  for (const EllipseCase& c : cases) {
    const double covariance[2][2] = {{c.nn, c.ne}, {c.ne, c.ee}};
    const nlohmann::json e = internal::Ellipse2Sigma(covariance);
    EXPECT_NEAR(e["semi_major_m"].get<double>(), c.major_m, 1e-9) << c.bearing_deg;
    EXPECT_NEAR(e["semi_minor_m"].get<double>(), c.minor_m, 1e-9) << c.bearing_deg;
    EXPECT_NEAR(e["bearing_deg"].get<double>(), c.bearing_deg, 1e-9);
  }
  const double bad[2][2] = {{std::nan(""), 0.0}, {0.0, 1.0}};
  EXPECT_TRUE(internal::Ellipse2Sigma(bad).is_null());
}

TEST(CommandCenter, TrackRowsCarryTheFusion) {
  CommandCenter center({});
  fire_track_list_t list;
  list.utime = 50'000'000;
  list.tracks = {Track(2, fire_track_t::STATUS_TENTATIVE, {1, 4})};
  list.track_count = 1;
  center.OnFireTracks(list);
  const nlohmann::json track = center.State()["tracks"][0];
  EXPECT_EQ(track["id"], 2);
  EXPECT_EQ(track["status"], "tentative");
  EXPECT_EQ(track["drones"], nlohmann::json({1, 4}));
  EXPECT_EQ(track["reports"], 3);
  EXPECT_DOUBLE_EQ(track["first_seen_s"].get<double>(), 40.2);
  EXPECT_NEAR(track["ellipse"]["semi_major_m"].get<double>(), 4.0, 1e-9);
  EXPECT_DOUBLE_EQ(track["position"][0].get<double>(), kOrigin.lat_deg);
}

TEST(CommandCenter, CommandStateIsFailedIfAnyFailedElseTheLeastAdvanced) {
  CommandCenter center({});
  command_status_t status;
  status.utime = 90'000'000;
  status.command_id = 5;
  status.command = operator_command_t::RETURN_VEHICLE;
  status.issued_utime = 90'100'000;
  status.reason = "operator";
  status.target_ids = {3, 4};
  status.target_states = {command_status_t::STATE_ACKNOWLEDGED, command_status_t::STATE_SENT};
  status.target_count = 2;
  center.OnCommandStatus(status);
  nlohmann::json command = center.State()["commands"][0];
  EXPECT_EQ(command["id"], 5);
  EXPECT_EQ(command["kind"], "return");
  EXPECT_EQ(command["state"], "sent");
  EXPECT_DOUBLE_EQ(command["time_s"].get<double>(), 90.1);
  EXPECT_EQ(command["reason"], "operator");
  EXPECT_EQ(command["targets"][0], (nlohmann::json{{"vehicle", 3}, {"state", "acknowledged"}}));
  status.target_states = {command_status_t::STATE_FAILED, command_status_t::STATE_QUEUED};
  center.OnCommandStatus(status);
  EXPECT_EQ(center.State()["commands"][0]["state"], "failed");
  status.target_states = {command_status_t::STATE_ACKNOWLEDGED,
                          command_status_t::STATE_ACKNOWLEDGED};
  center.OnCommandStatus(status);
  EXPECT_EQ(center.State()["commands"][0]["state"], "acknowledged");
}

// A refused command's status (ID 0, why in `refusal`: a replayed log's) is no
// command to follow: it counts as refused.
TEST(CommandCenter, ARefusedCommandsStatusCountsAsRefused) {
  CommandCenter center({});
  command_status_t status{};
  status.command = operator_command_t::START;
  status.operator_id = "mallory";
  status.refusal = "bad_mac: the MAC does not match";
  center.OnCommandStatus(status);
  const nlohmann::json state = center.State();
  EXPECT_EQ(state["refused"], 1);
  EXPECT_TRUE(state["commands"].empty()) << state["commands"].dump();
}

TEST(CommandCenter, CommandsAreBoundedNewestKept) {
  CommandCenterConfig config;
  config.commands_kept = 2;
  CommandCenter center(config);
  for (int id = 1; id <= 4; ++id) {
    command_status_t status;
    status.command_id = id;
    status.command = operator_command_t::START;
    center.OnCommandStatus(status);
  }
  const nlohmann::json commands = center.State()["commands"];
  ASSERT_EQ(commands.size(), 2U);
  EXPECT_EQ(commands[0]["id"], 3);
  EXPECT_EQ(commands[1]["id"], 4);
  EXPECT_EQ(commands[0]["state"], "acknowledged") << "no targets: nothing left to send";
}

TEST(CommandCenter, MissionAndRadioAreCopiedWithNames) {
  CommandCenter center({});
  mission_status_t mission{};
  mission.utime = 1;
  mission.state = mission_status_t::STATE_RUNNING;
  mission.mission_id = 1;
  mission.coverage_fraction = 0.42;
  mission.elapsed_s = 80.0;
  mission.vehicles_active = 5;
  mission.fires_tentative = 1;
  center.OnMissionStatus(mission);
  radio_stats_t radio{};
  radio.utime = 2;
  radio.busy_fraction = 0.61;
  radio.payload_bytes_per_s = 2100.0;
  radio.retries = 4;
  radio.timeouts = 9;
  radio.vehicle_ids = {3};
  radio.telemetry_age_s = {0.4};
  radio.vehicle_count = 1;
  radio.auth_failures = {0};
  radio.replays = {0};
  center.OnRadioStats(radio);
  const nlohmann::json state = center.State();
  EXPECT_EQ(state["mission"]["state"], "running");
  EXPECT_DOUBLE_EQ(state["mission"]["coverage"].get<double>(), 0.42);
  EXPECT_EQ(state["mission"]["vehicles_active"], 5);
  EXPECT_EQ(state["mission"]["fires_tentative"], 1);
  EXPECT_DOUBLE_EQ(state["radio"]["busy_fraction"].get<double>(), 0.61);
  EXPECT_EQ(state["radio"]["retries"], 4);
  EXPECT_EQ(state["radio"]["timeouts"], 9);
  EXPECT_DOUBLE_EQ(state["radio"]["telemetry_age_s"]["3"].get<double>(), 0.4);
}

TEST(CommandCenter, RefusedCommandsAreCounted) {
  CommandCenter center({});
  center.TakeDelta();
  center.NoteRefused();
  center.NoteRefused();
  EXPECT_EQ(center.State()["refused"], 2);
  const std::optional<nlohmann::json> delta = center.TakeDelta();
  ASSERT_TRUE(delta);
  EXPECT_EQ((*delta)["refused"], 2);
}

}  // namespace
}  // namespace fireswarm::server
