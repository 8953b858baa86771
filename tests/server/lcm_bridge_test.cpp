// The LCM bridge through real LCM: conversions, the event log (read back with
// lcm::LogFile and replayed by the stock lcm-logplayer), CSV files, and operator
// commands and publications over udpm:// on loopback (skipped, saying why, on a
// machine without a multicast route). No sleeps: waiting is handleTimeout().
#include "fireswarm/server/lcm_bridge.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <random>
#include <string>

#include "common/scratch_dir.hpp"
#include "fireswarm/common/time.hpp"
#include "server/fake_fleet.hpp"
#include "server/server_fixture.hpp"

namespace fireswarm::server {
namespace {

using common::Nanos;
using testing::Air;

using testing::kFrame;
using testing::kSecond;

std::filesystem::path TempDir(const std::string& name) {
  static const test_support::ScratchDir scratch("lcm_bridge");
  const std::filesystem::path dir = scratch.path() / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// Two vehicles heard by a server, one of them with a fire track.
struct HeardFleet {
  HeardFleet() : air(0.0), server(ServerConfig{}, kFrame) {
    for (std::uint8_t id = 1; id <= 2; ++id) {
      air.Add(id);
      server.AddVehicle(id);
      radio::Telemetry t;
      const common::LatLon where = kFrame.ToGeodetic({100.0 * id, 50.0});
      t.lat_deg = where.lat_deg;
      t.lon_deg = where.lon_deg;
      t.altitude_m = 60.0;
      t.heading_deg = 90.0;
      t.mode = radio::FlightMode::kSearch;
      t.battery_percent = 77;
      t.time_ms = 5'000;
      // Vehicle 2 has its GPS fix; vehicle 1 not yet (it sends 0, 0 then).
      if (id == 2) t.flags = radio::telemetry_flags::kGpsFix;
      air.vehicle(id).endpoint().SetTelemetry(t);
    }
    radio::FireReport report;
    const common::LatLon fire = kFrame.ToGeodetic({120.0, 80.0});
    report.lat_deg = fire.lat_deg;
    report.lon_deg = fire.lon_deg;
    report.sigma_north_m = 2.0;
    report.sigma_east_m = 3.0;
    report.observer_lat_deg = fire.lat_deg;
    report.observer_lon_deg = fire.lon_deg;
    report.confidence = 0.8;
    report.time_ms = 5'000;  // the vehicle's clock, as in its telemetry
    air.vehicle(1).endpoint().QueueFireReport(report);
    air.RunUntil(server, 5 * kSecond);
  }
  Air air;
  Server server;
};

TEST(LcmMessages, VehicleStateCarriesTheTelemetryAndTheLink) {
  HeardFleet fleet;
  const double now_s = 5.0;
  const vehicle_state_t m = ToVehicleState(fleet.server, 2, now_s, 123);
  EXPECT_EQ(m.utime, 123);
  EXPECT_EQ(m.receiver_id, 2);
  EXPECT_TRUE(m.has_position);
  const common::EastNorth where = kFrame.ToLocal({m.lat_deg, m.lon_deg});
  EXPECT_NEAR(where.east_m, 200.0, 0.05);
  EXPECT_NEAR(where.north_m, 50.0, 0.05);
  EXPECT_DOUBLE_EQ(m.battery_percent, 77.0);
  EXPECT_EQ(m.flight_mode, vehicle_state_t::MODE_SEARCH);
  EXPECT_EQ(m.link_state, vehicle_state_t::LINK_OK);
  EXPECT_GE(m.telemetry_age_s, 0.0);
  EXPECT_LT(m.telemetry_age_s, 2.0);
}

// A vehicle registered but not heard yet has no position: the demo's log put
// twelve of them at 0, 0 (off the coast of Africa on any outside map).
TEST(LcmMessages, AVehicleNotHeardYetHasNoPosition) {
  Server server(ServerConfig{}, kFrame);
  server.AddVehicle(4);
  const vehicle_state_t m = ToVehicleState(server, 4, 0.0, 1);
  EXPECT_FALSE(m.has_position);
  EXPECT_TRUE(std::isnan(m.lat_deg));
  EXPECT_TRUE(std::isnan(m.lon_deg));
  EXPECT_TRUE(std::isnan(m.altitude_m));
  EXPECT_EQ(m.link_state, vehicle_state_t::LINK_NEVER_HEARD);
}

TEST(LcmMessages, AVehicleWithoutAGpsFixHasNoPositionButItsOtherTelemetry) {
  HeardFleet fleet;
  const vehicle_state_t m = ToVehicleState(fleet.server, 1, 5.0, 1);
  EXPECT_FALSE(m.has_position);
  EXPECT_TRUE(std::isnan(m.lat_deg));
  EXPECT_TRUE(std::isnan(m.lon_deg));
  EXPECT_DOUBLE_EQ(m.altitude_m, 60.0) << "the barometer needs no fix";
  EXPECT_DOUBLE_EQ(m.battery_percent, 77.0);
  EXPECT_EQ(m.link_state, vehicle_state_t::LINK_OK);
}

TEST(LcmMessages, TrackListAndMissionStatusCountTheTracks) {
  HeardFleet fleet;
  const fire_track_list_t list = ToFireTrackList(fleet.server, 9, 1'000'000);
  ASSERT_EQ(list.track_count, 1);
  const fire_track_t& track = list.tracks[0];
  EXPECT_EQ(track.status, fire_track_t::STATUS_TENTATIVE);
  const common::EastNorth where = kFrame.ToLocal({track.lat_deg, track.lon_deg});
  EXPECT_NEAR(where.east_m, 120.0, 0.05);
  EXPECT_NEAR(where.north_m, 80.0, 0.05);
  EXPECT_EQ(track.vehicle_count, 1);
  EXPECT_EQ(track.vehicle_ids.at(0), 1);
  EXPECT_GT(track.covariance_m2[1][1], track.covariance_m2[0][0]) << "east sigma 3 m > north 2 m";
  EXPECT_GE(track.first_seen_utime, 1'000'000);

  const mission_status_t status = ToMissionStatus(fleet.server, 5.0, 9);
  EXPECT_EQ(status.fires_tentative, 1);
  EXPECT_EQ(status.fires_confirmed, 0);
  EXPECT_EQ(status.vehicles_active, 2);
  EXPECT_EQ(status.state, mission_status_t::STATE_IDLE);
}

TEST(LcmMessages, OperatorCommandsOutOfRangeAreRefusedWithAReason) {
  operator_command_t m{};
  m.command = operator_command_t::RETASK_VEHICLE;
  m.target_vehicle = 3;
  m.lat_deg = 46.0;
  m.lon_deg = -74.5;
  m.radius_m = 40.0;
  std::string why;
  const std::optional<OperatorCommand> command = FromLcm(m, &why);
  ASSERT_TRUE(command.has_value()) << why;
  EXPECT_EQ(command->kind, OperatorCommand::Kind::kRetaskVehicle);
  EXPECT_EQ(command->vehicle, 3);
  m.command = 42;
  EXPECT_FALSE(FromLcm(m, &why).has_value());
  EXPECT_EQ(why, "unknown command 42");
  m.command = operator_command_t::START;
  m.target_vehicle = 300;
  EXPECT_FALSE(FromLcm(m, &why).has_value());
  EXPECT_NE(why.find("target_vehicle 300"), std::string::npos) << why;
}

// Publishes at 10 Hz steps for 10 s into a log and CSV files.
void PublishTenSeconds(const Server& server, LcmBridge& bridge) {
  for (int step = 0; step < 100; ++step) {
    const double t = 0.1 * step;
    bridge.Publish(server, t, std::llround(t * 1e6), 0);
  }
}

TEST(LcmBridge, WritesALogAndCsvFilesAtTheConfiguredRates) {
  HeardFleet fleet;
  const std::filesystem::path dir = TempDir("log");
  LcmBridgeConfig config;
  config.log_path = dir / "run.lcmlog";
  config.csv_dir = dir / "csv";
  config.rates.vehicle_state_hz = 2.0;
  config.rates.fire_tracks_hz = 1.0;
  config.rates.mission_status_hz = 0.0;  // off
  config.rates.radio_stats_hz = 0.5;
  {
    LcmBridge bridge(config);
    PublishTenSeconds(fleet.server, bridge);
  }
  std::map<std::string, int> events;
  lcm::LogFile log(config.log_path->string(), "r");
  ASSERT_TRUE(log.good());
  std::int64_t last_utime = -1;
  while (const lcm::LogEvent* event = log.readNextEvent()) {
    ++events[event->channel];
    EXPECT_GE(event->timestamp, last_utime);
    last_utime = event->timestamp;
    if (event->channel == kVehicleStateChannel) {
      vehicle_state_t m;
      ASSERT_EQ(m.decode(event->data, 0, event->datalen), event->datalen);
      EXPECT_TRUE(m.receiver_id == 1 || m.receiver_id == 2);
    }
  }
  EXPECT_EQ(events[kVehicleStateChannel], 2 * 20);  // 2 vehicles at 2 Hz for 10 s
  EXPECT_EQ(events[kFireTracksChannel], 10);
  EXPECT_EQ(events[kRadioStatsChannel], 5);
  EXPECT_EQ(events.count(kMissionStatusChannel), 0u);

  std::ifstream csv(*config.csv_dir / "fireswarm_vehicle_state.csv");
  ASSERT_TRUE(csv.good());
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line.rfind("utime,receiver_id,", 0), 0u) << line;
  int rows = 0;
  while (std::getline(csv, line)) ++rows;
  EXPECT_EQ(rows, 40);
  EXPECT_FALSE(std::filesystem::exists(*config.csv_dir / "fireswarm_mission_status.csv"));
}

TEST(LcmBridge, RefusesAnUnwritableLogNamingIt) {
  LcmBridgeConfig config;
  config.log_path = "/nonexistent-dir/run.lcmlog";
  try {
    LcmBridge bridge(config);
    FAIL() << "no error for an unwritable log";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent-dir/run.lcmlog"), std::string::npos);
  }
  config.log_path.reset();
  config.rates.fire_tracks_hz = -1.0;
  EXPECT_THROW(LcmBridge{config}, std::invalid_argument);
}

struct StatusInbox {
  void On(const lcm::ReceiveBuffer*, const std::string&, const command_status_t* m) {
    received.push_back(*m);
  }
  std::vector<command_status_t> received;
};

// command_status_t goes out when a command is accepted and whenever one of its
// targets changes state (not at a rate), and into the log and the CSV files.
TEST(LcmBridge, PublishesACommandsStatusWhenItChangesOverMemq) {
  testing::Fleet fleet;
  const std::filesystem::path dir = TempDir("status");
  LcmBridgeConfig config;
  config.url = "memq://";
  config.log_path = dir / "run.lcmlog";
  config.csv_dir = dir / "csv";
  config.rates = {0.0, 0.0, 0.0, 0.0};  // nothing at a rate
  std::vector<command_status_t> logged;
  {
    LcmBridge bridge(config);
    ASSERT_NE(bridge.lcm(), nullptr);
    StatusInbox inbox;
    bridge.lcm()->subscribe(kCommandStatusChannel, &StatusInbox::On, &inbox);
    const auto publish = [&] {
      const double t_s = common::ToSeconds(fleet.air.channel().now());
      bridge.Publish(fleet.server, t_s, std::llround(t_s * 1e6), 0);
      while (bridge.lcm()->handleTimeout(0) > 0) {
      }
    };
    publish();  // the start, accepted before the bridge was there
    ASSERT_EQ(inbox.received.size(), 1U);
    EXPECT_EQ(inbox.received[0].command, operator_command_t::START);
    EXPECT_EQ(inbox.received[0].target_states,
              std::vector<std::int8_t>(3, command_status_t::STATE_ACKNOWLEDGED));
    inbox.received.clear();

    std::int32_t id = 0;
    ASSERT_TRUE(fleet.server.Handle({OperatorCommand::Kind::kHold, 2, {}, 0.0, "smoke, \"east\""},
                                    fleet.air.channel().now(), nullptr, &id));
    publish();
    ASSERT_EQ(inbox.received.size(), 1U) << "published when accepted";
    publish();
    EXPECT_EQ(inbox.received.size(), 1U) << "unchanged: not again";
    fleet.air.Run(fleet.server, fleet.air.channel().now() + 10 * kSecond, [&] {
      publish();
      const command_status_t& last = inbox.received.back();
      return last.target_states.at(0) == command_status_t::STATE_ACKNOWLEDGED;
    });
    std::vector<int> states;
    for (const command_status_t& m : inbox.received) {
      EXPECT_EQ(m.command_id, id);
      EXPECT_EQ(m.command, operator_command_t::HOLD);
      ASSERT_EQ(m.target_count, 1);
      EXPECT_EQ(m.target_ids.at(0), 2);
      states.push_back(m.target_states.at(0));
    }
    EXPECT_EQ(states,
              (std::vector<int>{command_status_t::STATE_QUEUED, command_status_t::STATE_SENT,
                                command_status_t::STATE_ACKNOWLEDGED}));
  }
  lcm::LogFile log(config.log_path->string(), "r");
  ASSERT_TRUE(log.good());
  int in_log = 0;
  while (const lcm::LogEvent* event = log.readNextEvent()) {
    in_log += event->channel == kCommandStatusChannel;
  }
  EXPECT_EQ(in_log, 4) << "the start's and the hold's three";
  std::ifstream csv(*config.csv_dir / "fireswarm_command_status.csv");
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "utime,command_id,command,issued_utime,target_id,target_state,reason");
  std::vector<std::string> rows;
  while (std::getline(csv, line)) rows.push_back(line);
  ASSERT_FALSE(rows.empty());
  EXPECT_NE(rows.back().find(",2,2,\"smoke, \"\"east\"\"\""), std::string::npos) << rows.back();
}

// ---- udpm:// on loopback ---------------------------------------------------

constexpr const char* kNoMulticastRoute =
    "udpm:// needs a multicast route and this machine has none; as root run "
    "scripts/install-deps.sh (it adds 224.0.0.0/4 on lo)";

std::string LoopbackUrl() {
  std::random_device random;
  return "udpm://239.255.76.67:" + std::to_string(20'000 + random() % 40'000U) + "?ttl=0";
}

template <typename Done>
bool HandleUntil(lcm::LCM& lcm, Done&& done) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(3);
  while (!done()) {
    if (std::chrono::steady_clock::now() > deadline) return false;
    lcm.handleTimeout(100);
  }
  return true;
}

struct Inbox {
  void OnState(const lcm::ReceiveBuffer*, const std::string&, const vehicle_state_t*) { ++states; }
  int states = 0;
};

TEST(LcmBridge, PublishesAndTakesOperatorCommandsOverUdpm) {
  HeardFleet fleet;
  LcmBridgeConfig config;
  config.url = LoopbackUrl();
  lcm::LCM operator_console(config.url);
  if (!operator_console.good()) GTEST_SKIP() << kNoMulticastRoute;
  std::unique_ptr<LcmBridge> bridge;
  try {
    bridge = std::make_unique<LcmBridge>(config);
  } catch (const std::runtime_error&) {
    GTEST_SKIP() << kNoMulticastRoute;
  }
  Inbox inbox;
  operator_console.subscribe(kVehicleStateChannel, &Inbox::OnState, &inbox);
  bridge->Publish(fleet.server, 0.0, 0, 0);
  ASSERT_TRUE(HandleUntil(operator_console, [&] { return inbox.states >= 2; }))
      << "vehicle states did not arrive within 3 s";

  operator_command_t m{};
  m.command = operator_command_t::RETURN_ALL;
  m.reason = "smoke on the ridge";
  if (operator_console.publish(kOperatorCommandChannel, &m) != 0) GTEST_SKIP() << kNoMulticastRoute;
  std::vector<IncomingCommand> taken;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(3);
  while (taken.empty() && std::chrono::steady_clock::now() < deadline) {
    for (IncomingCommand& c : bridge->TakeCommands()) taken.push_back(c);
  }
  ASSERT_EQ(taken.size(), 1u);
  const auto& command = std::get<SignedCommand>(taken[0]);
  EXPECT_EQ(command.command.kind, OperatorCommand::Kind::kReturnAll);
  EXPECT_EQ(command.command.reason, "smoke on the ridge");
}

// Issue 17 over udpm:// on loopback: a signed START is taken, the same message
// sent again (a replay) and an unsigned one are refused, each refusal answered
// on FIRESWARM_COMMAND_STATUS with why, and counted in radio_stats_t.
struct SignedInbox {
  void OnStatus(const lcm::ReceiveBuffer*, const std::string&, const command_status_t* m) {
    statuses.push_back(*m);
  }
  void OnStats(const lcm::ReceiveBuffer*, const std::string&, const radio_stats_t* m) {
    stats.push_back(*m);
  }
  std::vector<command_status_t> statuses;
  std::vector<radio_stats_t> stats;
};

TEST(LcmBridge, RefusesUnsignedAndReplayedCommandsOverUdpm) {
  common::SecretKey key{};
  key.fill(7);
  ServerConfig server_config;
  server_config.operators = {{"ann", key}};
  Server server(server_config, kFrame);
  server.AddVehicle(1);
  server.LoadMission(testing::Missions({1}));
  LcmBridgeConfig config;
  config.url = LoopbackUrl();
  lcm::LCM console(config.url);
  if (!console.good()) GTEST_SKIP() << kNoMulticastRoute;
  std::unique_ptr<LcmBridge> bridge;
  try {
    bridge = std::make_unique<LcmBridge>(config);
  } catch (const std::runtime_error&) {
    GTEST_SKIP() << kNoMulticastRoute;
  }
  SignedInbox inbox;
  console.subscribe(kCommandStatusChannel, &SignedInbox::OnStatus, &inbox);
  console.subscribe(kRadioStatsChannel, &SignedInbox::OnStats, &inbox);

  constexpr std::int64_t kUtime = 1'764'000'000'000'000;
  OperatorCommand start;
  start.reason = "console";
  const operator_command_t signed_start = ToLcm(SignCommand(start, "ann", key, kUtime, 11));
  operator_command_t unsigned_start = signed_start;
  unsigned_start.nonce = 12;
  std::fill(std::begin(unsigned_start.mac), std::end(unsigned_start.mac), 0);
  // Handed to the server in the order sent: signed, replayed, unsigned.
  std::vector<std::pair<bool, std::string>> outcomes;
  const std::array<const operator_command_t*, 3> sent = {&signed_start, &signed_start,
                                                         &unsigned_start};
  for (const operator_command_t* m : sent) {
    if (console.publish(kOperatorCommandChannel, m) != 0) GTEST_SKIP() << kNoMulticastRoute;
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(3);
    std::vector<IncomingCommand> taken;
    while (taken.empty() && std::chrono::steady_clock::now() < deadline) {
      taken = bridge->TakeCommands();
    }
    ASSERT_EQ(taken.size(), 1u) << "command " << outcomes.size() << " did not arrive within 3 s";
    std::string why;
    const bool accepted =
        server.HandleSigned(std::get<SignedCommand>(taken[0]), Nanos{0}, kUtime, &why);
    outcomes.emplace_back(accepted, why);
  }
  EXPECT_TRUE(outcomes[0].first) << outcomes[0].second;
  EXPECT_FALSE(outcomes[1].first);
  EXPECT_TRUE(outcomes[1].second.starts_with("replayed")) << outcomes[1].second;
  EXPECT_FALSE(outcomes[2].first);
  EXPECT_TRUE(outcomes[2].second.starts_with("bad_mac")) << outcomes[2].second;
  EXPECT_EQ(server.state(), MissionState::kUploading) << "started once";

  bridge->Publish(server, 0.0, kUtime, kUtime);
  ASSERT_TRUE(
      HandleUntil(console, [&] { return inbox.statuses.size() >= 3 && !inbox.stats.empty(); }))
      << inbox.statuses.size() << " statuses";
  EXPECT_EQ(inbox.statuses[0].command_id, 1);
  EXPECT_EQ(inbox.statuses[0].operator_id, "ann");
  EXPECT_EQ(inbox.statuses[0].nonce, 11);
  EXPECT_EQ(inbox.statuses[1].command_id, 0);
  EXPECT_EQ(inbox.statuses[1].nonce, 11);
  EXPECT_TRUE(inbox.statuses[1].refusal.starts_with("replayed")) << inbox.statuses[1].refusal;
  EXPECT_EQ(inbox.statuses[2].nonce, 12);
  EXPECT_TRUE(inbox.statuses[2].refusal.starts_with("bad_mac")) << inbox.statuses[2].refusal;
  EXPECT_EQ(inbox.stats[0].commands_replayed, 1);
  EXPECT_EQ(inbox.stats[0].commands_bad_mac, 1);
  EXPECT_EQ(inbox.stats[0].commands_stale, 0);
}

// A malformed command comes out as a refusal the server journals.
TEST(LcmBridge, AMalformedCommandComesOutAsARefusal) {
  LcmBridgeConfig config;
  config.url = "memq://";
  LcmBridge bridge(config);
  operator_command_t m{};
  m.command = 99;
  m.operator_id = "mallory";
  m.nonce = 5;
  bridge.lcm()->publish(kOperatorCommandChannel, &m);
  const std::vector<IncomingCommand> taken = bridge.TakeCommands();
  ASSERT_EQ(taken.size(), 1u);
  const auto& refusal = std::get<CommandRefused>(taken[0]);
  EXPECT_EQ(refusal.verdict, CommandVerdict::kMalformed);
  EXPECT_EQ(refusal.operator_id, "mallory");
  EXPECT_EQ(refusal.command, 99);
  EXPECT_NE(refusal.why.find("unknown command 99"), std::string::npos) << refusal.why;
  EXPECT_EQ(bridge.rejected_commands(), 1u);
}

// The URL the docs and the flags' help give keeps multicast on this host.
TEST(LcmBridge, TheDefaultUrlIsHostLocal) {
  const std::string url = kDefaultLcmUrl;
  EXPECT_TRUE(url.starts_with("udpm://")) << url;
  EXPECT_TRUE(url.ends_with("?ttl=0")) << url;
}

TEST(LcmBridge, TheStockLogPlayerReplaysTheLog) {
  HeardFleet fleet;
  const std::filesystem::path dir = TempDir("replay");
  LcmBridgeConfig config;
  config.log_path = dir / "run.lcmlog";
  {
    LcmBridge bridge(config);
    PublishTenSeconds(fleet.server, bridge);  // 2 vehicles at 2 Hz: 40 states
  }
  const std::string url = LoopbackUrl();
  lcm::LCM listener(url);
  if (!listener.good()) GTEST_SKIP() << kNoMulticastRoute;
  Inbox inbox;
  // LCM keeps 30 unhandled messages per subscription by default; the replay
  // arrives while std::system() blocks.
  listener.subscribe(kVehicleStateChannel, &Inbox::OnState, &inbox)->setQueueCapacity(1'000);
  // 10 s of log at 100x: about 0.1 s. The datagrams wait in the socket buffer.
  const std::string command = "lcm-logplayer --speed=100 --lcm-url='" + url + "' '" +
                              config.log_path->string() + "' >/dev/null 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  ASSERT_TRUE(HandleUntil(listener, [&] { return inbox.states >= 40; }))
      << "only " << inbox.states << " of 40 vehicle states replayed";
}

}  // namespace
}  // namespace fireswarm::server
