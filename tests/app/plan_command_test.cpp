// End-to-end tests of `fireswarm plan`: the real executable, the files it writes,
// its JSON, and exit code 2 with nothing written on bad input.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "app/run_fireswarm.hpp"

namespace fireswarm::app {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;
using ::testing::HasSubstr;

// About 1.5 km x 1.1 km near Mont-Tremblant, and a no-fly zone in its middle.
constexpr const char* kArea = R"({"type":"FeatureCollection","features":[{"type":"Feature",
  "properties":{"name":"test block"},"geometry":{"type":"Polygon","coordinates":[[
  [-74.61,46.195],[-74.59,46.195],[-74.59,46.205],[-74.61,46.205],[-74.61,46.195]]]}}]})";
constexpr const char* kNoFly = R"({"type":"Polygon","coordinates":[[
  [-74.601,46.199],[-74.599,46.199],[-74.599,46.201],[-74.601,46.201],[-74.601,46.199]]]})";
constexpr const char* kBowTie = R"({"type":"FeatureCollection","features":[{"type":"Feature",
  "properties":{"name":"bow tie"},"geometry":{"type":"Polygon","coordinates":[[
  [-74.61,46.195],[-74.59,46.205],[-74.59,46.195],[-74.61,46.205],[-74.61,46.195]]]}}]})";

std::string JoinLines(const RunResult& run) {
  std::string text;
  for (const std::string& line : run.lines) text += line + "\n";
  return text;
}

class PlanCommand : public CommandTest {
 protected:
  void SetUp() override {
    CommandTest::SetUp();
    std::ofstream(PathOf("area.geojson")) << kArea;
    std::ofstream(PathOf("nofly.geojson")) << kNoFly;
  }
  std::string Base() const {
    return "plan --area " + PathOf("area.geojson") + " --out " + PathOf("plan.geojson");
  }
  // Only the two inputs in the scratch directory: nothing else was written.
  bool NothingWritten() const {
    return std::distance(fs::directory_iterator(dir_), fs::directory_iterator()) == 2;
  }
};

TEST_F(PlanCommand, WritesGeoJsonAndQgcPlansAndConsistentJson) {
  const RunResult run =
      RunFireswarm(Base() + " --drones 3 --receiver-ids 4,7,9 --qgc " + PathOf("qgc") + " --json");
  ASSERT_EQ(run.exit_code, 0) << JoinLines(run);
  ASSERT_EQ(run.lines.size(), 1U) << JoinLines(run);
  const Json figures = Json::parse(run.lines[0]);
  for (const char* key : {"coverage", "makespan_s", "lower_bound_s", "nofly_violation_m",
                          "planning_seconds", "drones", "sweep_width_m"}) {
    EXPECT_TRUE(figures.contains(key)) << key;
  }
  EXPECT_GE(figures["coverage"].get<double>(), 0.99);
  EXPECT_LE(figures["coverage"].get<double>(), 1.0);
  EXPECT_EQ(figures["nofly_violation_m"].get<double>(), 0.0);
  EXPECT_GE(figures["makespan_s"].get<double>(), figures["lower_bound_s"].get<double>());

  const Json& drones = figures["drones"];
  ASSERT_EQ(drones.size(), 3U);
  const std::vector<int> ids{4, 7, 9};
  double slowest_s = 0.0;
  for (std::size_t i = 0; i < drones.size(); ++i) {
    EXPECT_EQ(drones[i]["receiver_id"], ids[i]);
    EXPECT_GT(drones[i]["length_m"].get<double>(), 0.0);
    EXPECT_GT(drones[i]["waypoints"].get<int>(), 1);
    slowest_s = std::max(slowest_s, drones[i]["time_s"].get<double>());
  }
  EXPECT_DOUBLE_EQ(slowest_s, figures["makespan_s"].get<double>());

  // The GeoJSON: one LineString per drone with the same figures.
  std::ifstream in(PathOf("plan.geojson"));
  const Json doc = Json::parse(in);
  EXPECT_EQ(doc["type"], "FeatureCollection");
  std::size_t paths = 0;
  for (const Json& feature : doc["features"]) {
    if (feature["properties"]["kind"] != "path") continue;
    EXPECT_EQ(feature["geometry"]["type"], "LineString");
    EXPECT_EQ(feature["properties"]["receiver_id"], drones[paths]["receiver_id"]);
    EXPECT_DOUBLE_EQ(feature["properties"]["length_m"].get<double>(),
                     drones[paths]["length_m"].get<double>());
    ++paths;
  }
  EXPECT_EQ(paths, 3U);

  // One .plan per drone (or per sortie), each a QGC plan with takeoff first, RTL last.
  std::size_t plans = 0;
  for (const auto& entry : fs::directory_iterator(PathOf("qgc"))) {
    std::ifstream plan_in(entry.path());
    const Json plan = Json::parse(plan_in);
    EXPECT_EQ(plan["fileType"], "Plan");
    const Json& items = plan["mission"]["items"];
    ASSERT_GE(items.size(), 3U);
    EXPECT_EQ(items.front()["command"], 22);
    EXPECT_EQ(items.back()["command"], 20);
    ++plans;
  }
  EXPECT_GE(plans, 3U);
  EXPECT_EQ(figures["qgc_files"].size(), plans);
}

TEST_F(PlanCommand, AvoidsNoFlyZonesWithBothPlanners) {
  for (const char* planner : {"lawnmower", "ompl"}) {
    const RunResult run = RunFireswarm(Base() + " --drones 2 --no-fly " + PathOf("nofly.geojson") +
                                       " --planner " + planner + " --camera lepton35 --json");
    ASSERT_EQ(run.exit_code, 0) << planner << "\n" << JoinLines(run);
    const Json figures = Json::parse(run.lines.back());
    EXPECT_EQ(figures["planner"], planner);
    EXPECT_EQ(figures["nofly_violation_m"].get<double>(), 0.0) << planner;
    EXPECT_GE(figures["coverage"].get<double>(), 0.99) << planner;
  }
}

TEST_F(PlanCommand, PrintsATableByDefault) {
  const RunResult run = RunFireswarm(Base() + " --drones 2 --launch 46.195,-74.61");
  ASSERT_EQ(run.exit_code, 0) << JoinLines(run);
  const std::string text = JoinLines(run);
  EXPECT_THAT(text, HasSubstr("receiver"));
  EXPECT_THAT(text, HasSubstr("coverage"));
  EXPECT_THAT(text, HasSubstr("makespan"));
  EXPECT_TRUE(fs::exists(PathOf("plan.geojson")));
}

TEST_F(PlanCommand, BadFlagsExitTwoNamingTheFlagAndWriteNothing) {
  const std::vector<std::pair<std::string, std::string>> cases{
      {" --drones 0", "--drones"},
      {" --drones 2 --camera flir", "--camera"},
      {" --drones 2 --planner astar", "--planner"},
      {" --drones 2 --speed-mps -1", "--speed-mps"},
      {" --drones 2 --overlap 1.5", "--overlap"},
      {" --drones 2 --receiver-ids 1,1", "--receiver-ids"},
      {" --drones 2 --launch 95,10", "--launch"},
      {" --drones 2 --altitude-m abc", "altitude-m"},
      {" --drones 2 --no-such-flag 1", "no-such-flag"},
      {" --drones 2 --swap-s -5", "--swap-s"},
      {" --drones 2 --climb-mps 0", "--climb-mps"},
      {" --drones 2 --descent-mps -1", "--descent-mps"},
      // 60 m up at 3 m/s and down at 1 m/s take 80 s of the 60.
      {" --drones 2 --endurance-s 60", "--endurance-s"},
      {" --drones 2 --launch 46.2,-74.6 --launch 46.2", "--launch"},
  };
  for (const auto& [flags, named] : cases) {
    const RunResult run = RunFireswarm(Base() + flags + " --qgc " + PathOf("qgc"));
    EXPECT_EQ(run.exit_code, 2) << flags;
    EXPECT_THAT(JoinLines(run), HasSubstr(named)) << flags;
    EXPECT_TRUE(NothingWritten()) << flags;
  }
}

TEST_F(PlanCommand, BadAreaExitsTwoNamingFileAndFeature) {
  std::ofstream(PathOf("bow.geojson")) << kBowTie;
  const RunResult run = RunFireswarm("plan --area " + PathOf("bow.geojson") + " --drones 2 --out " +
                                     PathOf("plan.geojson"));
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(JoinLines(run), HasSubstr("bow.geojson: feature 0 (\"bow tie\"): polygon is "
                                        "self-intersecting"));
  EXPECT_FALSE(fs::exists(PathOf("plan.geojson")));
  const RunResult missing = RunFireswarm("plan --area " + PathOf("none.geojson") +
                                         " --drones 2 --out " + PathOf("plan.geojson"));
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_THAT(JoinLines(missing), HasSubstr("none.geojson: cannot open"));
}

// Two launch sites given twice over: by repeated --launch and by a GeoJSON file
// that also fixes how many drones each site has.
TEST_F(PlanCommand, LaunchSitesFromFlagsOrAFile) {
  const RunResult flags = RunFireswarm(Base() +
                                       " --drones 4 --launch 46.195,-74.61 --launch "
                                       "46.205,-74.59 --swap-s 120 --endurance-s 600 --json");
  ASSERT_EQ(flags.exit_code, 0) << JoinLines(flags);
  const Json plan = Json::parse(flags.lines.at(0));
  std::set<int> sites;
  for (const Json& drone : plan["drones"]) {
    sites.insert(drone["site"].get<int>());
    EXPECT_DOUBLE_EQ(drone["ground_s"].get<double>(), 120.0 * (drone["sorties"].get<int>() - 1));
    EXPECT_LE(drone["longest_sortie_s"].get<double>(), 600.0);
  }
  EXPECT_EQ(sites, (std::set<int>{0, 1}));
  EXPECT_FALSE(plan["lower_bound_basis"].get<std::string>().empty());

  std::ofstream(PathOf("sites.geojson")) << R"({"type":"FeatureCollection","features":[
    {"type":"Feature","properties":{"drones":3},"geometry":{"type":"Point","coordinates":[-74.61,46.195]}},
    {"type":"Feature","properties":{"drones":1},"geometry":{"type":"Point","coordinates":[-74.59,46.205]}}]})";
  const RunResult file =
      RunFireswarm(Base() + " --drones 4 --launch-file " + PathOf("sites.geojson") + " --json");
  ASSERT_EQ(file.exit_code, 0) << JoinLines(file);
  std::vector<int> per_site(2, 0);
  const Json from_file = Json::parse(file.lines.at(0));
  for (const Json& drone : from_file["drones"]) {
    ++per_site.at(drone["site"].get<std::size_t>());
  }
  EXPECT_EQ(per_site, (std::vector<int>{3, 1}));
  const Json written = Json::parse(std::ifstream(PathOf("plan.geojson")));
  int site_points = 0;
  for (const Json& feature : written["features"]) {
    site_points += feature["properties"]["kind"] == "launch_site" ? 1 : 0;
  }
  EXPECT_EQ(site_points, 2);
}

TEST_F(PlanCommand, BadLaunchFileExitsTwoNamingFileAndFeature) {
  std::ofstream(PathOf("sites.geojson")) << R"({"type":"FeatureCollection","features":[
    {"type":"Feature","properties":{"drones":2},"geometry":{"type":"Point","coordinates":[-74.61,46.195]}},
    {"type":"Feature","properties":{"name":"north gate","drones":-1},"geometry":{"type":"Point","coordinates":[-74.59,46.205]}}]})";
  const RunResult run =
      RunFireswarm(Base() + " --drones 2 --launch-file " + PathOf("sites.geojson"));
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(JoinLines(run), HasSubstr("sites.geojson: feature 1 (\"north gate\"): "
                                        "properties.drones must be an integer in 0..254"));
  EXPECT_FALSE(fs::exists(PathOf("plan.geojson")));
  std::ofstream(PathOf("sites.geojson"), std::ios::trunc)
      << R"({"type":"FeatureCollection","features":[
    {"type":"Feature","properties":{"drones":1},"geometry":{"type":"Point","coordinates":[-74.61,46.195]}},
    {"type":"Feature","properties":{"drones":5},"geometry":{"type":"Point","coordinates":[-74.59,46.205]}}]})";
  const RunResult sum =
      RunFireswarm(Base() + " --drones 2 --launch-file " + PathOf("sites.geojson"));
  EXPECT_EQ(sum.exit_code, 2);
  EXPECT_THAT(JoinLines(sum), HasSubstr("--launch-file: the counts add up to 6, the fleet has 2"));
  std::ofstream(PathOf("sites.geojson"), std::ios::trunc)
      << R"({"type":"Polygon","coordinates":[[[-74.61,46.195],[-74.59,46.195],[-74.59,46.205],[-74.61,46.195]]]})";
  const RunResult polygon =
      RunFireswarm(Base() + " --drones 2 --launch-file " + PathOf("sites.geojson"));
  EXPECT_EQ(polygon.exit_code, 2);
  EXPECT_THAT(JoinLines(polygon), HasSubstr("expected a Point"));
}

TEST_F(PlanCommand, HelpListsTheOptions) {
  const RunResult run = RunFireswarm("plan --help");
  EXPECT_EQ(run.exit_code, 0);
  const std::string text = JoinLines(run);
  for (const char* flag : {"--area", "--no-fly", "--drones", "--altitude-m", "--speed-mps",
                           "--camera", "--planner", "--out", "--qgc", "--json", "--launch",
                           "--launch-file", "--swap-s", "--climb-mps", "--descent-mps"}) {
    EXPECT_THAT(text, HasSubstr(flag));
  }
}

}  // namespace
}  // namespace fireswarm::app
