// End-to-end tests of `fireswarm sim-bench`: the real executable and its JSON.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "app/run_fireswarm.hpp"

namespace fireswarm::app {
namespace {

using Json = nlohmann::json;

Json RunJson(const std::string& arguments) {
  const RunResult run = RunFireswarm("sim-bench --json " + arguments);
  EXPECT_EQ(run.exit_code, 0);
  if (run.lines.size() != 1) {
    ADD_FAILURE() << "expected one JSON line, got " << run.lines.size();
    return {};
  }
  return Json::parse(run.lines[0]);
}

TEST(SimBenchCommand, JsonHasTheFiguresAndTheyAgree) {
  const Json f = RunJson("--drones 4 --camera amg8833 --area-km2 0.5 --seconds 10");
  for (const char* key : {"real_time_factor", "drones", "camera_frames", "sim_seconds",
                          "wall_seconds", "wall_seconds_by_part", "state_hash"}) {
    EXPECT_TRUE(f.contains(key)) << key;
  }
  EXPECT_EQ(f["drones"], 4);
  EXPECT_DOUBLE_EQ(f["sim_seconds"].get<double>(), 10.0);
  // amg8833 runs at 10 Hz: frame k is due at k / 10 s, k = 1..100 within 10 s.
  EXPECT_EQ(f["camera_frames"], 4 * 100);
  const double rtf = f["real_time_factor"].get<double>();
  EXPECT_NEAR(rtf, f["sim_seconds"].get<double>() / f["wall_seconds"].get<double>(), 1e-6 * rtf);
  double parts_s = 0.0;
  for (const auto& [part, seconds] : f["wall_seconds_by_part"].items()) {
    parts_s += seconds.get<double>();
  }
  EXPECT_LE(parts_s, f["wall_seconds"].get<double>());
}

TEST(SimBenchCommand, SameSeedSameStateDifferentSeedDifferent) {
  const std::string run = "--drones 6 --camera seed --area-km2 0.5 --seconds 8 --seed ";
  const Json a = RunJson(run + "3");
  const Json b = RunJson(run + "3");
  const Json c = RunJson(run + "4");
  EXPECT_EQ(a["state_hash"], b["state_hash"]);
  EXPECT_NE(a["state_hash"], c["state_hash"]);
}

TEST(SimBenchCommand, WithoutCamerasThereAreNoFrames) {
  const Json f = RunJson("--drones 3 --camera none --area-km2 0.5 --seconds 2");
  EXPECT_EQ(f["camera_frames"], 0);
}

TEST(SimBenchCommand, BadFlagsExitTwoNamingTheFlag) {
  const auto first_line = [](const RunResult& run) {
    return run.lines.empty() ? std::string() : run.lines.front();
  };
  RunResult run = RunFireswarm("sim-bench --drones 0");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(first_line(run).find("drones must be in [1, 1000], got 0"), std::string::npos)
      << first_line(run);
  run = RunFireswarm("sim-bench --camera flir");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(first_line(run).find("camera must be none|seed|amg8833|lepton35, got 'flir'"),
            std::string::npos)
      << first_line(run);
  run = RunFireswarm("sim-bench --seconds -1");
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_NE(first_line(run).find("--seconds"), std::string::npos) << first_line(run);
}

}  // namespace
}  // namespace fireswarm::app
