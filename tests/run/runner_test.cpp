// Whole missions in lockstep: the real planner, server, vehicles, radio channel
// and simulator, scored against truth. Scenarios are small (< 1 km^2, two drones)
// so the suite stays fast under ASan on two cores.
#include "fireswarm/run/runner.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <type_traits>
#include <utility>

#include "fireswarm/common/local_frame.hpp"
#include "fireswarm/run/report_json.hpp"
#include "fireswarm/run/scenario.hpp"
#include "fireswarm/server/lcm_bridge.hpp"
#include "scoring.hpp"
#include "small_area.hpp"

namespace fireswarm::run {
namespace {

// 800 m x 500 m of forest, two drones with the seed's camera, one fire near the
// middle, every expectation stated.
constexpr const char* kSmallFire = R"(
name: small_fire
seed: 7
duration_s: 900
area:
  polygon: [[7.0, 45.0], [7.010146, 45.0], [7.010146, 45.0045], [7.0, 45.0045]]
fleet:
  count: 2
  launch: {lat: 44.9995, lon: 7.005}
  camera: seed
  altitude_m: 60
  speed_mps: 10
fires:
  - {lat: 45.00230, lon: 7.00480, start_s: 0}
expect:
  all_fires_confirmed_within_s: 600
  max_fused_error_m: 10
  no_collisions: true
  min_coverage: 0.5
  max_false_tracks: 0
)";

Scenario SmallFire() {
  return ParseScenario(kSmallFire, "small_fire.yaml", ".");
}

// The server at the small fire run's last step (what it publishes on LCM).
struct ServerAtEnd {
  double coverage_fraction = -1.0;  ///< mission_status_t's
  std::size_t searchable_cells = 0;
  std::size_t seen_cells = 0;
  std::map<double, double> coverage_at;  ///< simulated s -> mission_status_t's coverage
};
ServerAtEnd& SmallFireServer() {
  static ServerAtEnd end;
  return end;
}

// Runs once per process: the small scenario is the expensive part of the suite.
const RunResult& SmallFireRun() {
  static const RunResult result = [] {
    RunOptions options;
    options.on_step = [](double t_s, const server::Server& server) {
      ServerAtEnd& end = SmallFireServer();
      end.coverage_fraction = server::ToMissionStatus(server, t_s, 0).coverage_fraction;
      end.coverage_at[t_s] = end.coverage_fraction;
      if (const planner::CoverageGrid* grid = server.coverage()) {
        end.searchable_cells = grid->searchable_cells();
        end.seen_cells = grid->seen_cells();
      }
    };
    return RunScenario(SmallFire(), options);
  }();
  return result;
}

void PrintFigures(const RunResult& result) {
  const Report& report = result.report;
  std::printf("stop %s, mission %s, %.1f sim s in %.2f wall s (x%.1f), coverage %.3f\n",
              ToString(result.stop), result.mission_state.c_str(), report.sim_seconds,
              report.wall_seconds, report.real_time_factor, report.coverage);
  for (const FireOutcome& fire : report.fires) {
    std::printf("fire: error %.2f m, first report %.1f s, confirmed %.1f s\n",
                fire.error_m.value_or(-1.0), fire.first_report_s.value_or(-1.0),
                fire.confirmed_s.value_or(-1.0));
  }
}

TEST(RunScenario, SmallFireIsConfirmedAccurately) {
  const RunResult& result = SmallFireRun();
  PrintFigures(result);
  const Report& report = result.report;
  ASSERT_EQ(report.fires.size(), 1U);
  const FireOutcome& fire = report.fires.front();
  ASSERT_TRUE(fire.confirmed_s.has_value()) << ToJson(report).dump(2);
  ASSERT_TRUE(fire.error_m.has_value());
  EXPECT_LT(*fire.error_m, 10.0);
  // The truth is where the fire burns: the centre of its 5 m cell (it has not
  // spread by then), not the scenario's point, which lies in that cell.
  const common::LocalFrame frame(fire.ignition);
  const common::EastNorth truth = frame.ToLocal(fire.truth);
  EXPECT_GT(std::hypot(truth.east_m, truth.north_m), 0.01);
  EXPECT_LE(std::hypot(truth.east_m, truth.north_m), 2.5 * std::sqrt(2.0) + 1e-6);
  ASSERT_TRUE(fire.ignition_error_m.has_value());
  ASSERT_TRUE(fire.first_report_s.has_value());
  EXPECT_LE(*fire.first_report_s, *fire.confirmed_s);
  EXPECT_FALSE(fire.vehicles.empty());
  EXPECT_TRUE(report.false_tracks.empty());
  EXPECT_TRUE(report.collisions.empty());
  EXPECT_GT(report.coverage, 0.5);
  EXPECT_GT(report.sim_seconds, 0.0);
  EXPECT_GT(report.real_time_factor, 0.0);
  EXPECT_TRUE(report.AllExpectationsHold()) << ToJson(report).dump(2);
}

TEST(RunScenario, ReportsRadioAndVehicles) {
  const Report& report = SmallFireRun().report;
  EXPECT_GT(report.radio.busy_fraction, 0.0);
  EXPECT_LT(report.radio.busy_fraction, 1.0);
  EXPECT_EQ(report.radio.telemetry_age_p50_p99_s.size(), 2U);
  for (const auto& [id, ages] : report.radio.telemetry_age_p50_p99_s) {
    EXPECT_LE(ages.first, ages.second) << "vehicle " << id;
    EXPECT_LT(ages.second, 5.0) << "vehicle " << id;
  }
  EXPECT_GT(report.radio.reports_received, 0U);
  ASSERT_TRUE(report.radio.report_latency_p50_s.has_value());
  EXPECT_LT(*report.radio.report_latency_p50_s, 5.0);
  ASSERT_EQ(report.vehicles.size(), 2U);
  for (const auto& [id, vehicle] : report.vehicles) {
    EXPECT_GT(vehicle.distance_m, 500.0) << "vehicle " << id;
    EXPECT_GT(vehicle.battery_used, 0.0) << "vehicle " << id;
    EXPECT_FALSE(vehicle.final_state.empty());
  }
  ASSERT_TRUE(report.min_separation_m.has_value());
  EXPECT_GT(*report.min_separation_m, 1.0);
  ASSERT_GE(report.coverage_over_time.size(), 2U);
  EXPECT_DOUBLE_EQ(report.coverage_over_time.back().second, report.coverage);
}

TEST(RunScenario, ReportJsonHasTheContractKeys) {
  const nlohmann::ordered_json j = ToJson(SmallFireRun().report);
  std::vector<std::string> keys;
  for (const auto& item : j.items()) keys.push_back(item.key());
  EXPECT_EQ(keys, (std::vector<std::string>{
                      "fires", "false_tracks", "tracks", "investigations", "coverage",
                      "coverage_over_time", "collisions", "min_separation_m", "separation", "radio",
                      "vehicles", "sim_seconds", "wall_seconds", "real_time_factor", "expect"}));
  std::vector<std::string> fire_keys;
  for (const auto& item : j["fires"][0].items()) fire_keys.push_back(item.key());
  EXPECT_EQ(fire_keys,
            (std::vector<std::string>{"true_lat", "true_lon", "fused_lat", "fused_lon", "error_m",
                                      "first_report_s", "confirmed_s", "vehicles", "ignition_lat",
                                      "ignition_lon", "ignition_error_m", "start_s"}));
  for (const char* key :
       {"busy_fraction", "telemetry_age_s", "retries", "report_latency_s", "reports_lost"}) {
    EXPECT_TRUE(j["radio"].contains(key)) << key;
  }
  for (const char* key : {"rule", "separation_m", "conflicts", "orders", "resolved",
                          "lost_separation", "closest", "lost"}) {
    EXPECT_TRUE(j["separation"].contains(key)) << key;
  }
  for (const auto& item : j["vehicles"].items()) {
    EXPECT_TRUE(item.value().contains("distance_m"));
    EXPECT_TRUE(item.value().contains("battery_used"));
    EXPECT_TRUE(item.value().contains("final_state"));
  }
  ASSERT_EQ(j["expect"].size(), 5U);
  for (const auto& e : j["expect"]) EXPECT_EQ(e["verdict"], "pass") << e.dump();
  // Every track the server ended with, the confirmed fire's among them.
  ASSERT_FALSE(j["tracks"].empty());
  EXPECT_EQ(j["tracks"][0]["status"], "confirmed");
  EXPECT_GE(j["tracks"][0]["reports"].get<int>(), 2);
}

// Issue 15: the server's LCM coverage said 0.984 where the report said 1.0 (it
// counted waypoints passed). Both now mark one planner::CoverageGrid over the
// same searchable cells, the report from the truth every 0.5 s, the server from
// telemetry: they agree within a percent at the end. Along the run the server is
// a little behind: telemetry comes once a second and a radio turn late, while
// two drones sweep ~1,800 m^2/s of this 400,000 m^2 (0.46 % a second); the
// largest gap seen was 1.1 % (seed 7).
TEST(RunScenario, TheServersCoverageIsTheReports) {
  constexpr double kLagTolerance = 0.02;
  static_assert(std::is_same_v<decltype(std::declval<const server::Server&>().coverage()),
                               const planner::CoverageGrid*>);
  static_assert(std::is_same_v<decltype(std::declval<const internal::Scorer&>().coverage_grid()),
                               const planner::CoverageGrid&>);
  const Report& report = SmallFireRun().report;
  const ServerAtEnd& server = SmallFireServer();
  std::printf("coverage: report %.4f, server %.4f (%zu of %zu cells)\n", report.coverage,
              server.coverage_fraction, server.seen_cells, server.searchable_cells);
  EXPECT_NEAR(server.coverage_fraction, report.coverage, 0.01);
  EXPECT_GT(server.coverage_fraction, 0.5);
  const Scenario scenario = SmallFire();
  const internal::Scorer scorer(scenario, {});
  EXPECT_EQ(server.searchable_cells, scorer.coverage_grid().searchable_cells());
  EXPECT_DOUBLE_EQ(server.coverage_fraction, static_cast<double>(server.seen_cells) /
                                                 static_cast<double>(server.searchable_cells));
  double worst = 0.0;
  for (const auto& [t_s, fraction] : report.coverage_over_time) {
    const auto at = server.coverage_at.find(t_s);
    if (at == server.coverage_at.end()) continue;  // the end's sample, after the last step
    EXPECT_NEAR(at->second, fraction, kLagTolerance) << "at " << t_s << " s";
    worst = std::max(worst, std::abs(at->second - fraction));
  }
  std::printf("coverage over time: largest difference %.4f over %zu samples\n", worst,
              report.coverage_over_time.size());
  EXPECT_GT(report.coverage_over_time.size(), 10U);
}

// A shorter run of the same scenario, twice: identical reports apart from the
// wall-clock fields, and the same simulator state.
TEST(RunScenario, SameSeedSameReport) {
  Scenario scenario = SmallFire();
  scenario.duration_s = 120.0;
  const RunResult first = RunScenario(scenario);
  const RunResult second = RunScenario(scenario);
  nlohmann::ordered_json a = ToJson(first.report);
  nlohmann::ordered_json b = ToJson(second.report);
  for (const char* key : {"wall_seconds", "real_time_factor"}) {
    a.erase(key);
    b.erase(key);
  }
  EXPECT_EQ(a.dump(), b.dump());
  EXPECT_EQ(first.state_hash, second.state_hash);
  EXPECT_EQ(first.stop, StopReason::kDuration);
  EXPECT_DOUBLE_EQ(first.report.sim_seconds, 120.0);
}

TEST(RunScenario, FailedExpectationIsReported) {
  Scenario scenario = SmallFire();
  scenario.duration_s = 30.0;  // far too short to search anything
  scenario.expect = Expectations{};
  scenario.expect.min_coverage = 0.9;
  scenario.expect.no_collisions = true;
  const Report report = RunScenario(scenario).report;
  EXPECT_FALSE(report.AllExpectationsHold());
  ASSERT_EQ(report.expect.size(), 2U);
  EXPECT_EQ(report.expect[0].name, "no_collisions");
  EXPECT_TRUE(report.expect[0].passed);
  EXPECT_EQ(report.expect[1].name, "min_coverage");
  EXPECT_FALSE(report.expect[1].passed);
  EXPECT_DOUBLE_EQ(report.expect[1].limit, 0.9);
  EXPECT_LT(report.expect[1].value, 0.9);
  EXPECT_FALSE(report.expect[1].detail.empty());
}

using test::SmallArea;

std::vector<std::pair<double, double>> TruePositions(const Report& report) {
  std::vector<std::pair<double, double>> out;
  for (const FireOutcome& fire : report.fires)
    out.emplace_back(fire.truth.lat_deg, fire.truth.lon_deg);
  return out;
}

TEST(RunScenario, RandomFiresLieInsideTheAreaAndFollowTheirSeed) {
  Scenario scenario = SmallArea("random_fires: {count: 4, seed: 5}\n");
  scenario.duration_s = 1.0;
  const Report a = RunScenario(scenario).report;
  const Report b = RunScenario(scenario).report;
  scenario.random_fires->seed = 6;
  const Report c = RunScenario(scenario).report;
  ASSERT_EQ(a.fires.size(), 4U);
  for (const FireOutcome& fire : a.fires) {
    EXPECT_GT(fire.truth.lat_deg, 45.0);
    EXPECT_LT(fire.truth.lat_deg, 45.0045);
    EXPECT_GT(fire.truth.lon_deg, 7.0);
    EXPECT_LT(fire.truth.lon_deg, 7.010146);
    EXPECT_FALSE(fire.confirmed_s.has_value());
    EXPECT_FALSE(fire.error_m.has_value());
  }
  EXPECT_EQ(TruePositions(a), TruePositions(b));
  EXPECT_NE(TruePositions(a), TruePositions(c));
}

// A vehicle whose radio is silent from the start never hears its mission: it stays
// on the ground while the other one flies.
TEST(RunScenario, RadioSilentVehicleNeitherHearsNorIsHeard) {
  const Report report =
      RunScenario(SmallArea("faults:\n  - {vehicle: 2, at_s: 0, kind: radio_silent}\n")).report;
  ASSERT_EQ(report.vehicles.size(), 2U);
  EXPECT_EQ(report.vehicles.at(2).final_state, "idle");
  EXPECT_LT(report.vehicles.at(2).distance_m, 1.0);
  EXPECT_GT(report.vehicles.at(1).distance_m, 100.0);
  EXPECT_EQ(report.radio.telemetry_age_p50_p99_s.count(2), 0U);
  EXPECT_EQ(report.radio.telemetry_age_p50_p99_s.count(1), 1U);
}

// The server dies 20 times in the mission's first seconds, while it uploads the
// missions (its radio busy most of the time), and a new one takes over from its
// journal each time: each restart waits for the server's radio to fall quiet
// (one started inside the old server's transmission threw), and the drones still
// get their missions and fly.
TEST(RunScenario, ServerRestartFaultsReplaceTheServerBetweenItsTransmissions) {
  std::string faults = "faults:\n";
  for (int k = 0; k < 20; ++k) {
    faults += "  - {at_s: " + std::to_string(1.0 + 0.25 * k) + ", kind: server_restart}\n";
  }
  const RunResult result = RunScenario(SmallArea(faults));
  EXPECT_EQ(result.server_restarts, 20);
  ASSERT_EQ(result.report.vehicles.size(), 2U);
  EXPECT_GT(result.report.vehicles.at(1).distance_m, 100.0);
  EXPECT_GT(result.report.vehicles.at(2).distance_m, 100.0);
  EXPECT_EQ(result.report.radio.reports_lost, 0U);
}

// The separation, lost-report and collision expectations judged on a real run:
// two drones a minute into their mission are far closer than a kilometre, lose
// no report (there is no fire) and collide nowhere.
TEST(RunScenario, SeparationReportsLostAndCollisionExpectationsAreJudged) {
  Scenario scenario = SmallArea("");
  scenario.expect.min_separation_m = 1'000.0;
  scenario.expect.max_reports_lost = 0;
  scenario.expect.min_collisions = 1;
  const Report report = RunScenario(scenario).report;
  ASSERT_TRUE(report.min_separation_m.has_value());
  ASSERT_EQ(report.expect.size(), 3U);
  const ExpectOutcome& separation = report.expect[0];
  EXPECT_EQ(separation.name, "min_separation_m");
  EXPECT_FALSE(separation.passed);
  EXPECT_DOUBLE_EQ(separation.value, *report.min_separation_m);
  EXPECT_DOUBLE_EQ(separation.limit, 1'000.0);
  EXPECT_THAT(separation.detail, ::testing::HasSubstr("at least 1000 m required"));
  const ExpectOutcome& lost = report.expect[1];
  EXPECT_EQ(lost.name, "max_reports_lost");
  EXPECT_TRUE(lost.passed);
  EXPECT_DOUBLE_EQ(lost.value, 0.0);
  EXPECT_TRUE(lost.detail.empty());
  const ExpectOutcome& collisions = report.expect[2];
  EXPECT_EQ(collisions.name, "min_collisions");
  EXPECT_FALSE(collisions.passed);
  EXPECT_DOUBLE_EQ(collisions.value, 0.0);
  EXPECT_DOUBLE_EQ(collisions.limit, 1.0);
  EXPECT_EQ(collisions.detail, "0 collision(s) reported, at least 1 expected");
  EXPECT_FALSE(report.AllExpectationsHold());
}

// Horizontal distance between the first truth positions (the stands) of two vehicles, m.
double StandDistanceM(const Scenario& scenario, const Report& report, int a, int b) {
  const common::EastNorth stand_a =
      scenario.area.frame.ToLocal(report.vehicles.at(a).track.front());
  const common::EastNorth stand_b =
      scenario.area.frame.ToLocal(report.vehicles.at(b).track.front());
  return std::hypot(stand_a.east_m - stand_b.east_m, stand_a.north_m - stand_b.north_m);
}

TEST(RunScenario, StandsKeepTheFleetsStandSpacing) {
  // Two stands sit exactly the spacing apart, and Box2D keeps positions in floats.
  constexpr double kFloatToleranceM = 1e-3;
  Scenario scenario = SmallArea("");
  scenario.duration_s = 1.0;
  const Report by_default = RunScenario(scenario).report;
  EXPECT_GE(StandDistanceM(scenario, by_default, 1, 2), kDefaultStandSpacingM - kFloatToleranceM);
  scenario = SmallArea("");
  scenario.duration_s = 1.0;
  scenario.fleet.stand_spacing_m = 30.0;
  const Report wide = RunScenario(scenario).report;
  EXPECT_GE(StandDistanceM(scenario, wide, 1, 2), 30.0 - kFloatToleranceM);
}

TEST(RunScenario, LostVehicleEndsLost) {
  Scenario scenario = SmallArea("faults:\n  - {vehicle: 2, at_s: 20, kind: total_loss}\n");
  scenario.duration_s = 40.0;
  const Report report = RunScenario(scenario).report;
  EXPECT_EQ(report.vehicles.at(2).final_state, "lost");
  EXPECT_NE(report.vehicles.at(1).final_state, "lost");
}

}  // namespace
}  // namespace fireswarm::run
