#include "web_feed.hpp"

#include <chrono>
#include <ctime>
#include <iostream>
#include <nlohmann/json.hpp>

#include "fireswarm/server/web_command.hpp"

namespace fireswarm::app {
namespace {

constexpr double kUpdatePeriodS = 0.2;  // 5 Hz (docs/command_center.md)
constexpr int kUpdatePeriodMs = 200;    // ... and at most 5 Hz of the wall clock
constexpr double kRadioWindowS = 2.0;   // radio_stats_t's window, as LcmRates' 0.5 Hz
// The coverage raster is up to 2 million cells; the page fetches it every few
// seconds, so it is rebuilt at most once a second (of the run's clock and of the
// wall clock), and only when a cell was seen since.
constexpr double kCoveragePeriodS = 1.0;
constexpr int kCoveragePeriodMs = 1000;  // ... and of the wall clock
constexpr int kAccepted = 202;
constexpr int kBadRequest = 400;
constexpr int kUnauthorized = 401;
constexpr int kConflict = 409;

server::CommandCenterConfig ModelConfig(const std::string& source) {
  server::CommandCenterConfig config;
  config.source = source;
  return config;
}

// CPU time on `clock` (CLOCK_THREAD_CPUTIME_ID, CLOCK_PROCESS_CPUTIME_ID), s.
double CpuSeconds(clockid_t clock) {
  timespec cpu{};
  clock_gettime(clock, &cpu);
  return static_cast<double>(cpu.tv_sec) + static_cast<double>(cpu.tv_nsec) * 1e-9;
}

// The wall clock, ms since the Unix epoch: the documents' `built_unix_ms`.
std::int64_t UnixMillisNow() {
  return std::chrono::duration_cast<std::chrono::milliseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

std::string ErrorBody(const std::string& why) {
  return nlohmann::json{{"error", why}}.dump();
}

}  // namespace

WebFeed::WebFeed(server::WebServer& web, const std::string& source)
    : web_(web), model_(ModelConfig(source)), plan_document_(model_.Plan().dump()) {
  // WebSocket clients and GET /api/state wait for the state the first Step serves.
  web_.SetPlanDocuments(plan_document_, coverage_document_);
  web_.HoldSnapshots();
}

void WebFeed::Step(server::Server& server, common::Nanos now, std::int64_t utime,
                   std::int64_t utime_at_zero) {
  const std::vector<server::PendingCommand> commands = web_.TakeCommands();
  const std::vector<server::ClientMessage> messages = web_.TakeClientMessages();
  const double now_s = common::ToSeconds(now);
  // 5 Hz of the run's clock, and no more often than 5 times a second of the wall
  // clock: a run paced at K would otherwise update and serialise K times as often
  // as anybody can watch (the delta taken later carries every change since the last).
  const std::chrono::steady_clock::time_point wall = std::chrono::steady_clock::now();
  const bool update_due = now_s + 1e-9 >= next_update_s_ && wall >= next_update_wall_;
  // Most steps have nothing to do: the looks above are atomic loads and the vDSO's
  // clock. The thread's CPU clock, a system call, is read only around work.
  if (commands.empty() && messages.empty() && !update_due && !web_.snapshot_wanted()) return;
  const double cpu_start_s = CpuSeconds(CLOCK_THREAD_CPUTIME_ID);
  Answer(server, now, utime, commands, messages);
  if (update_due) {
    next_update_s_ = now_s + kUpdatePeriodS;
    next_update_wall_ = wall + std::chrono::milliseconds(kUpdatePeriodMs);
    Update(server, now_s, utime, utime_at_zero);
  }
  // The whole state (every drone's row and trail, every track) is serialised only
  // for a new WebSocket client's snapshot or a GET /api/state, at the step after it
  // asked: the updates send the delta alone (WebServer::HoldSnapshots).
  if (web_.snapshot_wanted()) {
    nlohmann::json state = model_.State();
    state["built_unix_ms"] = UnixMillisNow();
    web_.SetDocuments(state.dump(), plan_document_, coverage_document_);
  }
  cpu_s_ += CpuSeconds(CLOCK_THREAD_CPUTIME_ID) - cpu_start_s;
}

nlohmann::json WebFeed::CpuFigures() const {
  const double io_cpu_s = web_.io_cpu_seconds();
  const double web_cpu_s = cpu_s_ + io_cpu_s;
  const double process_cpu_s = CpuSeconds(CLOCK_PROCESS_CPUTIME_ID);
  return {{"event", "web_cpu"},
          {"feed_cpu_s", cpu_s_},
          {"io_cpu_s", io_cpu_s},
          {"web_cpu_s", web_cpu_s},
          {"process_cpu_s", process_cpu_s},
          {"share", process_cpu_s > 0.0 ? web_cpu_s / process_cpu_s : 0.0}};
}

void WebFeed::Answer(server::Server& server, common::Nanos now, std::int64_t utime,
                     const std::vector<server::PendingCommand>& commands,
                     const std::vector<server::ClientMessage>& messages) {
  for (const server::PendingCommand& pending : commands) {
    std::string why;
    const std::optional<server::OperatorCommand> command =
        server::ParseWebCommand(pending.body, &why);
    const std::optional<server::CommandCredentials> credentials =
        command ? server::ParseWebCredentials(pending.body, &why) : std::nullopt;
    int status = kAccepted;
    std::int32_t command_id = 0;
    server::CommandVerdict verdict = server::CommandVerdict::kAccepted;
    if (!command) {
      status = kBadRequest;
    } else if (!credentials) {
      // Unsigned: journaled and counted like every refusal of an unread command.
      status = kUnauthorized;
      why = "malformed: " + why;
      server.Refuse({server::CommandVerdict::kMalformed, static_cast<int>(command->kind),
                     command->vehicle, "", 0, 0, why},
                    now);
    } else if (!server.HandleSigned({*command, *credentials}, now, utime, &why, &command_id,
                                    &verdict)) {
      status = verdict == server::CommandVerdict::kAccepted ? kConflict : kUnauthorized;
    }
    if (status == kAccepted) {
      // The server's command ID: the one command_status_t and the state's
      // "commands" carry, so the page follows this command there.
      web_.Answer(pending.id, status,
                  nlohmann::json{{"id", command_id}, {"state", "queued"}}.dump());
      continue;
    }
    std::cerr << "web: refused a command from " << pending.peer << ": " << why << std::endl;
    model_.NoteRefused();
    web_.Answer(pending.id, status, ErrorBody(why));
  }
  // Live there are no replay controls to take.
  for (const server::ClientMessage& message : messages) {
    web_.SendTo(
        message.client,
        nlohmann::json{{"type", "error"}, {"error", "replay controls need a replay"}}.dump());
  }
}

void WebFeed::Update(const server::Server& server, double now_s, std::int64_t utime,
                     std::int64_t utime_at_zero) {
  for (; refused_noted_ < web_.refused(); ++refused_noted_) model_.NoteRefused();
  // The plan changes only with the missions (a handover gives a drone new lanes).
  const server::MissionManager* mission = server.mission();
  if (mission != nullptr && plan_missions_version_ != mission->missions_version()) {
    plan_missions_version_ = mission->missions_version();
    model_.OnPlan(server::ToPlan(server, utime));
    plan_document_ = model_.Plan().dump();
    plan_documents_changed_ = true;
  }
  if (server.commands_version() != commands_version_) {
    for (const server::CommandRecord& record : server.commands()) {
      if (record.version <= commands_version_) continue;
      model_.OnCommandStatus(server::ToCommandStatus(record, utime, utime_at_zero));
    }
    commands_version_ = server.commands_version();
  }
  const server::TrafficControl& traffic = server.traffic();
  if (traffic.version() != traffic_version_) {
    for (const server::Conflict& conflict : traffic.conflicts()) {
      if (conflict.version <= traffic_version_) continue;
      model_.OnConflict(server::ToConflict(conflict, utime, utime_at_zero));
    }
    traffic_version_ = traffic.version();
  }
  for (const std::uint8_t id : server.registry().ids()) {
    model_.OnVehicleState(server::ToVehicleState(server, id, now_s, utime));
  }
  model_.OnFireTracks(server::ToFireTrackList(server, utime, utime_at_zero));
  model_.OnMissionStatus(server::ToMissionStatus(server, now_s, utime));
  if (now_s + 1e-9 >= next_radio_s_) {
    next_radio_s_ = now_s + kRadioWindowS;
    model_.OnRadioStats(server::ToRadioStats(server, now_s, utime, kRadioWindowS, radio_counters_));
  }
  const std::chrono::steady_clock::time_point wall = std::chrono::steady_clock::now();
  if (coverage_version_served_ != model_.coverage_version() && now_s + 1e-9 >= next_coverage_s_ &&
      wall >= next_coverage_wall_) {
    next_coverage_s_ = now_s + kCoveragePeriodS;
    next_coverage_wall_ = wall + std::chrono::milliseconds(kCoveragePeriodMs);
    coverage_version_served_ = model_.coverage_version();
    coverage_document_ = model_.Coverage().dump();
    plan_documents_changed_ = true;
  }
  const std::int64_t built_unix_ms = UnixMillisNow();
  // A delta may tell the page to fetch the plan: it is served before the delta goes.
  if (plan_documents_changed_) {
    web_.SetPlanDocuments(plan_document_, coverage_document_);
    plan_documents_changed_ = false;
  }
  if (std::optional<nlohmann::json> delta = model_.TakeDelta()) {
    (*delta)["built_unix_ms"] = built_unix_ms;
    web_.HoldSnapshots();  // the state document does not hold this delta yet
    web_.Broadcast(delta->dump());
  }
}

}  // namespace fireswarm::app
