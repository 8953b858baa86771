// Scenario files: every key read and typed, the defaults, GeoJSON and inline areas,
// and, for each kind of bad input, a ScenarioError naming the file, the key path and
// the problem. The repository's scenarios/*.yaml and the documentation's full
// example must load too.
#include "fireswarm/run/scenario.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <boost/geometry/algorithms/area.hpp>
#include <boost/geometry/algorithms/covered_by.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "common/scratch_dir.hpp"
#include "fireswarm/planner/area_io.hpp"
#include "fireswarm/radio/channel.hpp"
#include "fireswarm/radio/master_scheduler.hpp"

namespace fireswarm::run {
namespace {

namespace bg = boost::geometry;
namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::StartsWith;

constexpr const char* kSource = "test.yaml";

// A box of 0.02 x 0.02 degrees (about 1.5 km x 2.2 km) in the Laurentians.
constexpr const char* kBoxGeoJson =
    R"({"type":"Polygon","coordinates":[[[-74.61,46.19],[-74.59,46.19],[-74.59,46.21],)"
    R"([-74.61,46.21],[-74.61,46.19]]]})";
constexpr const char* kBoxPolygonYaml =
    "[[-74.61, 46.19], [-74.59, 46.19], [-74.59, 46.21], [-74.61, 46.21]]";
constexpr double kBoxAreaM2 = 0.02 * 111'150.0 * 0.02 * 111'150.0 * 0.6921;  // cos(46.2 deg)

void WriteFile(const fs::path& path, const std::string& text) {
  fs::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

// A directory of this test process with areas/box.geojson in it.
const fs::path& TestDir() {
  static const test_support::ScratchDir dir("fireswarm_scenario_test");
  const fs::path box = dir.path() / "areas" / "box.geojson";
  if (!fs::exists(box)) WriteFile(box, kBoxGeoJson);
  return dir.path();
}

// The repository root, found by walking up from this source file.
fs::path RepoRoot() {
  for (fs::path dir = fs::path(__FILE__).parent_path(); !dir.empty(); dir = dir.parent_path()) {
    if (fs::exists(dir / "scenarios") && fs::exists(dir / "docs") && fs::exists(dir / "tests")) {
      return dir;
    }
    if (dir == dir.root_path()) break;
  }
  ADD_FAILURE() << "no repository root above " << __FILE__;
  return {};
}

Scenario Parse(const std::string& yaml) {
  return ParseScenario(yaml, kSource, TestDir());
}

std::string ErrorOf(const std::string& yaml) {
  try {
    Parse(yaml);
  } catch (const ScenarioError& e) {
    return e.what();
  }
  return "(no error)";
}

// The smallest valid scenario plus `extra` (YAML lines at the top level).
std::string Minimal(const std::string& extra = "") {
  return std::string("area:\n  polygon: ") + kBoxPolygonYaml + "\nfleet:\n  count: 2\n" + extra;
}

constexpr const char* kFullExample = R"(name: full
seed: 7
duration_s: 900
area:
  geojson: areas/box.geojson
no_fly:
  - [[-74.601, 46.199], [-74.599, 46.199], [-74.599, 46.201], [-74.601, 46.201]]
fleet:
  count: 3
  first_id: 10
  launch: {lat: 46.191, lon: -74.609}
  camera: lepton35
  camera_pitch_deg: -60
  altitude_m: 80
  speed_mps: 12
  endurance_s: 1200
  planner: ompl
  stand_spacing_m: 12.5
radio:
  baud: 115200
  turnaround_ms: 2.5
  loss: 0.1
  checksum: xor
  mode: poll
fires:
  - {lat: 46.195, lon: -74.605, start_s: 30, radius_m: 20}
  - {lat: 46.205, lon: -74.595}
random_fires: {count: 2, seed: 99, radius_m: 7}
distractors:
  - {lat: 46.2, lon: -74.605, radius_m: 4, temp_c: 65}
wind: {speed_mps: 5, from_deg: 225}
faults:
  - {vehicle: 11, at_s: 100, kind: total_loss}
  - {vehicle: 10, at_s: 50, kind: bias, duration_s: 60, sensor: attitude, bias: [0.1, -0.2, 0]}
  - {vehicle: 12, at_s: 10, kind: extra_noise, duration_s: 20, sensor: baro, noise_factor: 4}
  - {vehicle: 12, at_s: 200, kind: ballast, ballast_offset_m: [0.05, -0.02]}
  - {vehicle: 10, at_s: 300, kind: radio_silent, duration_s: 45}
expect:
  all_fires_confirmed_within_s: 600
  max_fused_error_m: 12.5
  no_collisions: true
  min_coverage: 0.9
  max_false_tracks: 1
  min_separation_m: 2.5
  max_reports_lost: 3
)";

TEST(ParseScenario, FullExampleReadsEveryField) {
  const Scenario s = Parse(kFullExample);
  EXPECT_EQ(s.source, kSource);
  EXPECT_EQ(s.name, "full");
  EXPECT_EQ(s.seed, 7U);
  EXPECT_DOUBLE_EQ(s.duration_s, 900.0);
  ASSERT_TRUE(s.area_geojson.has_value());
  EXPECT_EQ(*s.area_geojson, (TestDir() / "areas" / "box.geojson").lexically_normal());
  EXPECT_FALSE(s.no_fly_geojson.has_value());
  EXPECT_FALSE(s.area.no_fly.empty());
  EXPECT_NEAR(bg::area(s.area.area), kBoxAreaM2 - bg::area(s.area.no_fly), 0.01 * kBoxAreaM2);

  EXPECT_EQ(s.fleet.count, 3);
  EXPECT_EQ(s.fleet.first_id, 10);
  EXPECT_EQ(s.fleet.ReceiverIds(), (std::vector<int>{10, 11, 12}));
  EXPECT_TRUE(s.fleet.launch_given);
  EXPECT_DOUBLE_EQ(s.fleet.launch.lat_deg, 46.191);
  EXPECT_DOUBLE_EQ(s.fleet.launch.lon_deg, -74.609);
  ASSERT_NE(s.fleet.camera, nullptr);
  EXPECT_EQ(s.fleet.camera->name, "lepton35");
  EXPECT_DOUBLE_EQ(s.fleet.camera_pitch_deg, -60.0);
  EXPECT_DOUBLE_EQ(s.fleet.altitude_m, 80.0);
  EXPECT_DOUBLE_EQ(s.fleet.speed_mps, 12.0);
  EXPECT_DOUBLE_EQ(s.fleet.endurance_s, 1200.0);
  EXPECT_EQ(s.fleet.planner, planner::PlannerKind::kOmpl);
  EXPECT_DOUBLE_EQ(s.fleet.stand_spacing_m, 12.5);

  EXPECT_EQ(s.radio.baud, 115'200);
  EXPECT_DOUBLE_EQ(s.radio.turnaround_ms, 2.5);
  EXPECT_DOUBLE_EQ(s.radio.loss, 0.1);
  EXPECT_EQ(s.radio.checksum, radio::ChecksumMode::kXor);
  EXPECT_EQ(s.radio.mode, radio::LinkMode::kPoll);

  ASSERT_EQ(s.fires.size(), 2U);
  EXPECT_DOUBLE_EQ(s.fires[0].position.lat_deg, 46.195);
  EXPECT_DOUBLE_EQ(s.fires[0].position.lon_deg, -74.605);
  EXPECT_DOUBLE_EQ(s.fires[0].start_s, 30.0);
  EXPECT_DOUBLE_EQ(s.fires[0].radius_m, 20.0);
  EXPECT_DOUBLE_EQ(s.fires[1].start_s, 0.0);
  EXPECT_DOUBLE_EQ(s.fires[1].radius_m, kDefaultFireRadiusM);
  ASSERT_TRUE(s.random_fires.has_value());
  EXPECT_EQ(s.random_fires->count, 2);
  EXPECT_EQ(s.random_fires->seed, 99U);
  EXPECT_DOUBLE_EQ(s.random_fires->radius_m, 7.0);

  ASSERT_EQ(s.distractors.size(), 1U);
  EXPECT_DOUBLE_EQ(s.distractors[0].position.lat_deg, 46.2);
  EXPECT_DOUBLE_EQ(s.distractors[0].radius_m, 4.0);
  EXPECT_DOUBLE_EQ(s.distractors[0].temp_c, 65.0);
  EXPECT_DOUBLE_EQ(s.wind.speed_mps, 5.0);
  EXPECT_DOUBLE_EQ(s.wind.from_deg, 225.0);

  ASSERT_EQ(s.faults.size(), 5U);
  EXPECT_EQ(s.faults[0].vehicle, 11);
  EXPECT_EQ(s.faults[0].kind, FaultKind::kTotalLoss);
  EXPECT_DOUBLE_EQ(s.faults[0].at_s, 100.0);
  EXPECT_TRUE(std::isinf(s.faults[0].duration_s));
  EXPECT_EQ(s.faults[1].kind, FaultKind::kBias);
  EXPECT_EQ(s.faults[1].sensor, FaultSensor::kAttitude);
  EXPECT_DOUBLE_EQ(s.faults[1].duration_s, 60.0);
  EXPECT_EQ(s.faults[1].bias, (std::array<double, 3>{0.1, -0.2, 0.0}));
  EXPECT_EQ(s.faults[2].kind, FaultKind::kExtraNoise);
  EXPECT_EQ(s.faults[2].sensor, FaultSensor::kBaro);
  EXPECT_DOUBLE_EQ(s.faults[2].noise_factor, 4.0);
  EXPECT_EQ(s.faults[3].kind, FaultKind::kBallast);
  EXPECT_EQ(s.faults[3].ballast_offset_m, (std::array<double, 2>{0.05, -0.02}));
  EXPECT_EQ(s.faults[4].kind, FaultKind::kRadioSilent);
  EXPECT_DOUBLE_EQ(s.faults[4].duration_s, 45.0);

  EXPECT_EQ(s.expect.all_fires_confirmed_within_s, 600.0);
  EXPECT_EQ(s.expect.max_fused_error_m, 12.5);
  EXPECT_TRUE(s.expect.no_collisions);
  EXPECT_EQ(s.expect.min_coverage, 0.9);
  EXPECT_EQ(s.expect.max_false_tracks, 1);
  EXPECT_EQ(s.expect.min_separation_m, 2.5);
  EXPECT_EQ(s.expect.max_reports_lost, 3);
  EXPECT_FALSE(s.expect.min_collisions.has_value());
}

TEST(ParseScenario, DefaultsMatchThePlannerAndTheRadio) {
  const Scenario s = Parse(Minimal());
  EXPECT_EQ(s.name, "test");  // the file's stem
  EXPECT_EQ(s.seed, kDefaultSeed);
  EXPECT_DOUBLE_EQ(s.duration_s, kDefaultDurationS);
  EXPECT_FALSE(s.area_geojson.has_value());
  EXPECT_TRUE(s.area.no_fly.empty());

  const planner::FleetSpec planner_defaults;
  EXPECT_EQ(s.fleet.ReceiverIds(), (std::vector<int>{1, 2}));
  EXPECT_FALSE(s.fleet.launch_given);
  const planner::Point launch = planner::DefaultLaunchPoint(s.area);
  const common::EastNorth launch_local = s.area.frame.ToLocal(s.fleet.launch);
  EXPECT_NEAR(launch_local.east_m, launch.x(), 1e-6);
  EXPECT_NEAR(launch_local.north_m, launch.y(), 1e-6);
  ASSERT_NE(s.fleet.camera, nullptr);
  EXPECT_EQ(s.fleet.camera->name, kDefaultCamera);
  EXPECT_DOUBLE_EQ(s.fleet.camera_pitch_deg, planner_defaults.camera_pitch_deg);
  EXPECT_DOUBLE_EQ(s.fleet.altitude_m, planner_defaults.altitude_m);
  EXPECT_DOUBLE_EQ(s.fleet.speed_mps, planner_defaults.speed_mps);
  EXPECT_DOUBLE_EQ(s.fleet.endurance_s, planner_defaults.endurance_s);
  EXPECT_DOUBLE_EQ(s.fleet.swap_s, planner_defaults.swap_s);
  ASSERT_EQ(s.fleet.launch_sites.size(), 1U);
  EXPECT_DOUBLE_EQ(s.fleet.launch_sites[0].position.lat_deg, s.fleet.launch.lat_deg);
  EXPECT_DOUBLE_EQ(s.fleet.launch_sites[0].position.lon_deg, s.fleet.launch.lon_deg);
  EXPECT_FALSE(s.fleet.launch_sites[0].drones.has_value());
  EXPECT_EQ(s.fleet.planner, planner::PlannerKind::kLawnmower);
  EXPECT_DOUBLE_EQ(s.fleet.stand_spacing_m, kDefaultStandSpacingM);

  const radio::ChannelConfig channel;
  const radio::SchedulerConfig scheduler;
  EXPECT_EQ(s.radio.baud, channel.baud);
  EXPECT_DOUBLE_EQ(s.radio.turnaround_ms * 1e6, static_cast<double>(channel.turnaround.count()));
  EXPECT_DOUBLE_EQ(s.radio.loss, channel.loss);
  // Scenarios run secured by default (issue 17); the bare scheduler's default is crc16.
  EXPECT_EQ(s.radio.checksum, radio::ChecksumMode::kSecure);
  EXPECT_EQ(s.radio.mode, scheduler.mode);

  EXPECT_TRUE(s.fires.empty());
  EXPECT_FALSE(s.random_fires.has_value());
  EXPECT_TRUE(s.distractors.empty());
  EXPECT_DOUBLE_EQ(s.wind.speed_mps, 0.0);
  EXPECT_TRUE(s.faults.empty());
  EXPECT_FALSE(s.expect.all_fires_confirmed_within_s.has_value());
  EXPECT_FALSE(s.expect.max_fused_error_m.has_value());
  EXPECT_FALSE(s.expect.no_collisions);
  EXPECT_FALSE(s.expect.min_coverage.has_value());
  EXPECT_FALSE(s.expect.max_false_tracks.has_value());
  EXPECT_FALSE(s.expect.min_separation_m.has_value());
  EXPECT_FALSE(s.expect.max_reports_lost.has_value());
  EXPECT_FALSE(s.expect.min_collisions.has_value());
}

// A scenario built to collide states how many collisions it must report; it may
// say no_collisions: false, never true.
TEST(ParseScenario, MinCollisionsReadsWithoutNoCollisions) {
  const Scenario s = Parse(Minimal("expect: {min_collisions: 2, no_collisions: false}\n"));
  EXPECT_EQ(s.expect.min_collisions, 2);
  EXPECT_FALSE(s.expect.no_collisions);
  EXPECT_EQ(Parse(Minimal("expect: {max_reports_lost: 0}\n")).expect.max_reports_lost, 0);
}

TEST(ParseScenario, RandomFiresSeedDefaultsToTheScenarioSeed) {
  const Scenario s = Parse(Minimal("seed: 1234\nrandom_fires: {count: 5}\n"));
  ASSERT_TRUE(s.random_fires.has_value());
  EXPECT_EQ(s.random_fires->seed, 1234U);
  EXPECT_DOUBLE_EQ(s.random_fires->radius_m, kDefaultFireRadiusM);
}

TEST(ParseScenario, InlinePolygonOpenOrClosedGivesTheSameArea) {
  const Scenario open = Parse(Minimal());
  EXPECT_NEAR(bg::area(open.area.area), kBoxAreaM2, 0.01 * kBoxAreaM2);
  const Scenario closed = Parse(
      "area:\n  polygon: [[-74.61, 46.19], [-74.59, 46.19], [-74.59, 46.21], [-74.61, 46.21], "
      "[-74.61, 46.19]]\nfleet: {count: 1}\n");
  EXPECT_DOUBLE_EQ(bg::area(closed.area.area), bg::area(open.area.area));
  // Clockwise (against GeoJSON's winding) is accepted as the planner accepts it.
  const Scenario clockwise = Parse(
      "area:\n  polygon: [[-74.61, 46.19], [-74.61, 46.21], [-74.59, 46.21], [-74.59, 46.19]]\n"
      "fleet: {count: 1}\n");
  EXPECT_NEAR(bg::area(clockwise.area.area), bg::area(open.area.area), 1e-6);
}

TEST(ParseScenario, NoFlyFromAGeoJsonFileOrInlineCutsTheArea) {
  WriteFile(TestDir() / "zones" / "tower.geojson",
            R"({"type":"Polygon","coordinates":[[[-74.601,46.199],[-74.599,46.199],)"
            R"([-74.599,46.201],[-74.601,46.201],[-74.601,46.199]]]})");
  const Scenario from_file = Parse(Minimal("no_fly: zones/tower.geojson\n"));
  ASSERT_TRUE(from_file.no_fly_geojson.has_value());
  EXPECT_EQ(*from_file.no_fly_geojson, (TestDir() / "zones" / "tower.geojson").lexically_normal());
  const Scenario inline_zone =
      Parse(Minimal("no_fly:\n  - [[-74.601, 46.199], [-74.599, 46.199], [-74.599, 46.201], "
                    "[-74.601, 46.201]]\n"));
  const double zone_m2 = bg::area(inline_zone.area.no_fly);
  EXPECT_GT(zone_m2, 30'000.0);  // 0.002 x 0.002 deg, about 154 m x 222 m
  EXPECT_NEAR(bg::area(from_file.area.no_fly), zone_m2, 1.0);
  EXPECT_NEAR(bg::area(inline_zone.area.area), kBoxAreaM2 - zone_m2, 0.01 * kBoxAreaM2);
  EXPECT_FALSE(bg::covered_by(planner::Point(0.0, 0.0), inline_zone.area.area));
  // An empty list is no zones.
  EXPECT_TRUE(Parse(Minimal("no_fly: []\n")).area.no_fly.empty());
}

TEST(LoadScenario, ResolvesGeoJsonRelativeToTheScenarioFile) {
  const fs::path scenario = TestDir() / "nested" / "deeper" / "mission.yaml";
  WriteFile(scenario, "area:\n  geojson: ../../areas/box.geojson\nfleet:\n  count: 4\n");
  // From another working directory, so a path relative to it would not be found.
  const fs::path before = fs::current_path();
  fs::current_path(fs::path(::testing::TempDir()));
  const Scenario s = LoadScenario(scenario);
  fs::current_path(before);
  EXPECT_EQ(s.name, "mission");
  EXPECT_EQ(s.source, scenario.string());
  ASSERT_TRUE(s.area_geojson.has_value());
  EXPECT_EQ(*s.area_geojson, (TestDir() / "areas" / "box.geojson").lexically_normal());
  EXPECT_NEAR(bg::area(s.area.area), kBoxAreaM2, 0.01 * kBoxAreaM2);
}

// LoadScenario's error for `path`; a test failure when it loads.
std::string LoadError(const fs::path& path) {
  try {
    LoadScenario(path);
  } catch (const ScenarioError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error for " << path;
  return {};
}

TEST(LoadScenario, AMissingScenarioFileNamesIt) {
  const fs::path missing = TestDir() / "no_such.yaml";
  const std::string error = LoadError(missing);
  EXPECT_THAT(error, StartsWith(missing.string() + ": "));
  EXPECT_THAT(error, HasSubstr("cannot open"));
}

// A name the system cannot look up (one component over 255 bytes): the error names
// the file and says why, where std::filesystem's throwing calls threw their own
// exception (found by the scenario fuzz target for a GeoJSON path).
TEST(LoadScenario, ANameTooLongIsAScenarioErrorNamingIt) {
  const fs::path too_long = TestDir() / (std::string(300, 'a') + ".yaml");
  const std::string error = LoadError(too_long);
  EXPECT_THAT(error, StartsWith(too_long.string() + ": cannot open the scenario file"));
  EXPECT_THAT(error, HasSubstr("File name too long"));
}

TEST(LoadScenario, ADirectoryIsNotAScenarioFile) {
  EXPECT_THAT(LoadError(TestDir()), HasSubstr(": is a directory, not a scenario file"));
}

TEST(LoadScenario, ErrorsNameTheFileAsGiven) {
  const fs::path bad = TestDir() / "bad.yaml";
  WriteFile(bad, Minimal("radio: {loss: 2}\n"));
  const std::string error = LoadError(bad);
  EXPECT_THAT(error, StartsWith(bad.string() + ":5:"));
  EXPECT_THAT(error, HasSubstr("radio.loss: must be in [0, 1], got 2"));
}

TEST(ParseScenario, UnknownKeyNamesTheNearestValidOneAndItsPlace) {
  const std::string error = ErrorOf(
      "area:\n  polygon: [[-74.61, 46.19], [-74.59, 46.19], [-74.59, 46.21]]\n"
      "fleet:\n  count: 2\n  altitude: 50\n");
  EXPECT_THAT(error, StartsWith("test.yaml:5:3: fleet.altitude: unknown key"));
  EXPECT_THAT(error, HasSubstr("did you mean 'altitude_m'?"));
  EXPECT_THAT(error, HasSubstr("valid keys: count|first_id|launch"));
  EXPECT_THAT(ErrorOf(Minimal("duraton_s: 10\n")), HasSubstr("did you mean 'duration_s'?"));
  EXPECT_THAT(ErrorOf(Minimal("expect: {min_coverag: 0.5}\n")),
              HasSubstr("expect.min_coverag: unknown key; did you mean 'min_coverage'?"));
  EXPECT_THAT(ErrorOf(Minimal("fires:\n  - {lat: 46.2, lon: -74.6, start: 5}\n")),
              HasSubstr("fires[0].start: unknown key; did you mean 'start_s'?"));
}

TEST(ParseScenario, MalformedYamlGivesTheLine) {
  const std::string error = ErrorOf("fleet:\n  count: [1, 2\narea: {}\n");
  EXPECT_THAT(error, StartsWith("test.yaml:3:"));
  EXPECT_THAT(error, HasSubstr("malformed YAML"));
  EXPECT_THAT(ErrorOf(""), HasSubstr("test.yaml: the scenario must be a YAML mapping"));
  EXPECT_THAT(ErrorOf("- 1\n- 2\n"), HasSubstr("test.yaml: the scenario must be a YAML mapping"));
}

// One bad input: the YAML and what the message must contain besides the file name.
struct BadInput {
  const char* label;
  std::string yaml;
  std::string key_path;
  std::string problem;
};

void PrintTo(const BadInput& input, std::ostream* out) {
  *out << input.label;
}

class ParseScenarioErrors : public ::testing::TestWithParam<BadInput> {};

TEST_P(ParseScenarioErrors, NameFileKeyAndProblem) {
  const BadInput& input = GetParam();
  const std::string error = ErrorOf(input.yaml);
  EXPECT_THAT(error, StartsWith(std::string(kSource) + ":"));
  EXPECT_THAT(error, HasSubstr(" " + input.key_path + ": "));
  EXPECT_THAT(error, HasSubstr(input.problem));
}

const std::string kFleet = "fleet:\n  count: 2\n";
const std::string kArea = std::string("area:\n  polygon: ") + kBoxPolygonYaml + "\n";

INSTANTIATE_TEST_SUITE_P(
    Cases, ParseScenarioErrors,
    ::testing::Values(
        BadInput{"MissingArea", kFleet, "area", "missing (required)"},
        BadInput{"MissingFleet", kArea, "fleet", "missing (required)"},
        BadInput{"MissingCount", kArea + "fleet: {first_id: 3}\n", "fleet.count",
                 "missing (required)"},
        BadInput{"AreaNeitherKey", kFleet + "area: {}\n", "area",
                 "missing geojson (a file) or polygon"},
        BadInput{"AreaBothKeys", kFleet + "area: {geojson: a.geojson, polygon: []}\n", "area",
                 "either geojson or polygon, not both"},
        BadInput{"CountZero", kArea + "fleet: {count: 0}\n", "fleet.count",
                 "must be in [1, 254], got 0"},
        BadInput{"CountTooMany", kArea + "fleet: {count: 300}\n", "fleet.count",
                 "must be in [1, 254], got 300"},
        BadInput{"CountFraction", kArea + "fleet: {count: 2.5}\n", "fleet.count",
                 "must be an integer in [1, 254], got 2.5"},
        BadInput{"CountQuoted", kArea + "fleet: {count: \"4\"}\n", "fleet.count",
                 "got the string \"4\""},
        BadInput{"CountList", kArea + "fleet: {count: [4]}\n", "fleet.count",
                 "must be a single value, got a list"},
        BadInput{"IdsBeyond254", kArea + "fleet: {count: 3, first_id: 253}\n", "fleet.first_id",
                 "first_id + count - 1 = 255 is beyond the largest receiver ID 254"},
        BadInput{"FleetNotAMapping", kArea + "fleet: [1, 2]\n", "fleet", "must be a mapping"},
        BadInput{"LaunchListEmpty", kArea + "fleet: {count: 2, launch: []}\n", "fleet.launch",
                 "lists no launch site"},
        BadInput{
            "LaunchSiteLatitude",
            kArea + "fleet: {count: 1, launch: [{lat: 46.2, lon: -74.6}, {lat: 95, lon: 0}]}\n",
            "fleet.launch[1].lat", "must be in [-90, 90], got 95"},
        BadInput{"LaunchSiteUnknownKey",
                 kArea + "fleet: {count: 1, launch: [{lat: 46.2, lon: -74.6, drone: 1}]}\n",
                 "fleet.launch[0].drone", "did you mean 'drones'?"},
        BadInput{"LaunchSiteDronesOnSome",
                 kArea + "fleet: {count: 2, launch: [{lat: 46.2, lon: -74.6, drones: 2}, "
                         "{lat: 46.195, lon: -74.605}]}\n",
                 "fleet.launch[1]", "give drones on every site or on none"},
        BadInput{"LaunchSiteDronesSum",
                 kArea + "fleet: {count: 2, launch: [{lat: 46.2, lon: -74.6, drones: 1}, "
                         "{lat: 46.195, lon: -74.605, drones: 2}]}\n",
                 "fleet.launch[1].drones", "the sites' drones sum to 3, not fleet.count 2"},
        BadInput{"LaunchSiteDronesNegative",
                 kArea + "fleet: {count: 2, launch: [{lat: 46.2, lon: -74.6, drones: -1}]}\n",
                 "fleet.launch[0].drones", "must be in [0, 2], got -1"},
        BadInput{
            "LaunchSiteFarAway",
            kArea + "fleet: {count: 1, launch: [{lat: 46.2, lon: -74.6}, {lat: 40, lon: 0}]}\n",
            "fleet.launch[1]", "km"},
        BadInput{"SwapZero", kArea + "fleet: {count: 2, swap_s: 0}\n", "fleet.swap_s",
                 "must be in (0, 3600], got 0"},
        BadInput{"SwapOverAnHour", kArea + "fleet: {count: 2, swap_s: 4000}\n", "fleet.swap_s",
                 "got 4000"},
        BadInput{"LaunchLatitude", kArea + "fleet: {count: 1, launch: {lat: 95, lon: -74.6}}\n",
                 "fleet.launch.lat", "must be in [-90, 90], got 95"},
        BadInput{"LaunchMissingLon", kArea + "fleet: {count: 1, launch: {lat: 46.2}}\n",
                 "fleet.launch.lon", "missing (required)"},
        BadInput{"LaunchFarAway", kArea + "fleet: {count: 1, launch: {lat: 48.2, lon: -74.6}}\n",
                 "fleet.launch", "km from the area's centre"},
        BadInput{"LaunchInNoFly",
                 kArea + "fleet: {count: 1, launch: {lat: 46.2, lon: -74.6}}\n" +
                     "no_fly: [[[-74.601, 46.199], [-74.599, 46.199], [-74.599, 46.201], "
                     "[-74.601, 46.201]]]\n",
                 "fleet.launch", "inside a no-fly zone"},
        BadInput{"AltitudeNegative", kArea + "fleet: {count: 1, altitude_m: -5}\n",
                 "fleet.altitude_m", "must be in (0, 1000], got -5"},
        BadInput{"SpeedZero", kArea + "fleet: {count: 1, speed_mps: 0}\n", "fleet.speed_mps",
                 "must be in (0, 100], got 0"},
        BadInput{"EnduranceText", kArea + "fleet: {count: 1, endurance_s: long}\n",
                 "fleet.endurance_s", "must be a finite number, got long"},
        BadInput{"PitchAtHorizon", kArea + "fleet: {count: 1, camera_pitch_deg: 0}\n",
                 "fleet.camera_pitch_deg", "must be in [-90, 0), got 0"},
        BadInput{"UnknownCamera", kArea + "fleet: {count: 1, camera: flir}\n", "fleet.camera",
                 "must be one of seed|amg8833|lepton35, got flir"},
        BadInput{"UnknownPlannerTypo", kArea + "fleet: {count: 1, planner: lawnmover}\n",
                 "fleet.planner", "got lawnmover (did you mean 'lawnmower'?)"},
        BadInput{"UnknownPlanner", kArea + "fleet: {count: 1, planner: rrt}\n", "fleet.planner",
                 "must be one of lawnmower|ompl, got rrt"},
        BadInput{"StandSpacingBelowTheRotors", kArea + "fleet: {count: 2, stand_spacing_m: 0.5}\n",
                 "fleet.stand_spacing_m", "must be in [1, 100], got 0.5"},
        BadInput{"StandSpacingText", kArea + "fleet: {count: 2, stand_spacing_m: close}\n",
                 "fleet.stand_spacing_m", "must be a finite number, got close"},
        BadInput{"UnknownChecksum", Minimal("radio: {checksum: crc32}\n"), "radio.checksum",
                 "must be one of xor|crc16|secure, got crc32 (did you mean 'crc16'?)"},
        BadInput{"UnknownMode", Minimal("radio: {mode: tdma}\n"), "radio.mode",
                 "must be one of poll|slots, got tdma"},
        BadInput{"BaudZero", Minimal("radio: {baud: 0}\n"), "radio.baud",
                 "must be in [1, 10000000], got 0"},
        BadInput{"LossAboveOne", Minimal("radio: {loss: 1.5}\n"), "radio.loss",
                 "must be in [0, 1], got 1.5"},
        BadInput{"TurnaroundNegative", Minimal("radio: {turnaround_ms: -1}\n"),
                 "radio.turnaround_ms", "must be in [0, 1000], got -1"},
        BadInput{"DurationZero", Minimal("duration_s: 0\n"), "duration_s",
                 "must be in (0, 86400], got 0"},
        BadInput{"SeedNegative", Minimal("seed: -1\n"), "seed", "must be an integer in [0, "},
        BadInput{"NameEmpty", Minimal("name: ''\n"), "name", "must not be empty"},
        BadInput{"RepeatedKey", Minimal("seed: 1\nseed: 2\n"), "seed", "repeated key"},
        BadInput{"KeyWithoutValue", Minimal("wind:\n"), "wind", "has no value"},
        BadInput{"MissingGeoJsonFile", kFleet + "area: {geojson: areas/nowhere.geojson}\n",
                 "area.geojson", "GeoJSON file not found: "},
        BadInput{"GeoJsonNameTooLong",
                 kFleet + "area: {geojson: " + std::string(300, 'a') + ".geojson}\n",
                 "area.geojson", "cannot look up the GeoJSON file (File name too long): "},
        BadInput{"NoFlyNameTooLong", Minimal("no_fly: " + std::string(300, 'z') + ".geojson\n"),
                 "no_fly", "cannot look up the GeoJSON file (File name too long): "},
        BadInput{"MissingNoFlyFile", Minimal("no_fly: zones/none.geojson\n"), "no_fly",
                 "GeoJSON file not found: "},
        BadInput{"NoFlyWrongType", Minimal("no_fly: {geojson: x}\n"), "no_fly",
                 "must be a GeoJSON file name or a list of polygons"},
        BadInput{"PolygonLatitude",
                 kFleet + "area: {polygon: [[-74.61, 46.19], [-74.59, 95], [-74.59, 46.21]]}\n",
                 "area.polygon[1]", "latitude must be in [-90, 90], got 95"},
        BadInput{"PolygonNotPairs", kFleet + "area: {polygon: [[-74.61, 46.19, 3, 4]]}\n",
                 "area.polygon[0]", "must be a [longitude, latitude] pair"},
        BadInput{"PolygonTooFewCorners",
                 kFleet + "area: {polygon: [[-74.61, 46.19], [-74.59, 46.19]]}\n", "area.polygon",
                 "at least 3 corners"},
        BadInput{"PolygonSelfIntersecting",
                 kFleet + "area: {polygon: [[-74.61, 46.19], [-74.59, 46.21], [-74.59, 46.19], "
                          "[-74.61, 46.21]]}\n",
                 "area.polygon", "area.polygon: polygon is self-intersecting"},
        BadInput{"NoFlySelfIntersecting",
                 Minimal("no_fly:\n  - [[-74.601, 46.199], [-74.599, 46.199], [-74.599, 46.201]]\n"
                         "  - [[-74.601, 46.199], [-74.599, 46.201], [-74.599, 46.199], "
                         "[-74.601, 46.201]]\n"),
                 "no_fly[1]", "7:5: no_fly[1]: polygon is self-intersecting"},
        BadInput{"NoFlyCoversTheArea", Minimal(std::string("no_fly: [") + kBoxPolygonYaml + "]\n"),
                 "area.polygon", "no area left after subtracting the no-fly zones"},
        BadInput{"FireOutside",
                 Minimal("fires:\n  - {lat: 46.2, lon: -74.6}\n  - {lat: 46.2, lon: -74.6}\n"
                         "  - {lat: 46.3, lon: -74.6}\n"),
                 "fires[2]", "lies outside the search area"},
        BadInput{"FireStartAfterTheEnd",
                 Minimal("duration_s: 100\nfires: [{lat: 46.2, lon: -74.6, start_s: 100}]\n"),
                 "fires[0].start_s", "must be in [0, 100), got 100"},
        BadInput{"FireRadiusZero", Minimal("fires: [{lat: 46.2, lon: -74.6, radius_m: 0}]\n"),
                 "fires[0].radius_m", "must be in (0, 1000], got 0"},
        BadInput{"FiresNotAList", Minimal("fires: {lat: 46.2, lon: -74.6}\n"), "fires",
                 "must be a list, got a mapping"},
        BadInput{"RandomFireSpacingNegative",
                 Minimal("random_fires: {count: 2, min_spacing_m: -1}\n"),
                 "random_fires.min_spacing_m", "must be in [0, 10000], got -1"},
        BadInput{"RandomFiresWithoutCount", Minimal("random_fires: {seed: 3}\n"),
                 "random_fires.count", "missing (required)"},
        BadInput{"DistractorTooHot",
                 Minimal("distractors: [{lat: 46.2, lon: -74.6, temp_c: 5000}]\n"),
                 "distractors[0].temp_c", "must be in [-50, 200], got 5000"},
        // The simulator refused it, after the plan and without the file's name.
        BadInput{"DistractorHotterThanTheSimulatorTakes",
                 Minimal("distractors: [{lat: 46.2, lon: -74.6, temp_c: 300}]\n"),
                 "distractors[0].temp_c", "must be in [-50, 200], got 300"},
        BadInput{"WindFromFullCircle", Minimal("wind: {from_deg: 360}\n"), "wind.from_deg",
                 "must be in [0, 360), got 360"},
        BadInput{"FaultUnknownKind", Minimal("faults: [{vehicle: 1, at_s: 5, kind: explode}]\n"),
                 "faults[0].kind",
                 "must be one of stream_cut|frozen|bias|extra_noise|ballast|total_loss|"
                 "radio_silent|server_restart|vehicle_reboot|gps_loss|radio_burst, got explode"},
        BadInput{"ServerRestartWithAVehicle",
                 Minimal("faults: [{vehicle: 1, at_s: 5, kind: server_restart}]\n"),
                 "faults[0].vehicle", "server_restart concerns the server: it takes no vehicle"},
        BadInput{"ServerRestartDownTooLong",
                 Minimal("faults: [{at_s: 5, kind: server_restart, duration_s: 4000}]\n"),
                 "faults[0].duration_s", "must be in (0, 3600], got 4000"},
        BadInput{"ServerRestartDownZero",
                 Minimal("faults: [{at_s: 5, kind: server_restart, duration_s: 0}]\n"),
                 "faults[0].duration_s", "must be in (0, 3600], got 0"},
        BadInput{"VehicleRebootWithoutAVehicle",
                 Minimal("faults: [{at_s: 5, kind: vehicle_reboot}]\n"), "faults[0].vehicle",
                 "missing (required)"},
        BadInput{"VehicleRebootTooLong",
                 Minimal("faults: [{vehicle: 1, at_s: 5, kind: vehicle_reboot, duration_s: 11}]\n"),
                 "faults[0].duration_s", "must be in (0, 10], got 11"},
        BadInput{"VehicleRebootWithASensor",
                 Minimal("faults:\n  - {at_s: 1, kind: stream_cut, vehicle: 1}\n"
                         "  - {vehicle: 2, at_s: 5, kind: vehicle_reboot, sensor: gps}\n"),
                 "faults[1].sensor", "applies only to kind stream_cut|frozen|bias|extra_noise"},
        BadInput{"VehicleRebootWithALoss",
                 Minimal("faults: [{vehicle: 1, at_s: 5, kind: vehicle_reboot, loss: 0.5}]\n"),
                 "faults[0].loss", "applies only to kind radio_burst"},
        BadInput{"GpsLossWithASensor",
                 Minimal("faults: [{vehicle: 1, at_s: 5, kind: gps_loss, sensor: baro}]\n"),
                 "faults[0].sensor", "applies only to kind stream_cut|frozen|bias|extra_noise"},
        BadInput{"GpsLossOfAnUnknownVehicle",
                 Minimal("faults: [{vehicle: 7, at_s: 5, kind: gps_loss, duration_s: 5}]\n"),
                 "faults[0].vehicle", "is not one of the fleet's receiver IDs 1..2, got 7"},
        BadInput{"GpsLossDurationZero",
                 Minimal("faults: [{vehicle: 1, at_s: 5, kind: gps_loss, duration_s: 0}]\n"),
                 "faults[0].duration_s", "must be in (0, 86400], got 0"},
        BadInput{"RadioBurstWithAVehicle",
                 Minimal("faults: [{vehicle: 1, at_s: 5, kind: radio_burst, duration_s: 2, "
                         "loss: 1}]\n"),
                 "faults[0].vehicle",
                 "radio_burst concerns every radio channel: it takes no vehicle"},
        BadInput{"RadioBurstWithoutLoss",
                 Minimal("faults: [{at_s: 5, kind: radio_burst, duration_s: 2}]\n"),
                 "faults[0].loss", "missing (required)"},
        BadInput{"RadioBurstLossZero",
                 Minimal("faults: [{at_s: 5, kind: radio_burst, duration_s: 2, loss: 0}]\n"),
                 "faults[0].loss", "must be in (0, 1], got 0"},
        BadInput{"RadioBurstLossAboveOne",
                 Minimal("faults: [{at_s: 5, kind: radio_burst, duration_s: 2, loss: 1.5}]\n"),
                 "faults[0].loss", "must be in (0, 1], got 1.5"},
        BadInput{"RadioBurstWithoutDuration",
                 Minimal("faults: [{at_s: 5, kind: radio_burst, loss: 0.5}]\n"),
                 "faults[0].duration_s", "missing (required)"},
        BadInput{"LossOnAServerRestart",
                 Minimal("faults: [{at_s: 5, kind: server_restart, loss: 0.5}]\n"),
                 "faults[0].loss", "applies only to kind radio_burst"},
        BadInput{"VehicleFaultWithoutAVehicle", Minimal("faults: [{at_s: 5, kind: total_loss}]\n"),
                 "faults[0].vehicle", "missing (required)"},
        BadInput{"FaultUnknownVehicle",
                 Minimal("faults: [{vehicle: 3, at_s: 5, kind: total_loss}]\n"),
                 "faults[0].vehicle", "is not one of the fleet's receiver IDs 1..2, got 3"},
        BadInput{"FaultAfterTheEnd",
                 Minimal("duration_s: 60\nfaults: [{vehicle: 1, at_s: 60, kind: total_loss}]\n"),
                 "faults[0].at_s", "must be in [0, 60), got 60"},
        BadInput{"FaultTotalLossWithDuration",
                 Minimal("faults: [{vehicle: 1, at_s: 5, kind: total_loss, duration_s: 3}]\n"),
                 "faults[0].duration_s", "total_loss is permanent"},
        BadInput{"FaultBiasWithoutVector",
                 Minimal("faults: [{vehicle: 1, at_s: 5, kind: bias, duration_s: 3}]\n"),
                 "faults[0].bias", "missing (required)"},
        BadInput{"FaultBiasWrongLength",
                 Minimal("faults: [{vehicle: 1, at_s: 5, kind: bias, bias: [1, 2]}]\n"),
                 "faults[0].bias", "must be a list of 3 numbers, got 2"},
        // Issue 19: every numeric key has a range.
        BadInput{"FaultBiasBeyondRange",
                 Minimal("faults: [{vehicle: 1, at_s: 5, kind: bias, sensor: gps, "
                         "bias: [1, 1e300, 0]}]\n"),
                 "faults[0].bias[1]", "must be in [-200000, 200000], got 1e300"},
        BadInput{"FaultDurationBeyondADay",
                 Minimal("faults: [{vehicle: 1, at_s: 5, kind: frozen, sensor: gps, "
                         "duration_s: 1e9}]\n"),
                 "faults[0].duration_s", "must be in (0, 86400], got 1e9"},
        BadInput{"FaultParameterOfAnotherKind",
                 Minimal("faults: [{vehicle: 1, at_s: 5, kind: bias, bias: [1, 2, 3], "
                         "noise_factor: 3}]\n"),
                 "faults[0].noise_factor", "applies only to kind extra_noise"},
        BadInput{"FaultSensorOnTotalLoss",
                 Minimal("faults: [{vehicle: 1, at_s: 5, kind: total_loss, sensor: gps}]\n"),
                 "faults[0].sensor", "applies only to kind stream_cut|frozen|bias|extra_noise"},
        BadInput{"FaultUnknownSensor",
                 Minimal("faults: [{vehicle: 1, at_s: 5, kind: frozen, sensor: lidar}]\n"),
                 "faults[0].sensor", "must be one of gps|baro|attitude|battery, got lidar"},
        BadInput{"FaultNoiseFactorOne",
                 Minimal("faults: [{vehicle: 1, at_s: 5, kind: extra_noise, noise_factor: 1}]\n"),
                 "faults[0].noise_factor", "must be in (1, 1000], got 1"},
        BadInput{"CoverageAsPercent", Minimal("expect: {min_coverage: 95}\n"),
                 "expect.min_coverage", "is a fraction in [0, 1], got 95 (did you mean 0.95?)"},
        BadInput{"NoCollisionsNotBool", Minimal("expect: {no_collisions: yes}\n"),
                 "expect.no_collisions", "must be true or false, got yes"},
        BadInput{"FalseTracksNegative", Minimal("expect: {max_false_tracks: -1}\n"),
                 "expect.max_false_tracks", "must be in [0, 1000000], got -1"},
        BadInput{"ConfirmWithinZero", Minimal("expect: {all_fires_confirmed_within_s: 0}\n"),
                 "expect.all_fires_confirmed_within_s", "must be > 0, got 0"},
        BadInput{"SeparationZero", Minimal("expect: {min_separation_m: 0}\n"),
                 "expect.min_separation_m", "must be > 0, got 0"},
        BadInput{"SeparationQuoted", Minimal("expect: {min_separation_m: \"2\"}\n"),
                 "expect.min_separation_m", "got the string \"2\""},
        BadInput{"ReportsLostNegative", Minimal("expect: {max_reports_lost: -1}\n"),
                 "expect.max_reports_lost", "must be in [0, 1000000], got -1"},
        BadInput{"ReportsLostFraction", Minimal("expect: {max_reports_lost: 0.5}\n"),
                 "expect.max_reports_lost", "must be an integer in [0, 1000000], got 0.5"},
        BadInput{"MinCollisionsZero", Minimal("expect: {min_collisions: 0}\n"),
                 "expect.min_collisions", "must be in [1, 1000000], got 0"},
        BadInput{"MinCollisionsWithNoCollisions",
                 Minimal("expect: {no_collisions: true, min_collisions: 1}\n"),
                 "expect.min_collisions", "contradicts no_collisions: true"},
        BadInput{"MinCollisionsTypo", Minimal("expect: {min_colisions: 1}\n"),
                 "expect.min_colisions", "did you mean 'min_collisions'?"}),
    [](const ::testing::TestParamInfo<BadInput>& param_info) {
      return std::string(param_info.param.label);
    });

TEST(ParseScenario, AnInvalidGeoJsonFileIsNamedWithTheKey) {
  WriteFile(TestDir() / "areas" / "broken.geojson", "{\"type\": \"Polygon\", ");
  const std::string error = ErrorOf(kFleet + "area: {geojson: areas/broken.geojson}\n");
  EXPECT_THAT(error, StartsWith("test.yaml:3:"));
  EXPECT_THAT(error,
              HasSubstr("area.geojson: " + (TestDir() / "areas" / "broken.geojson").string() +
                        ": malformed JSON"));
}

TEST(MakeFleetSpec, CarriesTheFleetIntoThePlannersFrame) {
  const Scenario s = Parse(kFullExample);
  const planner::FleetSpec spec = MakeFleetSpec(s);
  EXPECT_EQ(spec.receiver_ids, (std::vector<int>{10, 11, 12}));
  ASSERT_EQ(spec.launch_points.size(), 1U);
  const common::LatLon back =
      s.area.frame.ToGeodetic({spec.launch_points[0].x(), spec.launch_points[0].y()});
  EXPECT_NEAR(back.lat_deg, 46.191, 1e-9);
  EXPECT_NEAR(back.lon_deg, -74.609, 1e-9);
  EXPECT_EQ(spec.camera, s.fleet.camera);
  EXPECT_DOUBLE_EQ(spec.camera_pitch_deg, -60.0);
  EXPECT_DOUBLE_EQ(spec.altitude_m, 80.0);
  EXPECT_DOUBLE_EQ(spec.speed_mps, 12.0);
  EXPECT_DOUBLE_EQ(spec.endurance_s, 1200.0);
}

TEST(ParseScenario, LaunchIsAListOfSitesWithTheirDronesAndSwapS) {
  const Scenario s = Parse(kArea +
                           "fleet:\n  count: 3\n  swap_s: 120\n  launch:\n"
                           "    - {lat: 46.191, lon: -74.609, drones: 1}\n"
                           "    - {lat: 46.209, lon: -74.591, drones: 2}\n");
  ASSERT_EQ(s.fleet.launch_sites.size(), 2U);
  EXPECT_TRUE(s.fleet.launch_given);
  EXPECT_DOUBLE_EQ(s.fleet.launch.lat_deg, 46.191);
  EXPECT_DOUBLE_EQ(s.fleet.launch_sites[1].position.lat_deg, 46.209);
  EXPECT_EQ(s.fleet.launch_sites[1].drones, 2);
  EXPECT_DOUBLE_EQ(s.fleet.swap_s, 120.0);

  const planner::FleetSpec spec = MakeFleetSpec(s);
  ASSERT_EQ(spec.launch_points.size(), 2U);
  const common::LatLon second =
      s.area.frame.ToGeodetic({spec.launch_points[1].x(), spec.launch_points[1].y()});
  EXPECT_NEAR(second.lat_deg, 46.209, 1e-9);
  EXPECT_NEAR(second.lon_deg, -74.591, 1e-9);
  EXPECT_EQ(spec.site_drones, (std::vector<int>{1, 2}));
  EXPECT_DOUBLE_EQ(spec.swap_s, 120.0);

  // Without counts the planner shares the drones out.
  const Scenario shared = Parse(
      kArea +
      "fleet:\n  count: 2\n  launch: [{lat: 46.191, lon: -74.609}, {lat: 46.2, lon: -74.6}]\n");
  EXPECT_EQ(MakeFleetSpec(shared).launch_points.size(), 2U);
  EXPECT_TRUE(MakeFleetSpec(shared).site_drones.empty());
}

TEST(ParseScenario, ChaosFaultsReadTheirParametersAndDefaults) {
  const Scenario scenario =
      Parse(Minimal("faults:\n"
                    "  - {vehicle: 1, at_s: 10, kind: vehicle_reboot}\n"
                    "  - {vehicle: 2, at_s: 20, kind: vehicle_reboot, duration_s: 5}\n"
                    "  - {vehicle: 1, at_s: 30, kind: gps_loss, duration_s: 8}\n"
                    "  - {at_s: 40, kind: radio_burst, duration_s: 3, loss: 0.75}\n"
                    "  - {at_s: 50, kind: server_restart}\n"
                    "  - {at_s: 60, kind: server_restart, duration_s: 12}\n"));
  ASSERT_EQ(scenario.faults.size(), 6U);
  EXPECT_EQ(scenario.faults[0].kind, FaultKind::kVehicleReboot);
  EXPECT_DOUBLE_EQ(scenario.faults[0].duration_s, kDefaultRebootS);
  EXPECT_DOUBLE_EQ(scenario.faults[1].duration_s, 5.0);
  EXPECT_EQ(scenario.faults[2].kind, FaultKind::kGpsLoss);
  EXPECT_DOUBLE_EQ(scenario.faults[2].duration_s, 8.0);
  EXPECT_EQ(scenario.faults[3].kind, FaultKind::kRadioBurst);
  EXPECT_EQ(scenario.faults[3].vehicle, 0);
  EXPECT_DOUBLE_EQ(scenario.faults[3].loss, 0.75);
  EXPECT_DOUBLE_EQ(scenario.faults[3].duration_s, 3.0);
  EXPECT_DOUBLE_EQ(scenario.faults[4].duration_s, 0.0);  // a restart at once
  EXPECT_DOUBLE_EQ(scenario.faults[5].duration_s, 12.0);
}

TEST(ScenarioNames, RoundTripTheEnums) {
  EXPECT_EQ(ToString(FaultKind::kStreamCut), "stream_cut");
  EXPECT_EQ(ToString(FaultKind::kTotalLoss), "total_loss");
  EXPECT_EQ(ToString(FaultKind::kRadioSilent), "radio_silent");
  EXPECT_EQ(ToString(FaultKind::kServerRestart), "server_restart");
  EXPECT_EQ(ToString(FaultKind::kVehicleReboot), "vehicle_reboot");
  EXPECT_EQ(ToString(FaultKind::kGpsLoss), "gps_loss");
  EXPECT_EQ(ToString(FaultKind::kRadioBurst), "radio_burst");
  EXPECT_EQ(ToString(FaultSensor::kBattery), "battery");
  EXPECT_EQ(ToString(planner::PlannerKind::kLawnmower), "lawnmower");
  EXPECT_EQ(ToString(planner::PlannerKind::kOmpl), "ompl");
}

TEST(RepositoryScenarios, DemoLoadsWithFourDronesThreeFiresAndExpectations) {
  const Scenario s = LoadScenario(RepoRoot() / "scenarios" / "demo.yaml");
  EXPECT_EQ(s.name, "demo");
  EXPECT_EQ(s.fleet.count, 4);
  EXPECT_EQ(s.fires.size(), 3U);
  EXPECT_EQ(s.distractors.size(), 1U);
  EXPECT_GT(s.wind.speed_mps, 0.0);
  // Flown secured (ctest scenario.demo runs it whole): issue 17.
  EXPECT_EQ(s.radio.checksum, radio::ChecksumMode::kSecure);
  const double area_km2 = bg::area(s.area.area) / 1e6;
  EXPECT_GT(area_km2, 1.0);
  EXPECT_LT(area_km2, 5.0);
  EXPECT_TRUE(s.expect.all_fires_confirmed_within_s.has_value());
  EXPECT_TRUE(s.expect.no_collisions);
  EXPECT_TRUE(s.expect.min_coverage.has_value());
  // The distractor lies in the area, where the drones will see it.
  const common::EastNorth rock = s.area.frame.ToLocal(s.distractors[0].position);
  EXPECT_TRUE(bg::covered_by(planner::Point(rock.east_m, rock.north_m), s.area.area));
}

// The scenario tests ctest runs (scenarios/CMakeLists.txt) state what they test.
TEST(RepositoryScenarios, Swarm20FliesTwentyDronesOverALargerAreaKeepingApart) {
  const Scenario s = LoadScenario(RepoRoot() / "scenarios" / "swarm20.yaml");
  const Scenario demo = LoadScenario(RepoRoot() / "scenarios" / "demo.yaml");
  EXPECT_EQ(s.fleet.count, 20);
  EXPECT_GT(bg::area(s.area.area), 2.0 * bg::area(demo.area.area));
  EXPECT_TRUE(s.expect.no_collisions);
  ASSERT_TRUE(s.expect.min_separation_m.has_value());
  EXPECT_GE(*s.expect.min_separation_m, 2.0);  // sim2d's near-miss separation
}

TEST(RepositoryScenarios, CollideCrowdsTheStandsAndExpectsACollision) {
  const Scenario s = LoadScenario(RepoRoot() / "scenarios" / "collide.yaml");
  EXPECT_LT(s.fleet.stand_spacing_m, kDefaultStandSpacingM);
  EXPECT_FALSE(s.expect.no_collisions);
  ASSERT_TRUE(s.expect.min_collisions.has_value());
  EXPECT_GE(*s.expect.min_collisions, 1);
}

TEST(RepositoryScenarios, RadioLossLosesATenthAndNoReport) {
  const Scenario s = LoadScenario(RepoRoot() / "scenarios" / "radio_loss.yaml");
  EXPECT_DOUBLE_EQ(s.radio.loss, 0.1);
  EXPECT_FALSE(s.fires.empty());
  EXPECT_EQ(s.expect.max_reports_lost, 0);
  // ... also across two server restarts.
  ASSERT_EQ(s.faults.size(), 2U);
  for (const FaultSpec& fault : s.faults) {
    EXPECT_EQ(fault.kind, FaultKind::kServerRestart);
    EXPECT_EQ(fault.vehicle, 0);
  }
}

// Issue 19's chaos: every new fault kind at least once, and nothing may be lost.
TEST(RepositoryScenarios, ChaosHasEveryChaosFaultAndExpectsNothingLost) {
  const Scenario s = LoadScenario(RepoRoot() / "scenarios" / "chaos.yaml");
  for (const FaultKind kind : {FaultKind::kVehicleReboot, FaultKind::kGpsLoss,
                               FaultKind::kRadioBurst, FaultKind::kServerRestart}) {
    EXPECT_TRUE(std::ranges::any_of(s.faults, [&](const FaultSpec& f) { return f.kind == kind; }))
        << ToString(kind);
  }
  EXPECT_EQ(s.expect.max_reports_lost, 0);
  EXPECT_EQ(s.expect.max_false_tracks, 0);
  EXPECT_TRUE(s.expect.all_fires_confirmed_within_s.has_value());
  EXPECT_TRUE(s.expect.no_collisions);
  EXPECT_LE(s.fleet.count, 4);  // CI's budget: a small fleet
}

TEST(RepositoryScenarios, LostDroneLosesOneMidMissionAndStillCovers) {
  const Scenario s = LoadScenario(RepoRoot() / "scenarios" / "lost_drone.yaml");
  ASSERT_EQ(s.faults.size(), 1U);
  EXPECT_EQ(s.faults[0].kind, FaultKind::kTotalLoss);
  EXPECT_GT(s.faults[0].at_s, 0.0);
  ASSERT_TRUE(s.expect.min_coverage.has_value());
  EXPECT_GE(*s.expect.min_coverage, 0.98);
}

TEST(RepositoryScenarios, EveryScenarioFileLoads) {
  int loaded = 0;
  for (const fs::directory_entry& entry : fs::directory_iterator(RepoRoot() / "scenarios")) {
    if (entry.path().extension() != ".yaml") continue;
    SCOPED_TRACE(entry.path().string());
    EXPECT_NO_THROW(LoadScenario(entry.path()));
    ++loaded;
  }
  EXPECT_GE(loaded, 1);
}

// The documentation's full example (the ```yaml block under "## Full example" in
// docs/scenario.md, whose paths are relative to scenarios/) loads with every section.
TEST(RepositoryScenarios, DocumentationFullExampleLoads) {
  std::ifstream in(RepoRoot() / "docs" / "scenario.md");
  ASSERT_TRUE(in) << "docs/scenario.md";
  std::ostringstream text;
  text << in.rdbuf();
  const std::string doc = text.str();
  const std::size_t section = doc.find("## Full example");
  ASSERT_NE(section, std::string::npos);
  const std::size_t begin = doc.find("```yaml\n", section);
  ASSERT_NE(begin, std::string::npos);
  const std::size_t body = begin + std::string("```yaml\n").size();
  const std::size_t end = doc.find("```", body);
  ASSERT_NE(end, std::string::npos);
  const Scenario s =
      ParseScenario(doc.substr(body, end - body), "scenario.md", RepoRoot() / "scenarios");
  EXPECT_FALSE(s.fires.empty());
  EXPECT_TRUE(s.random_fires.has_value());
  EXPECT_FALSE(s.distractors.empty());
  EXPECT_FALSE(s.faults.empty());
  EXPECT_FALSE(s.area.no_fly.empty());
  EXPECT_TRUE(s.expect.max_false_tracks.has_value());
}

}  // namespace
}  // namespace fireswarm::run

namespace fireswarm::run {
namespace {

using ::testing::AllOf;

TEST(ParseScenario, RadioChannelsAndTheirOverrides) {
  EXPECT_EQ(Parse(Minimal()).radio.channels, 1);
  const Scenario s =
      Parse(Minimal("radio:\n  loss: 0.1\n  channels: 4\n  channel_overrides:\n"
                    "    - {channel: 2, baud: 19200, loss: 0.3, vehicles: [1]}\n"
                    "    - {channel: 3, turnaround_ms: 8}\n"));
  EXPECT_EQ(s.radio.channels, 4);
  ASSERT_EQ(s.radio.channel_overrides.size(), 2U);
  EXPECT_EQ(s.radio.channel_overrides[0].vehicles, std::vector<int>{1});
  EXPECT_EQ(s.radio.ChannelAt(0).baud, 57'600);
  EXPECT_DOUBLE_EQ(s.radio.ChannelAt(0).loss, 0.1);
  EXPECT_EQ(s.radio.ChannelAt(2).baud, 19'200);
  EXPECT_DOUBLE_EQ(s.radio.ChannelAt(2).loss, 0.3);
  EXPECT_DOUBLE_EQ(s.radio.ChannelAt(3).turnaround_ms, 8.0);
  EXPECT_DOUBLE_EQ(s.radio.ChannelAt(3).loss, 0.1);
}

TEST(ParseScenario, BadRadioChannelsNameTheFileLineAndKey) {
  EXPECT_THAT(ErrorOf(Minimal("radio: {channels: 17}\n")),
              AllOf(StartsWith("test.yaml:"), HasSubstr("radio.channels")));
  EXPECT_THAT(ErrorOf(Minimal("radio: {channels: 0}\n")), HasSubstr("radio.channels"));
  EXPECT_THAT(ErrorOf(Minimal("radio:\n  channels: 2\n  channel_overrides:\n    - {channel: 2}\n")),
              AllOf(StartsWith("test.yaml:"), HasSubstr("radio.channel_overrides[0].channel")));
  EXPECT_THAT(ErrorOf(Minimal("radio:\n  channels: 2\n  channel_overrides:\n    - {channel: 1}\n"
                              "    - {channel: 1, loss: 0.2}\n")),
              HasSubstr("channel 1 is overridden twice"));
  EXPECT_THAT(ErrorOf(Minimal("radio:\n  channels: 2\n  channel_overrides:\n"
                              "    - {channel: 0, vehicles: [1]}\n"
                              "    - {channel: 1, vehicles: [1]}\n")),
              HasSubstr("vehicle 1 is fixed on two channels"));
  EXPECT_THAT(ErrorOf(Minimal("radio:\n  channels: 2\n  channel_overrides:\n"
                              "    - {channel: 1, los: 0.2}\n")),
              HasSubstr("did you mean 'loss'?"));
}

}  // namespace
}  // namespace fireswarm::run
