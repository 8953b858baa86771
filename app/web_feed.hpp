// The glue between the server core and the command center's web server: at 5 Hz
// of the caller's clock (simulated for `run`, the mission clock for `serve`), and
// no more often than 5 times a second of the wall clock (a run paced at K > 1 is
// fed every K/5 simulated s), the server is converted into its LCM messages
// (lcm_bridge.hpp's pure conversions), fed to the page's model
// (server::CommandCenter), and the model's delta broadcast (the plan as LCM's
// plan_t when the missions changed, each command's status when it changed, the
// coverage raster at most once a second when a cell was seen). The whole state
// is serialised only when asked for: at the step after a new WebSocket client
// waits for its snapshot or a GET /api/state for the state (at 250 drones the
// state is several times the delta's size; WebServer::HoldSnapshots). At every
// step the page's commands are parsed (ParseWebCommand) and handed to
// Server::HandleSigned at that time with their signature (ParseWebCredentials),
// the same entry point as LCM's operator commands, and answered: 202 queued, 400
// unreadable, 401 unsigned or refused by the verifier (why names the verdict),
// 409 refused by the server core. Each delta and state document
// carries `built_unix_ms`, the wall clock when it was built (the page measures
// its state-to-screen latency with it).
#pragma once

#include <chrono>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "fireswarm/common/time.hpp"
#include "fireswarm/server/command_center.hpp"
#include "fireswarm/server/lcm_bridge.hpp"
#include "fireswarm/server/server.hpp"
#include "fireswarm/server/web_server.hpp"

namespace fireswarm::app {

class WebFeed {
 public:
  /// `web` must outlive the feed. `source`: "live" or "simulated" (the state's).
  WebFeed(server::WebServer& web, const std::string& source);

  /// Takes the page's commands and, once 1/5 s of the clock passed since the last
  /// update, updates and serves the model. `now`: the server's clock; `utime`,
  /// `utime_at_zero`: the LCM utime of now and of the clock's zero (docs/lcm.md).
  void Step(server::Server& server, common::Nanos now, std::int64_t utime,
            std::int64_t utime_at_zero);

  /// CPU time Step has taken on the caller's thread since the feed was made, s
  /// (the model's updates, the documents' and deltas' serialisation, the commands;
  /// not a step's look for work, a few atomic loads and a vDSO clock read).
  double cpu_seconds() const { return cpu_s_; }

  /// The web adapter's CPU against the process's, as one JSON event line's object:
  /// {"event": "web_cpu", "feed_cpu_s": this feed's (cpu_seconds()), "io_cpu_s": the
  /// web server's io thread's, "web_cpu_s": their sum, "process_cpu_s": the whole
  /// process's (CLOCK_PROCESS_CPUTIME_ID), "share": web_cpu_s / process_cpu_s}.
  nlohmann::json CpuFigures() const;

 private:
  // Hands the page's commands to the server (`utime`: now on the LCM clock, for
  // the signatures' window) and answers them; answers client
  // messages (live, there are no replay controls).
  void Answer(server::Server& server, common::Nanos now, std::int64_t utime,
              const std::vector<server::PendingCommand>& commands,
              const std::vector<server::ClientMessage>& messages);
  void Update(const server::Server& server, double now_s, std::int64_t utime,
              std::int64_t utime_at_zero);

  server::WebServer& web_;
  server::CommandCenter model_;
  server::RadioCounters radio_counters_;
  double next_update_s_ = 0.0;
  double next_radio_s_ = 0.0;
  std::optional<std::uint64_t> plan_missions_version_;    // MissionManager's, last fed
  std::optional<std::uint64_t> coverage_version_served_;  // the model's, in coverage_document_
  double next_coverage_s_ = 0.0;
  std::chrono::steady_clock::time_point next_update_wall_{};
  std::chrono::steady_clock::time_point next_coverage_wall_{};  // the coverage document
  bool plan_documents_changed_ = true;  // plan_document_ or coverage_document_ not served yet
  std::string coverage_document_ = "{}";
  std::string plan_document_;  // model_.Plan() serialised, redone when the plan is fed
  double cpu_s_ = 0.0;
  std::uint64_t commands_version_ = 0;  // the server's commands_version() last fed
  std::uint64_t traffic_version_ = 0;   // the server's traffic().version() last fed
  std::uint64_t refused_noted_ = 0;     // web_.refused() already counted in the model
};

}  // namespace fireswarm::app
