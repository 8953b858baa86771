// Whole simulated missions where the server must keep a crowd apart: take-offs
// and landings of many drones at one site, every drone on one altitude (the
// tactical watch alone), an investigation across the others' lanes, and a
// lost-link return through the fleet.
#include <gtest/gtest.h>

#include <string>

#include "fireswarm/run/report_json.hpp"
#include "fireswarm/run/runner.hpp"
#include "small_area.hpp"

namespace fireswarm::run {
namespace {

using test::SmallArea;

constexpr double kLimitM = 10.0;  // separation.separation_m's default
// sim2d's near miss: closer than this two drones count as a near collision.
constexpr double kNearMissM = 2.0;
// The tactical watch's margin over the limit (docs/separation.md).
constexpr double kPositionNoiseM = 3.0;

Scenario Crowd(int count, const std::string& extra) {
  Scenario scenario = SmallArea(extra);
  scenario.fleet.count = count;
  scenario.duration_s = 900.0;
  return scenario;
}

// No collision, no near miss, and every conflict accounted for. The 10 m limit
// itself is the benchmark's figure (bench/separation_bench.cpp, README): at a
// crowded shared site it is not yet met everywhere (the closing note).
void ExpectKeptApart(const Report& report) {
  EXPECT_TRUE(report.collisions.empty()) << report.collisions.size() << " collision(s)";
  ASSERT_TRUE(report.min_separation_m.has_value());
  EXPECT_GE(*report.min_separation_m, kNearMissM);
  const SeparationOutcome& s = report.separation;
  EXPECT_LE(s.resolved + s.lost_separation, s.conflicts);
  EXPECT_EQ(s.lost.size(), s.lost_separation);
  for (const SeparationOutcome::Lost& lost : s.lost) {
    EXPECT_LT(lost.reported_min_m, kLimitM);
    EXPECT_LT(lost.predicted_m, kLimitM + kPositionNoiseM);  // it was a conflict
    EXPECT_GE(lost.time_to_closest_s, 0.0);
  }
}

TEST(RunnerSeparation, TwentyFourDronesTakeOffSearchAndLandAtOneSiteApart) {
  const RunResult result = RunScenario(Crowd(24, ""));
  EXPECT_NE(result.stop, StopReason::kDuration);
  ExpectKeptApart(result.report);
  EXPECT_FALSE(result.report.separation.rule.empty());
  // Every drone that flew is back on its stand; a drone the plan gave nothing
  // to search (24 is more than this small area needs) never took off.
  int flew = 0;
  for (const auto& [id, vehicle] : result.report.vehicles) {
    if (vehicle.airborne_s > 0.0) {
      ++flew;
      EXPECT_EQ(vehicle.final_state, "landed") << "drone " << id;
    } else {
      EXPECT_EQ(vehicle.final_state, "idle") << "drone " << id;
      EXPECT_EQ(vehicle.distance_m, 0.0) << "drone " << id;
    }
  }
  EXPECT_GE(flew, 16);
}

TEST(RunnerSeparation, OnOneAltitudeTheTacticalWatchAloneKeepsACrowdApart) {
  // Every drone at the fleet's altitude: only the orders keep them apart. The
  // same missions without orders come closer than the limit.
  const std::string one_layer = "separation: {layers: false}\n";
  const Report resolved = RunScenario(Crowd(12, one_layer)).report;
  ExpectKeptApart(resolved);
  EXPECT_GE(resolved.separation.conflicts, 1U);
  EXPECT_GE(resolved.separation.orders, 1U);
  const Report unresolved =
      RunScenario(Crowd(12, "separation: {layers: false, resolve: false}\n")).report;
  EXPECT_EQ(unresolved.separation.orders, 0U);
  EXPECT_GE(unresolved.separation.conflicts, 1U);
  ASSERT_TRUE(unresolved.min_separation_m.has_value());
  EXPECT_LT(*unresolved.min_separation_m, kLimitM);
  // The orders turn most conflicts into passes at a distance.
  EXPECT_GT(*resolved.min_separation_m, *unresolved.min_separation_m);
  EXPECT_LT(resolved.separation.lost_separation, unresolved.separation.lost_separation);
  // Each lost one says what was predicted at detection, and how soon.
  ASSERT_FALSE(unresolved.separation.lost.empty());
  for (const SeparationOutcome::Lost& lost : unresolved.separation.lost) {
    EXPECT_LT(lost.predicted_m, kLimitM + kPositionNoiseM);
    EXPECT_GE(lost.time_to_closest_s, 0.0);
    EXPECT_LE(lost.time_to_closest_s, 30.0);  // separation.horizon_s's default
  }
  // ... and so does the report's JSON.
  const auto json_lost = ToJson(unresolved)["separation"]["lost"];
  ASSERT_EQ(json_lost.size(), unresolved.separation.lost.size());
  EXPECT_DOUBLE_EQ(json_lost[0]["predicted_m"].get<double>(),
                   unresolved.separation.lost[0].predicted_m);
  EXPECT_DOUBLE_EQ(json_lost[0]["time_to_closest_s"].get<double>(),
                   unresolved.separation.lost[0].time_to_closest_s);
}

TEST(RunnerSeparation, AnInvestigationAcrossTheOthersLanesKeepsItsDistance) {
  // A fire at the area's far east edge: the drone that confirms it flies across
  // the lanes of the drones between.
  Scenario scenario = Crowd(8, "fires:\n  - {lat: 45.0022, lon: 7.0095}\n");
  const Report report = RunScenario(scenario).report;
  EXPECT_FALSE(report.investigations.empty());
  ExpectKeptApart(report);
}

TEST(RunnerSeparation, ALostLinkReturnThroughTheFleetKeepsItsDistance) {
  Scenario scenario = Crowd(8, "");
  FaultSpec silent;
  silent.vehicle = 8;
  silent.at_s = 120.0;
  silent.kind = FaultKind::kRadioSilent;
  scenario.faults.push_back(silent);
  const Report report = RunScenario(scenario).report;
  EXPECT_EQ(report.vehicles.at(8).final_state, "landed");
  ExpectKeptApart(report);
}

}  // namespace
}  // namespace fireswarm::run
