// End-to-end tests of `fireswarm plan`: the real executable, the files it writes,
// its JSON, and exit code 2 with nothing written on bad input.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
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

// Issue 19: --overlap 0.99 grew past 4 GB and never ended; it is refused up
// front from the estimated lane count, naming the flag. --altitude-m has a range.
TEST_F(PlanCommand, RefusesWorkBeyondTheDocumentedLimitsNamingTheFlag) {
  // About 11.5 km x 11 km, as scenarios/areas/convex.geojson (6.9 km x 5.1 km).
  std::ofstream(PathOf("wide.geojson")) << R"({"type":"Polygon","coordinates":[[[-74.7,46.15],
    [-74.55,46.15],[-74.55,46.25],[-74.7,46.25],[-74.7,46.15]]]})";
  for (const char* overlap : {"0.99", "0.999"}) {
    const RunResult run = RunFireswarm("plan --area " + PathOf("wide.geojson") + " --out " +
                                       PathOf("plan.geojson") + " --drones 4 --overlap " + overlap);
    EXPECT_EQ(run.exit_code, 2) << JoinLines(run);
    EXPECT_THAT(JoinLines(run), HasSubstr("--overlap " + std::string(overlap)));
    EXPECT_THAT(JoinLines(run), HasSubstr("lanes, more than the limit of "));
    EXPECT_FALSE(fs::exists(PathOf("plan.geojson"))) << overlap;
  }
  const std::vector<std::pair<std::string, std::string>> cases{
      {" --altitude-m 100000", "--altitude-m must be in (0, 1000], got '100000'"},
      {" --speed-mps 1e9", "--speed-mps must be in (0, 100]"},
      {" --endurance-s 1e12", "--endurance-s must be in (0, 86400]"},
      {" --swap-s 1e7", "--swap-s must be in [0, 3600]"},
      {" --climb-mps 1000", "--climb-mps must be in (0, 50]"},
      {" --turn-cost-s 1e6", "--turn-cost-s must be in [0, 600]"},
  };
  for (const auto& [flags, message] : cases) {
    const RunResult run = RunFireswarm(Base() + " --drones 2" + flags);
    EXPECT_EQ(run.exit_code, 2) << flags;
    EXPECT_THAT(JoinLines(run), HasSubstr(message)) << flags;
    EXPECT_FALSE(fs::exists(PathOf("plan.geojson"))) << flags;
  }
}

// Issue 19: --out replaced a fifo, a symlink or a device with a regular file,
// and could overwrite its own input.
TEST_F(PlanCommand, RefusesAnOutputThatIsNotARegularFileOrIsAnInput) {
  ASSERT_EQ(::mkfifo(PathOf("fifo").c_str(), 0600), 0);
  std::ofstream(PathOf("keep.txt")) << "keep";
  fs::create_symlink(PathOf("keep.txt"), PathOf("link.geojson"));
  const std::string plan = "plan --drones 2 --area " + PathOf("area.geojson") + " --no-fly " +
                           PathOf("nofly.geojson") + " --out ";
  const std::vector<std::pair<std::string, std::string>> cases{
      {PathOf("fifo"), "is a fifo"},
      {PathOf("link.geojson"), "is a symbolic link"},
      {"/dev/full", "/dev/full: "},
      {PathOf("area.geojson"), "is the input"},
      {PathOf("sub/../nofly.geojson"), "is the input"},
      {PathOf("none/plan.geojson"), "does not exist"},
  };
  fs::create_directories(PathOf("sub"));
  for (const auto& [out, problem] : cases) {
    const RunResult run = RunFireswarm(plan + out);
    EXPECT_EQ(run.exit_code, 2) << out;
    EXPECT_THAT(JoinLines(run), HasSubstr("--out " + out + ": ")) << out;
    EXPECT_THAT(JoinLines(run), HasSubstr(problem)) << out;
  }
  struct stat info {};
  ASSERT_EQ(::lstat(PathOf("fifo").c_str(), &info), 0);
  EXPECT_TRUE(S_ISFIFO(info.st_mode));
  EXPECT_TRUE(fs::is_symlink(PathOf("link.geojson")));
  ASSERT_EQ(::stat("/dev/full", &info), 0);
  EXPECT_TRUE(S_ISCHR(info.st_mode));
  std::ifstream area(PathOf("area.geojson"));
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(area), {}), kArea);
}

// Issue 19: a flat polygon was planned, 1e999 gave a library message without
// the file, and an uneven bow tie was called "wrong orientation".
TEST_F(PlanCommand, RefusesFlatCrossedAndOutOfRangeAreasNamingFileAndFeature) {
  const std::vector<std::pair<std::string, std::string>> cases{
      // A block and a flat strip north of it: the union hid the strip, which was planned.
      {R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{"name":
        "block"},"geometry":{"type":"Polygon","coordinates":[[[-74.61,46.195],[-74.59,46.195],
        [-74.59,46.205],[-74.61,46.205],[-74.61,46.195]]]}},{"type":"Feature","properties":{
        "name":"flat"},"geometry":{"type":"Polygon","coordinates":[[[-74.61,46.21],[-74.60,46.21],
        [-74.59,46.210000001],[-74.61,46.21]]]}}]})",
       "flat.geojson: feature 1 (\"flat\"): polygon has (near-)zero area"},
      // A bow tie as a hole: named as the hole, not the polygon.
      {R"({"type":"Feature","properties":{"name":"crossed hole"},"geometry":{"type":"Polygon",
        "coordinates":[[[-74.62,46.19],[-74.58,46.19],[-74.58,46.21],[-74.62,46.21],[-74.62,46.19]],
        [[-74.61,46.195],[-74.59,46.209],[-74.59,46.195],[-74.605,46.2],[-74.61,46.195]]]}})",
       "feature 0 (\"crossed hole\"): polygon hole 1 is self-intersecting"},
      {R"({"type":"Polygon","coordinates":[[[-74.61,46.195],[-74.59,1e999],
        [-74.59,46.205],[-74.61,46.195]]]})",
       "big.geojson: number out of range at line 1, column "},
  };
  const char* names[] = {"flat.geojson", "crossed.geojson", "big.geojson"};
  for (std::size_t i = 0; i < cases.size(); ++i) {
    std::ofstream(PathOf(names[i])) << cases[i].first;
    const RunResult run = RunFireswarm("plan --area " + PathOf(names[i]) + " --drones 2 --out " +
                                       PathOf("plan.geojson"));
    EXPECT_EQ(run.exit_code, 2) << names[i];
    EXPECT_THAT(JoinLines(run), HasSubstr(cases[i].second)) << names[i];
    EXPECT_FALSE(fs::exists(PathOf("plan.geojson"))) << names[i];
  }
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
