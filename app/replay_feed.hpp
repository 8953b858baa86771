// The glue between a recorded mission (server::ReplayLog) and the command
// center's web server for `fireswarm replay`: a timeline over the log's time
// that plays at `speed` times the wall clock, pauses and seeks on the page's
// {"type": "replay"} messages (docs/command_center.md), feeds the page's model
// (server::CommandCenter) up to the timeline's time, and serves it. Starts paused
// at the log's start; pauses at its end.
#pragma once

#include <chrono>
#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>

#include "fireswarm/server/command_center.hpp"
#include "fireswarm/server/replay.hpp"
#include "fireswarm/server/web_server.hpp"

namespace fireswarm::app {

class ReplayFeed {
 public:
  using Clock = std::chrono::steady_clock;

  /// Highest --speed and page speed accepted, times the wall clock.
  static constexpr double kMaxSpeed = 1000.0;

  /// Feeds the model up to the log's start and serves it. `log` and `web` must
  /// outlive the feed. Precondition: 0 < speed <= kMaxSpeed.
  ReplayFeed(const server::ReplayLog& log, server::WebServer& web, double speed,
             Clock::time_point now);

  /// Carries out one page message ({"type": "replay", "action": "play" | "pause"
  /// | "seek", "time_s", "speed"}); a malformed one gets {"type": "error"} back
  /// naming the field, and changes nothing.
  void Handle(const server::ClientMessage& message, Clock::time_point now);
  /// Plays on to `now` when an update is due (5 Hz of the wall clock while
  /// playing), broadcasting the model's delta, and the replay status when due
  /// (once a second while playing).
  void Advance(Clock::time_point now);
  /// When Advance next has something to do; Clock::time_point::max() when paused.
  Clock::time_point NextDue() const;

  double time_s() const { return time_s_; }
  bool playing() const { return playing_; }

 private:
  // {"time_s", "start_s", "end_s", "playing", "speed"}: the state's "replay",
  // and with "type": "replay" the stream's status message.
  nlohmann::json Status() const;
  // Plays on to `now`: feeds the model, serves it, broadcasts its delta; pauses at the end.
  void Update(Clock::time_point now);
  void Play(double speed, Clock::time_point now);
  void Pause(double speed);
  void Seek(double time_s, Clock::time_point now);
  // Feeds the model up to time_s_ (rebuilding it first when time_s_ is before
  // what it was fed) and serves it.
  void FeedTo(bool rebuild);
  // Serves the model (the coverage raster rebuilt when due); returns the state served.
  std::string Serve(bool coverage_due);
  void BroadcastStatus(Clock::time_point now);

  const server::ReplayLog& log_;
  server::WebServer& web_;
  server::CommandCenter model_;
  std::size_t next_event_ = 0;  // the first event not fed to model_
  double fed_to_s_ = 0.0;       // model_ holds every event up to this time
  double time_s_ = 0.0;         // the timeline's time, log seconds
  double speed_ = 1.0;
  bool playing_ = false;
  // While playing: time_s_ = anchor_s_ + speed_ * (wall - anchor_wall_).
  double anchor_s_ = 0.0;
  Clock::time_point anchor_wall_;
  Clock::time_point next_update_;
  Clock::time_point next_status_;
  Clock::time_point next_coverage_;
  std::string coverage_document_ = "{}";
};

}  // namespace fireswarm::app
