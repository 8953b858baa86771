// A patrol, whole: the server flies the same plan as mission after mission
// (scenario key `patrol`), the vehicles land, get a fresh pack and take each
// round's mission under new IDs, and a fire that starts after the first round is
// found by a later one. Also across a server restart from the journal.
#include <gtest/gtest.h>

#include <cstdio>
#include <set>
#include <string>

#include "fireswarm/run/runner.hpp"
#include "fireswarm/run/scenario.hpp"
#include "fireswarm/server/mission_manager.hpp"
#include "fireswarm/server/server.hpp"
#include "run/small_area.hpp"

namespace fireswarm::run {
namespace {

// A round of the small area takes a few minutes; the fire starts after the
// first round has flown over its place.
// The runner tests' small area (run/small_area.hpp) for 2000 s: a round takes
// about 520 s, and the crew's swap 60 s after it.
constexpr const char* kPatrol = R"(name: patrol
seed: 3
duration_s: 2000
area:
  polygon: [[7.0, 45.0], [7.010146, 45.0], [7.010146, 45.0045], [7.0, 45.0045]]
fleet:
  count: 2
  launch: {lat: 44.9995, lon: 7.005}
  swap_s: 60
patrol: {every_s: 400}
fires:
  - {lat: 45.00230, lon: 7.00480, start_s: 450}
expect:
  all_fires_confirmed_within_s: 700
  no_collisions: true
  max_reports_lost: 0
)";

struct PatrolRun {
  RunResult result;
  std::set<std::uint16_t> first_mission_ids;  // each round's, as the server held it
};

PatrolRun RunPatrol(const std::string& extra) {
  PatrolRun out;
  RunOptions options;
  options.on_step = [&out](double, const server::Server& server) {
    if (const server::MissionManager* mission = server.mission()) {
      out.first_mission_ids.insert(mission->mission_of(1).mission_id);
    }
  };
  out.result =
      RunScenario(ParseScenario(std::string(kPatrol) + extra, "patrol.yaml", "."), options);
  return out;
}

void ExpectRounds(const PatrolRun& run) {
  const RunResult& result = run.result;
  const Report& report = result.report;
  std::printf("%d rounds, %.0f sim s in %.1f wall s, mission %s\n", result.missions,
              report.sim_seconds, report.wall_seconds, result.mission_state.c_str());
  EXPECT_EQ(result.stop, StopReason::kDuration) << "a patrol ends at its duration only";
  // Rounds at 0 s and about 580, 1160 and 1740 s: each once the one before is
  // over and the packs are fresh, later than every_s.
  EXPECT_EQ(result.missions, 4);
  EXPECT_EQ(run.first_mission_ids.size(), 4U) << "each round its own mission IDs";
  for (const ExpectOutcome& e : report.expect) EXPECT_TRUE(e.passed) << e.name << ": " << e.detail;
  for (const auto& [id, vehicle] : report.vehicles) {
    // Every round's sorties flown but maybe the last round's.
    EXPECT_GE(vehicle.sorties_flown, 3 * vehicle.sorties_planned / 4) << "vehicle " << id;
    EXPECT_GE(vehicle.battery_swaps, 3) << "vehicle " << id;
  }
}

TEST(RunScenarioPatrol, FliesRoundAfterRoundAndFindsAFireThatStartedAfterTheFirst) {
  const PatrolRun run = RunPatrol("");
  ExpectRounds(run);
  EXPECT_EQ(run.result.server_restarts, 0);
}

TEST(RunScenarioPatrol, ARestartedServerGoesOnWithTheRoundItWasIn) {
  // During the first round's search, and between the second and the third
  // (the drones on their stands for the swap).
  const PatrolRun run = RunPatrol(R"(faults:
  - {at_s: 300, kind: server_restart}
  - {at_s: 1130, kind: server_restart}
)");
  ExpectRounds(run);
  EXPECT_EQ(run.result.server_restarts, 2);
}

TEST(RunScenarioPatrol, EveryIsRequiredAndAtLeastAMinute) {
  EXPECT_THROW(test::SmallArea("patrol: {}\n"), ScenarioError);
  try {
    test::SmallArea("patrol: {every_s: 30}\n");
    FAIL() << "every_s 30 was accepted";
  } catch (const ScenarioError& e) {
    EXPECT_NE(std::string(e.what()).find("patrol.every_s"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace fireswarm::run
