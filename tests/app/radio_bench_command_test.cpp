// End-to-end tests of `fireswarm radio-bench`: the real executable, its JSON, and the
// air captures it writes, read back by `fireswarm radio-decode` and lcm::LogFile.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <lcm/lcm-cpp.hpp>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app/run_fireswarm.hpp"
#include "fireswarm/radio_frame_t.hpp"

namespace fireswarm::app {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

constexpr const char* kSmallRun = "radio-bench --vehicles 6 --seconds 20 --loss 0.05";
constexpr int kSeed = 7;

class RadioBenchCommand : public CommandTest {
 protected:
  // Runs the small bench with --json and returns its one JSON object.
  Json RunJson(const std::string& extra, int seed = kSeed) {
    const RunResult run = RunFireswarm(std::string(kSmallRun) + " --json --seed " +
                                       std::to_string(seed) + " " + extra);
    EXPECT_EQ(run.exit_code, 0);
    if (run.lines.size() != 1) {
      ADD_FAILURE() << "expected one JSON line, got " << run.lines.size();
      return {};
    }
    return Json::parse(run.lines[0]);
  }
};

std::string ReadFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST_F(RadioBenchCommand, JsonHasTheFiguresToolsRead) {
  const Json figures = RunJson("");
  for (const char* key : {"busy_fraction", "payload_bytes_per_s", "telemetry_hz_min",
                          "telemetry_age_p99_s", "report_latency_p99_s", "reports_sent",
                          "reports_lost", "collisions", "retries", "wall_seconds"}) {
    EXPECT_TRUE(figures.contains(key)) << key;
  }
  EXPECT_GT(figures["busy_fraction"].get<double>(), 0.0);
  EXPECT_EQ(figures["vehicles"], 6);

  // Per vehicle: one entry per receiver ID, consistent with the fleet figures.
  const Json& per_vehicle = figures.at("per_vehicle");
  ASSERT_EQ(per_vehicle.size(), 6U);
  double slowest_hz = 1e9;
  double stalest_p99_s = 0.0;
  std::uint64_t reports = 0;
  for (std::size_t i = 0; i < per_vehicle.size(); ++i) {
    EXPECT_EQ(per_vehicle[i]["receiver_id"], i + 1);
    EXPECT_LE(per_vehicle[i]["telemetry_age_p50_s"].get<double>(),
              per_vehicle[i]["telemetry_age_p99_s"].get<double>());
    slowest_hz = std::min(slowest_hz, per_vehicle[i]["telemetry_hz"].get<double>());
    stalest_p99_s = std::max(stalest_p99_s, per_vehicle[i]["telemetry_age_p99_s"].get<double>());
    reports += per_vehicle[i]["reports_sent"].get<std::uint64_t>();
  }
  EXPECT_DOUBLE_EQ(slowest_hz, figures["telemetry_hz_min"].get<double>());
  EXPECT_LE(figures["telemetry_age_p99_s"].get<double>(), stalest_p99_s);
  EXPECT_EQ(reports, figures["reports_sent"].get<std::uint64_t>());
}

TEST_F(RadioBenchCommand, RawCaptureDecodesWithoutErrors) {
  const Json figures = RunJson("--capture " + PathOf("air.bin"));
  ASSERT_TRUE(fs::exists(PathOf("air.bin")));
  EXPECT_FALSE(fs::exists(PathOf("air.bin.partial")));

  const RunResult decoded = RunFireswarm("radio-decode " + PathOf("air.bin"));
  ASSERT_EQ(decoded.exit_code, 0);
  ASSERT_FALSE(decoded.lines.empty());
  const Json summary = Json::parse(decoded.lines.back()).at("summary");
  // The capture holds every transmission not lost to a collision, byte-exact.
  EXPECT_EQ(summary["checksum_errors"], 0);
  EXPECT_EQ(summary["truncated_frames"], 0);
  EXPECT_EQ(summary["skipped_bytes"], 0);
  EXPECT_EQ(summary["decode_errors"], 0);
  const auto clean_transmissions =
      figures["transmissions"].get<std::uint64_t>() - figures["collisions"].get<std::uint64_t>();
  EXPECT_GE(summary["frames"].get<std::uint64_t>(), clean_transmissions);
  EXPECT_EQ(decoded.lines.size(), summary["frames"].get<std::size_t>() + 1);
}

TEST_F(RadioBenchCommand, LcmLogHoldsOneRadioFramePerTransmission) {
  const Json figures = RunJson("--lcm-log " + PathOf("air.lcmlog"));
  lcm::LogFile log(PathOf("air.lcmlog"), "r");
  ASSERT_TRUE(log.good());
  std::uint64_t events = 0;
  std::int64_t previous_timestamp = 0;
  for (const lcm::LogEvent* event = log.readNextEvent(); event != nullptr;
       event = log.readNextEvent()) {
    ++events;
    EXPECT_EQ(event->channel, "RADIO_AIR");
    EXPECT_GE(event->timestamp, previous_timestamp) << "timestamps must not go backwards";
    previous_timestamp = event->timestamp;
    radio_frame_t frame{};
    ASSERT_GT(frame.decode(event->data, 0, event->datalen), 0);
    EXPECT_EQ(frame.byte_count, static_cast<std::int32_t>(frame.bytes.size()));
    EXPECT_GT(frame.end_us, frame.start_us);
    EXPECT_LE(frame.transmitter_receiver_id, 6);
  }
  EXPECT_EQ(events, figures["transmissions"].get<std::uint64_t>());
}

TEST_F(RadioBenchCommand, SameSeedGivesTheSameRunByteForByte) {
  // The wall-clock figures (the run's, the server's CPU per channel) vary.
  const auto simulated = [](Json run) {
    run.erase("wall_seconds");
    for (Json& channel : run.at("per_channel")) channel.erase("server_step_s");
    return run;
  };
  const Json first = simulated(RunJson("--capture " + PathOf("a.bin")));
  const Json second = simulated(RunJson("--capture " + PathOf("b.bin")));
  EXPECT_EQ(first, second);
  EXPECT_EQ(ReadFile(PathOf("a.bin")), ReadFile(PathOf("b.bin")));
  const Json other = simulated(RunJson("", kSeed + 1));
  EXPECT_NE(first, other);
}

TEST_F(RadioBenchCommand, BadFlagsExitTwoNamingTheFlag) {
  const RunResult mode = RunFireswarm("radio-bench --mode shout");
  EXPECT_EQ(mode.exit_code, 2);
  ASSERT_FALSE(mode.lines.empty());
  EXPECT_NE(mode.lines[0].find("--mode"), std::string::npos) << mode.lines[0];

  const RunResult vehicles = RunFireswarm("radio-bench --vehicles 0");
  EXPECT_EQ(vehicles.exit_code, 2);
  ASSERT_FALSE(vehicles.lines.empty());
  EXPECT_NE(vehicles.lines[0].find("--vehicles"), std::string::npos) << vehicles.lines[0];

  const RunResult unknown = RunFireswarm("radio-bench --warp 9");
  EXPECT_EQ(unknown.exit_code, 2);
}

TEST_F(RadioBenchCommand, UnwritableCaptureExitsTwoAndLeavesNothing) {
  const std::string path = PathOf("missing_dir/air.bin");
  const RunResult run = RunFireswarm(std::string(kSmallRun) + " --capture " + path);
  EXPECT_EQ(run.exit_code, 2);
  ASSERT_FALSE(run.lines.empty());
  EXPECT_NE(run.lines[0].find(path), std::string::npos) << run.lines[0];
  EXPECT_FALSE(fs::exists(path));
}

}  // namespace
}  // namespace fireswarm::app
