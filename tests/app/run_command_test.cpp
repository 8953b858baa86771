// `fireswarm run` end to end through the built executable: exit codes 0 (every
// expectation holds), 1 (one fails) and 2 (bad input), and the files it writes,
// the LCM log among them.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "app/run_fireswarm.hpp"
#include "fireswarm/command_status_t.hpp"
#include "fireswarm/conflict_t.hpp"
#include "fireswarm/fire_track_list_t.hpp"
#include "fireswarm/mission_status_t.hpp"
#include "fireswarm/operator_command_t.hpp"
#include "fireswarm/plan_t.hpp"
#include "fireswarm/radio_stats_t.hpp"
#include "fireswarm/vehicle_state_t.hpp"

namespace fireswarm::app {
namespace {

// One event of an LCM log, copied out of lcm::LogFile's buffer.
struct LoggedEvent {
  std::int64_t timestamp = 0;
  std::string channel;
  std::vector<std::uint8_t> data;
};

std::vector<LoggedEvent> ReadLcmLog(const std::string& path) {
  std::vector<LoggedEvent> events;
  lcm::LogFile log(path, "r");
  EXPECT_TRUE(log.good()) << path;
  if (!log.good()) return events;
  while (const lcm::LogEvent* event = log.readNextEvent()) {
    const auto* bytes = static_cast<const std::uint8_t*>(event->data);
    events.push_back({event->timestamp, event->channel,
                      std::vector<std::uint8_t>(bytes, bytes + event->datalen)});
  }
  return events;
}

// Decodes one event as `Message`; fails the test when it does not decode whole.
template <typename Message>
Message Decode(const LoggedEvent& event) {
  Message message;
  const int size = static_cast<int>(event.data.size());
  EXPECT_EQ(message.decode(event.data.data(), 0, size), size) << event.channel;
  return message;
}

std::string FileText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

class RunCommandTest : public CommandTest {
 protected:
  std::string Write(const std::string& name, const std::string& text) const {
    std::ofstream(PathOf(name)) << text;
    return PathOf(name);
  }
  static bool Mentions(const RunResult& result, const std::string& text) {
    return std::ranges::any_of(result.lines, [&](const std::string& line) {
      return line.find(text) != std::string::npos;
    });
  }
  static std::string Output(const RunResult& result) {
    std::string all;
    for (const std::string& line : result.lines) all += line + "\n";
    return all;
  }
  // The names in the scratch directory: what a run left behind.
  std::set<std::string> Files() const {
    std::set<std::string> names;
    for (const auto& entry : std::filesystem::directory_iterator(dir_)) {
      names.insert(entry.path().filename().string());
    }
    return names;
  }
};

TEST_F(RunCommandTest, ExitsZeroWhenEveryExpectationHoldsAndWritesFiles) {
  const std::string scenario = Write("ok.yaml", TinyScenario(900.0,
                                                             "  all_fires_confirmed_within_s: 900\n"
                                                             "  max_fused_error_m: 10\n"
                                                             "  no_collisions: true\n"
                                                             "  min_coverage: 0.5\n"));
  const RunResult result =
      RunFireswarm("run " + scenario + " --report " + PathOf("r.json") + " --junit " +
                   PathOf("r.xml") + " --svg " + PathOf("map.svg"));
  EXPECT_EQ(result.exit_code, 0) << Output(result);
  std::ifstream in(PathOf("r.json"));
  ASSERT_TRUE(in.good());
  const nlohmann::json report = nlohmann::json::parse(in);
  ASSERT_EQ(report["fires"].size(), 1U);
  EXPECT_FALSE(report["fires"][0]["error_m"].is_null());
  EXPECT_EQ(report["expect"].size(), 4U);
  EXPECT_TRUE(std::filesystem::exists(PathOf("r.xml")));
  EXPECT_TRUE(std::filesystem::exists(PathOf("map.svg")));
  // stderr is a pipe here: no progress bar.
  EXPECT_FALSE(Mentions(result, "\r[")) << Output(result);
}

TEST_F(RunCommandTest, ExitsOneWhenAnExpectationFails) {
  const std::string scenario = Write("short.yaml", TinyScenario(30.0, "  min_coverage: 0.9\n"));
  const RunResult result = RunFireswarm("run " + scenario + " --report " + PathOf("r.json"));
  EXPECT_EQ(result.exit_code, 1) << Output(result);
  EXPECT_TRUE(Mentions(result, "FAIL  min_coverage")) << Output(result);
  std::ifstream in(PathOf("r.json"));
  ASSERT_TRUE(in.good());
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_EQ(report["expect"][0]["verdict"], "fail");
}

TEST_F(RunCommandTest, ExitsTwoOnABadScenarioNamingFileAndKey) {
  const std::string scenario =
      Write("bad.yaml", TinyScenario(30.0, "  min_coverage: 0.5\n") + "fleeet: 3\n");
  const RunResult result = RunFireswarm("run " + scenario + " --report " + PathOf("r.json") +
                                        " --log " + PathOf("r.lcmlog"));
  EXPECT_EQ(result.exit_code, 2) << Output(result);
  EXPECT_TRUE(Mentions(result, "bad.yaml")) << Output(result);
  EXPECT_TRUE(Mentions(result, "fleeet")) << Output(result);
  EXPECT_EQ(Files(), std::set<std::string>{"bad.yaml"}) << "nothing written";
}

TEST_F(RunCommandTest, ExitsTwoOnAMissingFileOrABadFlag) {
  RunResult result = RunFireswarm("run " + PathOf("missing.yaml"));
  EXPECT_EQ(result.exit_code, 2) << Output(result);
  EXPECT_TRUE(Mentions(result, "missing.yaml")) << Output(result);
  const std::string scenario = Write("ok.yaml", TinyScenario(30.0, "  no_collisions: true\n"));
  result = RunFireswarm("run " + scenario + " --reprot x.json");
  EXPECT_EQ(result.exit_code, 2) << Output(result);
  EXPECT_TRUE(Mentions(result, "reprot")) << Output(result);
  result = RunFireswarm("run");
  EXPECT_EQ(result.exit_code, 2) << Output(result);
}

TEST_F(RunCommandTest, LogsTheServerOnLcmInSimulatedTime) {
  const std::string scenario = Write("ok.yaml", TinyScenario(60.0, "  no_collisions: true\n"));
  const RunResult result = RunFireswarm("run " + scenario + " --report " + PathOf("r.json") +
                                        " --log " + PathOf("run.lcmlog"));
  ASSERT_EQ(result.exit_code, 0) << Output(result);
  EXPECT_TRUE(Mentions(result, "LCM log " + PathOf("run.lcmlog"))) << Output(result);
  EXPECT_EQ(Files(), (std::set<std::string>{"ok.yaml", "r.json", "run.lcmlog"}))
      << "the scratch log is gone";
  std::ifstream in(PathOf("r.json"));
  const nlohmann::json report = nlohmann::json::parse(in);
  const double sim_s = report["sim_seconds"].get<double>();
  ASSERT_GT(sim_s, 50.0);

  const std::vector<LoggedEvent> events = ReadLcmLog(PathOf("run.lcmlog"));
  ASSERT_FALSE(events.empty());
  std::map<std::string, int> per_channel;
  std::map<int, int> states_per_vehicle;
  std::int64_t previous_utime = -1;
  std::int64_t previous_status_utime = -1;
  bool saw_returning = false;
  bool fixed_before_end = false;
  double last_coverage = -1.0;
  for (const LoggedEvent& event : events) {
    ++per_channel[event.channel];
    // One time line: the event times never go back.
    EXPECT_GE(event.timestamp, previous_utime) << event.channel;
    previous_utime = event.timestamp;
    if (event.channel == "FIRESWARM_VEHICLE_STATE") {
      const auto state = Decode<fireswarm::vehicle_state_t>(event);
      EXPECT_EQ(state.utime, event.timestamp);
      EXPECT_TRUE(state.receiver_id == 1 || state.receiver_id == 2) << state.receiver_id;
      ++states_per_vehicle[state.receiver_id];
      // A position only with a GPS fix (NaN before, never a made-up one at 0, 0).
      EXPECT_EQ(std::isnan(state.lat_deg), !state.has_position) << state.receiver_id;
      EXPECT_EQ(std::isnan(state.lon_deg), !state.has_position) << state.receiver_id;
      fixed_before_end |= state.has_position;
    } else if (event.channel == "FIRESWARM_MISSION_STATUS") {
      const auto status = Decode<fireswarm::mission_status_t>(event);
      EXPECT_EQ(status.utime, event.timestamp);
      EXPECT_GT(status.utime, previous_status_utime);
      previous_status_utime = status.utime;
      // utime is simulated time: the mission started at t = 0.
      EXPECT_NEAR(status.elapsed_s, static_cast<double>(status.utime) * 1e-6, 1e-6);
      // Once the drones fly home the mission says so, and never "running" again.
      if (status.state == fireswarm::mission_status_t::STATE_RETURNING) saw_returning = true;
      if (saw_returning) {
        EXPECT_NE(status.state, fireswarm::mission_status_t::STATE_RUNNING);
      }
      last_coverage = status.coverage_fraction;
    } else if (event.channel == "FIRESWARM_PLAN") {
      const auto plan = Decode<fireswarm::plan_t>(event);
      EXPECT_EQ(plan.utime, event.timestamp);
      EXPECT_EQ(plan.mission_id, 1);
      int lanes = 0;
      const nlohmann::json geojson = nlohmann::json::parse(plan.geojson);
      for (const auto& feature : geojson["features"]) {
        lanes += feature["properties"]["kind"] == "lanes" ? 1 : 0;
      }
      EXPECT_EQ(lanes, 2) << "one per drone";
    } else if (event.channel == "FIRESWARM_FIRE_TRACKS") {
      EXPECT_EQ(Decode<fireswarm::fire_track_list_t>(event).utime, event.timestamp);
    } else if (event.channel == "FIRESWARM_RADIO_STATS") {
      EXPECT_EQ(Decode<fireswarm::radio_stats_t>(event).utime, event.timestamp);
    } else if (event.channel == "FIRESWARM_COMMAND_STATUS") {
      // The run's start, followed to each drone.
      const auto status = Decode<fireswarm::command_status_t>(event);
      EXPECT_EQ(status.utime, event.timestamp);
      EXPECT_EQ(status.command, fireswarm::operator_command_t::START);
      EXPECT_EQ(status.target_count, 2);
    } else if (event.channel == "FIRESWARM_CONFLICTS") {
      // The two drones' take-offs from neighbouring stands, watched.
      const auto conflict = Decode<fireswarm::conflict_t>(event);
      EXPECT_EQ(conflict.utime, event.timestamp);
      EXPECT_EQ(conflict.vehicle_a, 1);
      EXPECT_EQ(conflict.vehicle_b, 2);
      EXPECT_LE(conflict.detected_utime, conflict.utime);
    } else {
      ADD_FAILURE() << "unexpected channel " << event.channel;
    }
  }
  // The whole run at the bridge's rates (LcmRates): 2 Hz per vehicle, 1 Hz, 0.5 Hz, 0.2 Hz.
  EXPECT_LE(events.front().timestamp, 1'000'000);
  EXPECT_GE(events.back().timestamp, static_cast<std::int64_t>((sim_s - 1.0) * 1e6));
  EXPECT_LE(events.back().timestamp, static_cast<std::int64_t>(sim_s * 1e6) + 1);
  ASSERT_EQ(states_per_vehicle.size(), 2U);
  for (const auto& [vehicle, count] : states_per_vehicle) {
    EXPECT_NEAR(count, 2.0 * sim_s, 2.0) << "vehicle " << vehicle;
  }
  EXPECT_NEAR(per_channel["FIRESWARM_MISSION_STATUS"], sim_s, 1.0);
  EXPECT_TRUE(fixed_before_end) << "positions reached the server";
  EXPECT_NEAR(per_channel["FIRESWARM_FIRE_TRACKS"], sim_s, 1.0);
  EXPECT_NEAR(per_channel["FIRESWARM_RADIO_STATS"], 0.5 * sim_s, 1.0);
  EXPECT_NEAR(per_channel["FIRESWARM_PLAN"], 0.2 * sim_s, 1.0);
  // The server's coverage is the camera's, as the report counts it (issue 15).
  EXPECT_NEAR(last_coverage, report["coverage"].get<double>(), 0.01);
  EXPECT_GT(last_coverage, 0.0);
}

TEST_F(RunCommandTest, TheSameScenarioGivesTheSameLogAndPublishesLive) {
  const std::string scenario = Write("ok.yaml", TinyScenario(30.0, "  no_collisions: true\n"));
  const RunResult first = RunFireswarm("run " + scenario + " --log " + PathOf("a.lcmlog"));
  const RunResult second =
      RunFireswarm("run " + scenario + " --log " + PathOf("b.lcmlog") + " --lcm memq://");
  ASSERT_EQ(first.exit_code, 0) << Output(first);
  ASSERT_EQ(second.exit_code, 0) << Output(second);
  EXPECT_TRUE(Mentions(second, "published on memq://")) << Output(second);
  const std::string a = FileText(PathOf("a.lcmlog"));
  EXPECT_FALSE(a.empty());
  EXPECT_TRUE(a == FileText(PathOf("b.lcmlog"))) << "the logs differ";
}

TEST_F(RunCommandTest, ExitsTwoOnABadLcmUrlNamingTheFlagAndWritesNothing) {
  const std::string scenario = Write("ok.yaml", TinyScenario(30.0, "  no_collisions: true\n"));
  RunResult result = RunFireswarm("run " + scenario + " --lcm nosuchprovider://x --log " +
                                  PathOf("r.lcmlog") + " --report " + PathOf("r.json"));
  EXPECT_EQ(result.exit_code, 2) << Output(result);
  EXPECT_TRUE(Mentions(result, "--lcm")) << Output(result);
  EXPECT_TRUE(Mentions(result, "nosuchprovider://x")) << Output(result);
  EXPECT_EQ(Files(), std::set<std::string>{"ok.yaml"}) << "nothing written";
  result = RunFireswarm("run " + scenario + " --lcm");
  EXPECT_EQ(result.exit_code, 2) << Output(result);
  EXPECT_TRUE(Mentions(result, "--lcm")) << Output(result);
}

TEST_F(RunCommandTest, ExitsTwoOnALogInAMissingDirectoryNamingThePath) {
  const std::string scenario = Write("ok.yaml", TinyScenario(30.0, "  no_collisions: true\n"));
  const std::string log = PathOf("no_such_dir/r.lcmlog");
  RunResult result = RunFireswarm("run " + scenario + " --log " + log);
  EXPECT_EQ(result.exit_code, 2) << Output(result);
  EXPECT_TRUE(Mentions(result, "--log " + log)) << Output(result);
  EXPECT_TRUE(Mentions(result, "does not exist")) << Output(result);
  result = RunFireswarm("run " + scenario + " --log " + dir_.string());
  EXPECT_EQ(result.exit_code, 2) << Output(result);
  EXPECT_TRUE(Mentions(result, "is a directory")) << Output(result);
  EXPECT_EQ(Files(), std::set<std::string>{"ok.yaml"}) << "nothing written";
}

// Issue 19: --report could name the scenario itself and overwrite it.
TEST_F(RunCommandTest, RefusesAReportThatIsTheScenario) {
  const std::string text = TinyScenario(30.0, "  no_collisions: true\n");
  const std::string scenario = Write("ok.yaml", text);
  std::filesystem::create_directories(PathOf("sub"));
  const RunResult result =
      RunFireswarm("run " + scenario + " --report " + PathOf("sub/../ok.yaml"));
  EXPECT_EQ(result.exit_code, 2) << Output(result);
  EXPECT_TRUE(Mentions(result, "--report " + PathOf("sub/../ok.yaml") + ": is the input " +
                                   scenario))
      << Output(result);
  EXPECT_EQ(FileText(scenario), text);
}

// Issue 19: a bad --svg was found only after the whole mission had run, with the
// report already written. Now every output is checked first and nothing runs.
TEST_F(RunCommandTest, ABadOutputIsFoundBeforeTheRunAndNothingIsWritten) {
  const std::string scenario = Write("ok.yaml", TinyScenario(30.0, "  no_collisions: true\n"));
  ASSERT_EQ(::mkfifo(PathOf("map.fifo").c_str(), 0600), 0);
  const std::vector<std::pair<std::string, std::string>> cases{
      {" --svg " + PathOf("map.fifo"), "--svg " + PathOf("map.fifo") + ": is a fifo"},
      {" --svg " + PathOf("none/map.svg"), "--svg " + PathOf("none/map.svg") + ": the directory"},
      {" --junit " + PathOf("r.json"), "--junit " + PathOf("r.json") + ": is also --report"},
  };
  for (const auto& [flags, message] : cases) {
    const RunResult result = RunFireswarm("run " + scenario + " --report " + PathOf("r.json") +
                                          " --log " + PathOf("r.lcmlog") + flags);
    EXPECT_EQ(result.exit_code, 2) << Output(result);
    EXPECT_TRUE(Mentions(result, message)) << Output(result);
    EXPECT_FALSE(Mentions(result, "simulated s")) << "the run went: " << Output(result);
    EXPECT_EQ(Files(), (std::set<std::string>{"map.fifo", "ok.yaml"})) << flags;
  }
}

}  // namespace
}  // namespace fireswarm::app
