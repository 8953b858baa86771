// Issue 19's chaos faults on whole missions: a vehicle's software reboot, a GPS
// loss, a radio burst and a server restart with down time, each on the runner
// tests' small fire scenario (800 m x 500 m, two drones, one fire).
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <map>
#include <optional>
#include <string>

#include "fireswarm/radio/messages.hpp"
#include "fireswarm/run/report_json.hpp"
#include "fireswarm/run/runner.hpp"
#include "fireswarm/run/scenario.hpp"
#include "fireswarm/server/server.hpp"

namespace fireswarm::run {
namespace {

// The vehicle declares its GPS lost after this long without a fix (agents/
// vehicle.hpp, which the run library keeps to itself), s.
constexpr double kGpsLostAfterS = 1.0;
// The runner's lockstep step (sim2d's default), s: telemetry received less than
// this before an on_step call is new at that step.
constexpr double kStepS = 0.01;

// The runner tests' small fire (runner_test.cpp), with `faults` appended.
Scenario SmallFireWith(const std::string& faults) {
  std::string text = R"(
name: small_fire_chaos
seed: 7
duration_s: 900
area:
  polygon: [[7.0, 45.0], [7.010146, 45.0], [7.010146, 45.0045], [7.0, 45.0045]]
fleet:
  count: 2
  launch: {lat: 44.9995, lon: 7.005}
fires:
  - {lat: 45.00230, lon: 7.00480, start_s: 0}
expect:
  all_fires_confirmed_within_s: 600
  max_fused_error_m: 10
  no_collisions: true
  min_coverage: 0.5
  max_false_tracks: 0
  max_reports_lost: 0
)";
  text += faults;
  return ParseScenario(text, "small_fire_chaos.yaml", ".");
}

void Print(const RunResult& result) {
  const Report& report = result.report;
  std::printf("stop %s, %.1f sim s, reports sent %llu received %llu lost %llu\n",
              ToString(result.stop), report.sim_seconds,
              static_cast<unsigned long long>(report.radio.reports_sent),
              static_cast<unsigned long long>(report.radio.reports_received),
              static_cast<unsigned long long>(report.radio.reports_lost));
  for (const FireOutcome& fire : report.fires) {
    std::printf("fire: error %.2f m, first report %.1f s, confirmed %.1f s\n",
                fire.error_m.value_or(-1.0), fire.first_report_s.value_or(-1.0),
                fire.confirmed_s.value_or(-1.0));
  }
  for (const auto& [id, age] : report.radio.telemetry_age_p50_p99_s) {
    std::printf("vehicle %d: telemetry age p50 %.2f s p99 %.2f s, %s, %.0f m\n", id, age.first,
                age.second, report.vehicles.at(id).final_state.c_str(),
                report.vehicles.at(id).distance_m);
  }
}

// The longest the server went without new telemetry from any vehicle (after the
// first), s: an on_step hook that watches the registry of whichever server runs.
struct TelemetryGaps {
  std::map<int, double> heard_at_s;  // vehicle -> latest telemetry seen
  double longest_s = 0.0;
  double longest_from_s = 0.0;
  void Watch(double t_s, const server::Server& server) {
    for (const std::uint8_t id : server.registry().ids()) {
      const server::VehicleState& state = server.registry().state(id);
      if (!state.telemetry || state.telemetry_time_s <= t_s - kStepS) continue;  // nothing new
      const auto last = heard_at_s.find(id);
      if (last != heard_at_s.end() && t_s - last->second > longest_s) {
        longest_s = t_s - last->second;
        longest_from_s = last->second;
      }
      heard_at_s[id] = t_s;
    }
  }
};

// The small fire without faults: when its fire is first reported (the reboot
// below is timed against it).
const RunResult& Baseline() {
  static const RunResult result = RunScenario(SmallFireWith(""));
  return result;
}

// The drone that first reported the fire in the baseline run.
int FirstReporter() {
  const FireOutcome& fire = Baseline().report.fires.at(0);
  EXPECT_FALSE(fire.vehicles.empty());
  return fire.vehicles.empty() ? 1 : fire.vehicles.front();
}

// The drone that sees the fire reboots just after its first report: reports it
// queued are still waiting for their acknowledgements, and it reports the fire
// again after the reboot. Its non-volatile storage keeps the report IDs going
// (the server would drop a new report with an old ID as a duplicate) and the
// unacknowledged reports (re-sent after the reboot), its mission and where it
// was: it resumes its search and lands home, and no report is lost.
TEST(RunScenario, VehicleRebootResumesTheSearchAndLosesNoReport) {
  const int vehicle = FirstReporter();
  const double first_report_s = Baseline().report.fires.at(0).first_report_s.value_or(100.0);
  const RunResult result = RunScenario(SmallFireWith(
      "faults:\n  - {vehicle: " + std::to_string(vehicle) +
      ", at_s: " + std::to_string(first_report_s + 0.5) + ", kind: vehicle_reboot}\n"));
  Print(result);
  EXPECT_EQ(result.vehicle_reboots, 1);
  EXPECT_TRUE(result.report.AllExpectationsHold()) << ToJson(result.report).dump(2);
  EXPECT_EQ(result.report.radio.reports_lost, 0U);
  EXPECT_GE(result.report.radio.reports_received, 2U);
  EXPECT_EQ(result.report.vehicles.at(vehicle).final_state, "landed");
  // It flew its whole search after the reboot, not straight home.
  EXPECT_GT(result.report.vehicles.at(vehicle).distance_m,
            0.8 * Baseline().report.vehicles.at(vehicle).distance_m);
}

// Ten seconds without GPS over the fire: the drone levels off and locates
// nothing while it has no fix (a report placed by a guessed position would
// make a false track or pull the fused fire away), then takes up its search.
TEST(RunScenario, GpsLossLevelsOffLocatesNothingAndTheFireIsStillConfirmed) {
  const int vehicle = FirstReporter();
  const double lost_at_s = Baseline().report.fires.at(0).first_report_s.value_or(100.0) - 3.0;
  constexpr double kLostForS = 10.0;
  // What the server hears: no fix from a second after the loss to its end, a fix
  // again soon after.
  int fixes_in_loss = 0;
  int telemetry_in_loss = 0;
  bool fix_after = false;
  RunOptions options;
  options.on_step = [&](double t_s, const server::Server& server) {
    const server::VehicleState& state = server.registry().state(static_cast<std::uint8_t>(vehicle));
    if (!state.telemetry || state.telemetry_time_s <= t_s - kStepS) return;  // nothing new
    const bool fix = (state.telemetry->flags & radio::telemetry_flags::kGpsFix) != 0;
    if (t_s > lost_at_s + kGpsLostAfterS + 0.5 && t_s < lost_at_s + kLostForS) {
      ++telemetry_in_loss;
      if (fix) ++fixes_in_loss;
    }
    if (t_s > lost_at_s + kLostForS + 1.0 && fix) fix_after = true;
  };
  const RunResult result = RunScenario(
      SmallFireWith("faults:\n  - {vehicle: " + std::to_string(vehicle) +
                    ", at_s: " + std::to_string(lost_at_s) + ", kind: gps_loss, duration_s: 10}\n"),
      options);
  Print(result);
  EXPECT_GT(telemetry_in_loss, 3);
  EXPECT_EQ(fixes_in_loss, 0);
  EXPECT_TRUE(fix_after);
  EXPECT_TRUE(result.report.AllExpectationsHold()) << ToJson(result.report).dump(2);
  EXPECT_EQ(result.report.vehicles.at(vehicle).final_state, "landed");
}

// A dead channel for 5 s mid-search: no telemetry gets through for that long
// (the longest silence of the run, where a clean run hears each drone every
// second or so), and the mission rides it out losing no report.
TEST(RunScenario, RadioBurstSilencesTheChannelForItsWindow) {
  TelemetryGaps gaps;
  RunOptions options;
  options.on_step = [&](double t_s, const server::Server& server) { gaps.Watch(t_s, server); };
  const RunResult result = RunScenario(
      SmallFireWith("faults:\n  - {at_s: 60, kind: radio_burst, duration_s: 5, loss: 1}\n"),
      options);
  Print(result);
  EXPECT_TRUE(result.report.AllExpectationsHold()) << ToJson(result.report).dump(2);
  EXPECT_GE(gaps.longest_s, 5.0);
  EXPECT_LT(gaps.longest_s, 8.0);
  EXPECT_LT(gaps.longest_from_s, 60.0);
  EXPECT_GT(gaps.longest_from_s, 55.0);
  // Half the frames lost for a minute: slower, but still no report lost.
  const RunResult half = RunScenario(
      SmallFireWith("faults:\n  - {at_s: 340, kind: radio_burst, duration_s: 60, loss: 0.5}\n"));
  EXPECT_TRUE(half.report.AllExpectationsHold()) << ToJson(half.report).dump(2);
}

// A server down for 8 s: the new one takes over from the journal only then, and
// nothing is heard meanwhile; the mission goes on and loses no report.
TEST(RunScenario, ServerRestartWithDownTimeTakesOverAfterIt) {
  std::optional<double> new_server_at_s;
  const server::Server* first = nullptr;
  TelemetryGaps gaps;
  RunOptions options;
  options.on_step = [&](double t_s, const server::Server& server) {
    if (first == nullptr) first = &server;
    if (&server != first && !new_server_at_s) new_server_at_s = t_s;
    gaps.Watch(t_s, server);
  };
  const RunResult result = RunScenario(
      SmallFireWith("faults:\n  - {at_s: 40, kind: server_restart, duration_s: 8}\n"), options);
  Print(result);
  EXPECT_EQ(result.server_restarts, 1);
  ASSERT_TRUE(new_server_at_s.has_value());
  EXPECT_GE(*new_server_at_s, 48.0);
  EXPECT_LT(*new_server_at_s, 49.0);
  EXPECT_TRUE(result.report.AllExpectationsHold()) << ToJson(result.report).dump(2);
  // Nothing heard while it was down.
  EXPECT_GE(gaps.longest_s, 8.0);
  EXPECT_GT(gaps.longest_from_s, 38.0);
  EXPECT_LE(gaps.longest_from_s, 40.5);
}

// Every chaos fault at once, twice: the same seed gives the same final state.
TEST(RunScenario, ChaosIsDeterministic) {
  const std::string faults =
      "faults:\n"
      "  - {at_s: 30, kind: radio_burst, duration_s: 3, loss: 0.5}\n"
      "  - {vehicle: 1, at_s: 45, kind: vehicle_reboot}\n"
      "  - {vehicle: 2, at_s: 50, kind: gps_loss, duration_s: 4}\n"
      "  - {at_s: 55, kind: server_restart, duration_s: 2}\n";
  Scenario scenario = SmallFireWith(faults);
  scenario.duration_s = 90.0;
  const RunResult a = RunScenario(scenario);
  const RunResult b = RunScenario(scenario);
  EXPECT_EQ(a.state_hash, b.state_hash);
  EXPECT_EQ(a.vehicle_reboots, 1);
  EXPECT_EQ(a.server_restarts, 1);
}

}  // namespace
}  // namespace fireswarm::run
