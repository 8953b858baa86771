// Sorties that really happen, whole: the real planner splits each drone's work
// into sorties (short endurance), the server uploads and starts them one at a
// time, the vehicles land at their stands, sim2d's ground crew swaps the pack,
// and the next sortie goes up once the vehicle reports a fresh pack. Also a
// server restarted from its journal between two sorties.
#include <gtest/gtest.h>

#include <cstdio>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "fireswarm/run/runner.hpp"
#include "fireswarm/run/scenario.hpp"
#include "fireswarm/server/mission_manager.hpp"
#include "fireswarm/server/server.hpp"

namespace fireswarm::run {
namespace {

// The runner tests' 800 m x 500 m area with a 280 s endurance (200 s at altitude
// after the climb and descent): the planner needs three sorties per drone; a fire
// to find on the way.
constexpr double kSortieSwapS = 120.0;
constexpr const char* kSortieScenario = R"(
name: sorties
seed: 5
duration_s: 2400
area:
  polygon: [[7.0, 45.0], [7.010146, 45.0], [7.010146, 45.0045], [7.0, 45.0045]]
fleet:
  count: 2
  launch: {lat: 44.9995, lon: 7.005}
  endurance_s: 280
  swap_s: 120
fires:
  - {lat: 45.00230, lon: 7.00480, start_s: 0}
expect:
  min_coverage: 0.99
  all_fires_confirmed_within_s: 1500
  no_collisions: true
)";

// One drone's phase changes as the server saw them after each step.
struct PhaseStep {
  double t_s = 0.0;
  server::DronePhase phase = server::DronePhase::kUploading;
  std::size_t sorties_flown = 0;
};
using PhaseLog = std::map<std::uint8_t, std::vector<PhaseStep>>;

void LogPhases(double t_s, const server::Server& server, PhaseLog& log) {
  const server::MissionManager* mission = server.mission();
  if (mission == nullptr) return;
  for (const std::uint8_t id : mission->vehicles()) {
    const server::DroneProgress& progress = mission->progress(id);
    std::vector<PhaseStep>& steps = log[id];
    if (steps.empty() || steps.back().phase != progress.phase ||
        steps.back().sorties_flown != progress.sorties_flown) {
      steps.push_back({t_s, progress.phase, progress.sorties_flown});
    }
  }
}

struct SortieRun {
  RunResult result;
  PhaseLog phases;
};

const SortieRun& UninterruptedSortieRun() {
  static const SortieRun run = [] {
    SortieRun out;
    RunOptions options;
    options.on_step = [&out](double t_s, const server::Server& server) {
      LogPhases(t_s, server, out.phases);
    };
    out.result = RunScenario(ParseScenario(kSortieScenario, "sorties.yaml", "."), options);
    return out;
  }();
  return run;
}

void PrintSortieFigures(const RunResult& result) {
  const Report& report = result.report;
  std::printf("stop %s, mission %s, %.1f sim s in %.2f wall s (x%.0f), coverage %.4f\n",
              ToString(result.stop), result.mission_state.c_str(), report.sim_seconds,
              report.wall_seconds, report.real_time_factor, report.coverage);
  for (const auto& [id, vehicle] : report.vehicles) {
    std::printf("vehicle %d: sorties planned %d flown %d, swaps %d, %s\n", id,
                vehicle.sorties_planned, vehicle.sorties_flown, vehicle.battery_swaps,
                vehicle.final_state.c_str());
  }
}

TEST(RunScenarioSorties, DronesLandSwapAndFlyTheNextSortieUntilTheAreaIsCovered) {
  const SortieRun& run = UninterruptedSortieRun();
  const RunResult& result = run.result;
  PrintSortieFigures(result);
  EXPECT_EQ(result.stop, StopReason::kMissionComplete);
  EXPECT_EQ(result.mission_state, "complete");
  EXPECT_GE(result.report.coverage, 0.99);
  for (const ExpectOutcome& e : result.report.expect) EXPECT_TRUE(e.passed) << e.detail;

  ASSERT_EQ(result.report.vehicles.size(), 2U);
  for (const auto& [id, vehicle] : result.report.vehicles) {
    EXPECT_GE(vehicle.sorties_planned, 2) << "vehicle " << id << ": the scenario needs sorties";
    // Every planned sortie flown, none twice (a sortie cut short would add one).
    EXPECT_EQ(vehicle.sorties_flown, vehicle.sorties_planned) << "vehicle " << id;
    // A fresh pack for each sortie after the first (and after the last landing,
    // when the other drone was still flying).
    EXPECT_GE(vehicle.battery_swaps, vehicle.sorties_planned - 1) << "vehicle " << id;
    EXPECT_EQ(vehicle.final_state, "landed");
  }

  // Each drone: flying -> swapping (landed) -> uploading the next sortie, the
  // upload only once the crew's swap is done, then flying again; done after
  // its last sortie.
  for (const auto& [id, steps] : run.phases) {
    const int planned = result.report.vehicles.at(id).sorties_planned;
    int swaps_seen = 0;
    for (std::size_t i = 1; i + 1 < steps.size(); ++i) {
      if (steps[i].phase != server::DronePhase::kSwapping) continue;
      ++swaps_seen;
      EXPECT_EQ(steps[i - 1].phase, server::DronePhase::kFlying) << "vehicle " << int{id};
      EXPECT_EQ(steps[i + 1].phase, server::DronePhase::kUploading) << "vehicle " << int{id};
      EXPECT_EQ(steps[i].sorties_flown, static_cast<std::size_t>(swaps_seen));
      // The vehicle reports landed a few seconds after touching down (its landing
      // detector); the crew's swap counts from the touchdown.
      const double waited_s = steps[i + 1].t_s - steps[i].t_s;
      EXPECT_GE(waited_s, kSortieSwapS - 10.0) << "vehicle " << int{id};
      EXPECT_LE(waited_s, kSortieSwapS + 10.0) << "vehicle " << int{id};
    }
    EXPECT_EQ(swaps_seen, planned - 1) << "vehicle " << int{id};
    EXPECT_EQ(steps.back().phase, server::DronePhase::kDone) << "vehicle " << int{id};
  }
}

TEST(RunScenarioSorties, ARestartedServerResumesAtTheSortieItWasIn) {
  // The server is restarted from its journal while a drone waits for its pack
  // after its second sortie (of three).
  std::uint8_t waiting = 0;
  bool restarted = false;
  std::optional<server::DroneProgress> resumed;
  RunOptions options;
  options.restart_server_when = [&](double, const server::Server& server) {
    const server::MissionManager* mission = server.mission();
    for (const std::uint8_t id : mission->vehicles()) {
      const server::DroneProgress& progress = mission->progress(id);
      if (progress.phase == server::DronePhase::kSwapping && progress.sorties_flown == 2) {
        waiting = id;
        restarted = true;
        return true;
      }
    }
    return false;
  };
  options.on_step = [&](double, const server::Server& server) {
    if (restarted && !resumed) resumed = server.mission()->progress(waiting);
  };
  const RunResult result =
      RunScenario(ParseScenario(kSortieScenario, "sorties.yaml", "."), options);
  PrintSortieFigures(result);
  ASSERT_EQ(result.server_restarts, 1);
  ASSERT_TRUE(resumed.has_value());
  // The new server knows the drone flew its second sortie and waits for its pack:
  // it neither uploads an earlier sortie again nor skips the swap.
  EXPECT_EQ(resumed->phase, server::DronePhase::kSwapping);
  EXPECT_EQ(resumed->sortie, 1U);
  EXPECT_EQ(resumed->sorties_flown, 2U);

  EXPECT_EQ(result.stop, StopReason::kMissionComplete);
  EXPECT_GE(result.report.coverage, 0.99);
  // Sortie for sortie what the uninterrupted run flew.
  const RunResult& reference = UninterruptedSortieRun().result;
  for (const auto& [id, vehicle] : result.report.vehicles) {
    EXPECT_EQ(vehicle.sorties_flown, vehicle.sorties_planned) << "vehicle " << id;
    EXPECT_EQ(vehicle.sorties_flown, reference.report.vehicles.at(id).sorties_flown);
    EXPECT_EQ(vehicle.battery_swaps, reference.report.vehicles.at(id).battery_swaps);
  }
}

// Three drones in short sorties (how many each flies is the planner's business);
// vehicle 2 is gone for good at 330 s, while it waits on the ground for its pack
// after its first sortie (the test checks that premise).
constexpr const char* kLostBetweenSorties = R"(
name: sorties_lost
seed: 5
duration_s: 2400
area:
  polygon: [[7.0, 45.0], [7.010146, 45.0], [7.010146, 45.0045], [7.0, 45.0045]]
fleet:
  count: 3
  launch: {lat: 44.9995, lon: 7.005}
  endurance_s: 280
  swap_s: 120
faults:
  - {vehicle: 2, at_s: 330, kind: total_loss}
)";

TEST(RunScenarioSorties, ADroneLostBetweenSortiesLeavesItsLaterSortiesToTheOthers) {
  std::optional<server::DronePhase> phase_when_lost;
  RunOptions options;
  options.on_step = [&](double t_s, const server::Server& server) {
    if (!phase_when_lost && t_s >= 330.0) phase_when_lost = server.mission()->progress(2).phase;
  };
  const RunResult result =
      RunScenario(ParseScenario(kLostBetweenSorties, "sorties_lost.yaml", "."), options);
  PrintSortieFigures(result);
  ASSERT_EQ(phase_when_lost, server::DronePhase::kSwapping) << "the scenario's premise";
  const Report& report = result.report;
  EXPECT_EQ(report.vehicles.at(2).final_state, "lost");
  EXPECT_EQ(report.vehicles.at(2).sorties_flown, 1);
  EXPECT_GE(report.vehicles.at(2).sorties_planned, 2) << "vehicle 2 had a sortie left";
  for (const int id : {1, 3}) {
    EXPECT_GE(report.vehicles.at(id).sorties_flown, report.vehicles.at(id).sorties_planned);
    EXPECT_EQ(report.vehicles.at(id).final_state, "landed");
  }
  // Its second sortie's lanes were flown by the others, after their swaps.
  EXPECT_GE(report.coverage, 0.99);
}

}  // namespace
}  // namespace fireswarm::run
