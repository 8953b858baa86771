// `fireswarm run` end to end through the built executable: exit codes 0 (every
// expectation holds), 1 (one fails) and 2 (bad input), and the files it writes.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "app/run_fireswarm.hpp"

namespace fireswarm::app {
namespace {

// 800 m x 500 m, two drones, one fire; `duration` and `expect` vary per test.
std::string Scenario(double duration_s, const std::string& expect) {
  return "name: tiny\n"
         "seed: 7\n"
         "duration_s: " +
         std::to_string(duration_s) +
         "\n"
         "area:\n"
         "  polygon: [[7.0, 45.0], [7.010146, 45.0], [7.010146, 45.0045], [7.0, 45.0045]]\n"
         "fleet:\n"
         "  count: 2\n"
         "  launch: {lat: 44.9995, lon: 7.005}\n"
         "fires:\n"
         "  - {lat: 45.00230, lon: 7.00480}\n"
         "expect:\n" +
         expect;
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
};

TEST_F(RunCommandTest, ExitsZeroWhenEveryExpectationHoldsAndWritesFiles) {
  const std::string scenario = Write("ok.yaml", Scenario(900.0,
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
  const std::string scenario = Write("short.yaml", Scenario(30.0, "  min_coverage: 0.9\n"));
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
      Write("bad.yaml", Scenario(30.0, "  min_coverage: 0.5\n") + "fleeet: 3\n");
  const RunResult result = RunFireswarm("run " + scenario + " --report " + PathOf("r.json"));
  EXPECT_EQ(result.exit_code, 2) << Output(result);
  EXPECT_TRUE(Mentions(result, "bad.yaml")) << Output(result);
  EXPECT_TRUE(Mentions(result, "fleeet")) << Output(result);
  EXPECT_FALSE(std::filesystem::exists(PathOf("r.json")));
}

TEST_F(RunCommandTest, ExitsTwoOnAMissingFileOrABadFlag) {
  RunResult result = RunFireswarm("run " + PathOf("missing.yaml"));
  EXPECT_EQ(result.exit_code, 2) << Output(result);
  EXPECT_TRUE(Mentions(result, "missing.yaml")) << Output(result);
  const std::string scenario = Write("ok.yaml", Scenario(30.0, "  no_collisions: true\n"));
  result = RunFireswarm("run " + scenario + " --reprot x.json");
  EXPECT_EQ(result.exit_code, 2) << Output(result);
  EXPECT_TRUE(Mentions(result, "reprot")) << Output(result);
  result = RunFireswarm("run");
  EXPECT_EQ(result.exit_code, 2) << Output(result);
}

}  // namespace
}  // namespace fireswarm::app
