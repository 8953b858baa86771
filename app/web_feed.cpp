#include "web_feed.hpp"

#include <iostream>
#include <nlohmann/json.hpp>

#include "fireswarm/server/web_command.hpp"

namespace fireswarm::app {
namespace {

constexpr double kUpdatePeriodS = 0.2;  // 5 Hz (docs/command_center.md)
constexpr double kRadioWindowS = 2.0;   // radio_stats_t's window, as LcmRates' 0.5 Hz
constexpr double kPlanPeriodS = 5.0;    // plan_t's period, as LcmRates' 0.2 Hz
// The coverage raster is up to 2 million cells; the page fetches it every few
// seconds, so it is rebuilt once a second, not at every update.
constexpr double kCoveragePeriodS = 1.0;
constexpr int kAccepted = 202;
constexpr int kBadRequest = 400;
constexpr int kConflict = 409;

server::CommandCenterConfig ModelConfig(const std::string& source) {
  server::CommandCenterConfig config;
  config.source = source;
  return config;
}

std::string ErrorBody(const std::string& why) {
  return nlohmann::json{{"error", why}}.dump();
}

}  // namespace

WebFeed::WebFeed(server::WebServer& web, const std::string& source)
    : web_(web), model_(ModelConfig(source)) {}

void WebFeed::Step(server::Server& server, common::Nanos now, std::int64_t utime,
                   std::int64_t utime_at_zero) {
  TakeCommands(server, now);
  const double now_s = common::ToSeconds(now);
  if (now_s + 1e-9 < next_update_s_) return;
  next_update_s_ = now_s + kUpdatePeriodS;
  Update(server, now_s, utime, utime_at_zero);
}

void WebFeed::TakeCommands(server::Server& server, common::Nanos now) {
  for (const server::PendingCommand& pending : web_.TakeCommands()) {
    std::string why;
    const std::optional<server::OperatorCommand> command =
        server::ParseWebCommand(pending.body, &why);
    int status = kAccepted;
    std::int32_t command_id = 0;
    if (!command) {
      status = kBadRequest;
    } else if (!server.Handle(*command, now, &why, &command_id)) {
      status = kConflict;
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
  for (const server::ClientMessage& message : web_.TakeClientMessages()) {
    web_.SendTo(
        message.client,
        nlohmann::json{{"type", "error"}, {"error", "replay controls need a replay"}}.dump());
  }
}

void WebFeed::Update(const server::Server& server, double now_s, std::int64_t utime,
                     std::int64_t utime_at_zero) {
  for (; refused_noted_ < web_.refused(); ++refused_noted_) model_.NoteRefused();
  if (server.mission() != nullptr && now_s + 1e-9 >= next_plan_s_) {
    next_plan_s_ = now_s + kPlanPeriodS;
    model_.OnPlan(server::ToPlan(server, utime));
  }
  if (server.commands_version() != commands_version_) {
    for (const server::CommandRecord& record : server.commands()) {
      if (record.version <= commands_version_) continue;
      model_.OnCommandStatus(server::ToCommandStatus(record, utime, utime_at_zero));
    }
    commands_version_ = server.commands_version();
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
  if (now_s + 1e-9 >= next_coverage_s_) {
    next_coverage_s_ = now_s + kCoveragePeriodS;
    coverage_document_ = model_.Coverage().dump();
  }
  web_.SetDocuments(model_.State().dump(), model_.Plan().dump(), coverage_document_);
  if (std::optional<nlohmann::json> delta = model_.TakeDelta()) web_.Broadcast(delta->dump());
}

}  // namespace fireswarm::app
