// The lockstep runner behind `fireswarm run`: one process, simulated time, every
// step in the same order (DESIGN "Data flow"): sim2d steps (physics, fire,
// cameras) -> every vehicle steps on its sensors and camera frames -> the shared
// radio channel runs event by event to the step's end, delivering bytes between
// the vehicles and the server -> the server steps. Scoring against the
// simulator's truth happens beside it, never inside the server or the vehicles.
//
// Same scenario, same seed, same binary -> the same report, apart from the
// wall-clock fields (wall_seconds, real_time_factor).
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "fireswarm/run/report.hpp"
#include "fireswarm/run/scenario.hpp"
#include "fireswarm/server/server.hpp"

namespace fireswarm::run {

/// Where a run is, for a progress bar.
struct RunProgress {
  double sim_s = 0.0;               ///< simulated time reached
  double duration_s = 0.0;          ///< the scenario's limit
  double coverage = 0.0;            ///< fraction 0..1 of the search area seen so far
  std::size_t fires_confirmed = 0;  ///< confirmed tracks so far (true or false)
  std::size_t fires_total = 0;      ///< true fires in the scenario
  int missions = 0;                 ///< missions started (a patrol's rounds)
  std::size_t journal_entries = 0;  ///< the journal a server restart would read
};

struct RunOptions {
  /// Called every `progress_interval_s` of simulated time and once at the end;
  /// empty: no progress. Must not throw.
  std::function<void(const RunProgress&)> progress;
  double progress_interval_s = 5.0;
  /// Called after every lockstep step with the simulated time reached, s, and the
  /// server as it stands then (what an adapter publishes, e.g. on LCM); empty: none.
  /// It may hand the server operator commands (Server::HandleSigned at t_s, its
  /// LCM clock simulated microseconds since the start), which then
  /// take effect from the next step on, as a command arriving then would.
  /// An exception it throws ends the run and leaves RunScenario.
  std::function<void(double t_s, server::Server& server)> on_step;
  /// A restart drill: called after every step (after on_step) on which the
  /// server's radio is off the air, until it returns true, once; the server is then replaced by one
  /// restored from the journal its predecessor wrote (through the journal file's record format, as
  /// `fireswarm serve --journal` after a crash), which flies the rest of the
  /// mission. Empty: no restart.
  std::function<bool(double t_s, const server::Server& server)> restart_server_when;
  /// After the mission is complete, the run goes on at most this long for fire
  /// reports still queued on the vehicles to reach the server, s.
  double drain_s = 30.0;
  /// Operator ID -> key: whose signed commands the server takes (on_step's, e.g.
  /// the page's through `run --keys`). The runner signs the mission's start
  /// itself, as operator "runner" with a key it makes for the run.
  std::map<std::string, common::SecretKey> operators;
};

/// Why the run stopped.
enum class StopReason : std::uint8_t {
  kDuration,         ///< the scenario's duration_s was reached
  kMissionComplete,  ///< the server's mission state became complete (or aborted)
  kAllDown,          ///< every vehicle landed, crashed or was lost
};
const char* ToString(StopReason reason);

struct RunResult {
  Report report;
  StopReason stop = StopReason::kDuration;
  /// sim2d's state hash at the end (truth, fire, camera frames): a determinism check.
  std::uint64_t state_hash = 0;
  std::string mission_state;  ///< the server's mission state at the end ("complete", ...)
  int server_restarts = 0;    ///< by server_restart faults and RunOptions::restart_server_when
  int missions = 0;           ///< missions started: 1, or a patrol's rounds
  int vehicle_reboots = 0;    ///< vehicle_reboot faults done (the vehicle back up)
};

/// Plans the search (planner::PlanSearch with the fleet's planner and the
/// scenario's seed), loads it on a server::Server in the area's frame, starts it
/// at t = 0 and flies the fleet in sim2d until duration_s, or the mission is
/// complete and queued reports are in, or every vehicle is down. Returns the
/// scored report with its expectations evaluated.
/// Throws ScenarioError (naming the scenario file) when the scenario cannot be
/// flown: the planner refuses the fleet or area, or random fires cannot be placed.
RunResult RunScenario(const Scenario& scenario, const RunOptions& options = {});

}  // namespace fireswarm::run
