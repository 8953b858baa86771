#include "web_feed.hpp"

#include <iostream>
#include <nlohmann/json.hpp>

#include "fireswarm/server/web_command.hpp"

namespace fireswarm::app {
namespace {

constexpr double kUpdatePeriodS = 0.2;  // 5 Hz (docs/command_center.md)
constexpr double kRadioWindowS = 2.0;   // radio_stats_t's window, as LcmRates' 0.5 Hz
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
    if (!command) {
      status = kBadRequest;
    } else if (!server.Handle(*command, now, &why)) {
      status = kConflict;
    }
    if (status == kAccepted) {
      web_.Answer(pending.id, status,
                  nlohmann::json{{"id", pending.id}, {"state", "queued"}}.dump());
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
  for (const std::uint8_t id : server.registry().ids()) {
    model_.OnVehicleState(server::ToVehicleState(server, id, now_s, utime));
  }
  model_.OnFireTracks(server::ToFireTrackList(server, utime, utime_at_zero));
  model_.OnMissionStatus(server::ToMissionStatus(server, now_s, utime));
  if (now_s + 1e-9 >= next_radio_s_) {
    next_radio_s_ = now_s + kRadioWindowS;
    model_.OnRadioStats(server::ToRadioStats(server, now_s, utime, kRadioWindowS, radio_counters_));
  }
  web_.SetDocuments(model_.State().dump(), model_.Plan().dump(), model_.Coverage().dump());
  if (std::optional<nlohmann::json> delta = model_.TakeDelta()) web_.Broadcast(delta->dump());
}

}  // namespace fireswarm::app
