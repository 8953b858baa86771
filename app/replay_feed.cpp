#include "replay_feed.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <set>
#include <utility>

namespace fireswarm::app {
namespace {

using namespace std::chrono_literals;

constexpr auto kUpdatePeriod = 200ms;   // deltas at 5 Hz (docs/command_center.md), as live
constexpr auto kStatusPeriod = 1000ms;  // the replay status while playing
// The coverage raster is up to 2 million cells: rebuilt once a second, as live.
constexpr auto kCoveragePeriod = 1000ms;

server::CommandCenterConfig ModelConfig() {
  server::CommandCenterConfig config;
  config.source = "replay";
  config.read_only = true;
  return config;
}

// A page message: {"type": "replay", "action", "time_s" (seek), "speed"}.
struct Request {
  std::string action;
  std::optional<double> time_s;
  std::optional<double> speed;
};

std::optional<double> Number(const nlohmann::json& message, const char* field, std::string* why) {
  const auto found = message.find(field);
  if (found == message.end()) return std::nullopt;
  if (!found->is_number() || !std::isfinite(found->get<double>())) {
    *why = std::string("replay: \"") + field + "\" must be a number, got " + found->dump();
    return std::nullopt;
  }
  return found->get<double>();
}

std::optional<Request> Parse(const nlohmann::json& message, std::string* why) {
  const auto type = message.find("type");
  if (type == message.end() || *type != "replay") {
    *why =
        "unknown message: a replay takes {\"type\": \"replay\", \"action\": ...}, got \"type\" " +
        (type == message.end() ? std::string("missing") : type->dump());
    return std::nullopt;
  }
  static const std::set<std::string> kFields{"type", "action", "time_s", "speed"};
  for (const auto& [key, value] : message.items()) {
    if (kFields.count(key) == 0) {
      *why = "replay: unknown field \"" + key + "\"";
      return std::nullopt;
    }
  }
  Request request;
  const auto action = message.find("action");
  if (action != message.end() && action->is_string()) request.action = action->get<std::string>();
  if (request.action != "play" && request.action != "pause" && request.action != "seek") {
    *why = "replay: \"action\" must be \"play\", \"pause\" or \"seek\", got " +
           (action == message.end() ? std::string("nothing") : action->dump());
    return std::nullopt;
  }
  request.time_s = Number(message, "time_s", why);
  request.speed = Number(message, "speed", why);
  if (!why->empty()) return std::nullopt;
  if (request.action == "seek" && !request.time_s) {
    *why = "replay: a seek needs \"time_s\" (log seconds)";
    return std::nullopt;
  }
  if (request.speed && !(*request.speed > 0.0 && *request.speed <= ReplayFeed::kMaxSpeed)) {
    *why = "replay: \"speed\" must be in (0, 1000], got " + message.at("speed").dump();
    return std::nullopt;
  }
  return request;
}

double Seconds(ReplayFeed::Clock::duration duration) {
  return std::chrono::duration<double>(duration).count();
}

}  // namespace

ReplayFeed::ReplayFeed(const server::ReplayLog& log, server::WebServer& web, double speed,
                       Clock::time_point now)
    : log_(log),
      web_(web),
      model_(ModelConfig()),
      time_s_(log.start_s()),
      speed_(speed),
      next_update_(now),
      next_status_(now),
      next_coverage_(now) {
  FeedTo(false);
  model_.TakeDelta();  // the first client's snapshot holds it all
  Serve(true);
}

void ReplayFeed::Handle(const server::ClientMessage& message, Clock::time_point now) {
  std::string why;
  const std::optional<Request> request = Parse(message.message, &why);
  if (!request) {
    web_.SendTo(message.client, nlohmann::json{{"type", "error"}, {"error", why}}.dump());
    return;
  }
  const double speed = request->speed.value_or(speed_);
  if (request->action == "play") {
    Play(speed, now);
  } else if (request->action == "pause") {
    Pause(speed);
  } else {
    speed_ = speed;
    Seek(*request->time_s, now);
  }
  BroadcastStatus(now);
}

void ReplayFeed::Advance(Clock::time_point now) {
  if (playing_ && now >= next_update_) Update(now);
  if (playing_ && now >= next_status_) BroadcastStatus(now);
}

void ReplayFeed::Update(Clock::time_point now) {
  next_update_ = now + kUpdatePeriod;
  time_s_ = std::min(log_.end_s(), anchor_s_ + speed_ * Seconds(now - anchor_wall_));
  const bool at_end = time_s_ >= log_.end_s();
  if (at_end) playing_ = false;  // so the state served says paused
  FeedTo(false);
  const bool coverage_due = now >= next_coverage_;
  if (coverage_due) next_coverage_ = now + kCoveragePeriod;
  Serve(coverage_due);
  if (std::optional<nlohmann::json> delta = model_.TakeDelta()) web_.Broadcast(delta->dump());
  if (at_end) BroadcastStatus(now);
}

ReplayFeed::Clock::time_point ReplayFeed::NextDue() const {
  return playing_ ? std::min(next_update_, next_status_) : Clock::time_point::max();
}

nlohmann::json ReplayFeed::Status() const {
  return {{"time_s", time_s_},
          {"start_s", log_.start_s()},
          {"end_s", log_.end_s()},
          {"playing", playing_},
          {"speed", speed_}};
}

void ReplayFeed::Play(double speed, Clock::time_point now) {
  if (playing_) {
    Update(now);  // up to now at the old speed, then on at the new one
  } else if (time_s_ >= log_.end_s()) {
    Seek(log_.start_s(), now);  // play at the end plays it again, as a video player does
  }
  speed_ = speed;
  playing_ = time_s_ < log_.end_s();
  anchor_s_ = time_s_;
  anchor_wall_ = now;
  next_update_ = now + kUpdatePeriod;
  Serve(false);
}

void ReplayFeed::Pause(double speed) {
  // Where the last update left it (at most 1/5 s behind): what the page shows.
  playing_ = false;
  speed_ = speed;
  Serve(false);
}

void ReplayFeed::Seek(double time_s, Clock::time_point now) {
  time_s_ = std::clamp(time_s, log_.start_s(), log_.end_s());
  const bool rebuild = time_s_ < fed_to_s_;
  anchor_s_ = time_s_;
  anchor_wall_ = now;
  FeedTo(rebuild);
  model_.TakeDelta();  // the snapshot below holds it all
  next_coverage_ = now + kCoveragePeriod;
  const std::string state = Serve(true);
  web_.Broadcast(R"({"type":"snapshot","state":)" + state + "}");
}

void ReplayFeed::FeedTo(bool rebuild) {
  if (rebuild) {
    // The model keeps trails and alerts raised on the way: it cannot go back.
    model_ = server::CommandCenter(ModelConfig());
    next_event_ = 0;
  }
  next_event_ = log_.Feed(model_, next_event_, time_s_);
  fed_to_s_ = time_s_;
}

std::string ReplayFeed::Serve(bool coverage_due) {
  if (coverage_due) coverage_document_ = model_.Coverage().dump();
  nlohmann::json state = model_.State();
  state["replay"] = Status();
  std::string text = state.dump();
  web_.SetDocuments(text, model_.Plan().dump(), coverage_document_);
  return text;
}

void ReplayFeed::BroadcastStatus(Clock::time_point now) {
  nlohmann::json status = Status();
  status["type"] = "replay";
  web_.Broadcast(status.dump());
  next_status_ = now + kStatusPeriod;
}

}  // namespace fireswarm::app
