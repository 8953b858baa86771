// Replaying an LCM log written by `fireswarm serve|run --log` into the command
// center: the log's FIRESWARM_* messages, decoded and in time order, fed to a
// CommandCenter up to a time. Seeking is rebuilding from the start (the model
// keeps trails and alerts raised on the way, so it cannot go back).
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <variant>
#include <vector>

#include "fireswarm/command_status_t.hpp"
#include "fireswarm/conflict_t.hpp"
#include "fireswarm/fire_track_list_t.hpp"
#include "fireswarm/mission_status_t.hpp"
#include "fireswarm/plan_t.hpp"
#include "fireswarm/radio_stats_t.hpp"
#include "fireswarm/server/command_center.hpp"
#include "fireswarm/vehicle_state_t.hpp"

namespace fireswarm::server {

/// One decoded message of the log.
using ReplayMessage = std::variant<plan_t, vehicle_state_t, fire_track_list_t, mission_status_t,
                                   radio_stats_t, command_status_t, conflict_t>;

/// A message and its time: its own `utime` in seconds (the publisher's clock,
/// docs/lcm.md), not the time the log writer received it.
struct ReplayEvent {
  double time_s = 0.0;
  ReplayMessage message;
};

/// The command center's messages of one LCM log.
class ReplayLog {
 public:
  /// Reads the log at `path`: every event on FIRESWARM_VEHICLE_STATE,
  /// FIRESWARM_FIRE_TRACKS, FIRESWARM_MISSION_STATUS, FIRESWARM_RADIO_STATS,
  /// FIRESWARM_PLAN and FIRESWARM_COMMAND_STATUS, stably sorted by time; other
  /// channels are skipped. Throws std::runtime_error "<path>: <problem>" when the
  /// file does not exist or cannot be read, holds no LCM event at all, or an event
  /// on one of those channels does not decode as its type (e.g. a log written with
  /// another version of the .lcm files).
  static ReplayLog Load(const std::filesystem::path& path);

  const std::vector<ReplayEvent>& events() const { return events_; }
  /// Time of the first and the last event, seconds; 0 for a log without any.
  double start_s() const;
  double end_s() const;
  /// Events on channels the command center does not read.
  std::size_t skipped() const { return skipped_; }
  /// Empty, or what was wrong with the file's tail (bytes after the last event
  /// that held none: a log cut short while it was written); the events before
  /// it are replayed.
  const std::string& warning() const { return warning_; }

  /// Feeds `center` the events from index `next` whose time is <= `until_s`, in
  /// order; returns the index of the first event not fed (events().size() at the end).
  std::size_t Feed(CommandCenter& center, std::size_t next, double until_s) const;

 private:
  std::vector<ReplayEvent> events_;
  std::size_t skipped_ = 0;
  std::string warning_;
};

/// Hands one decoded message to the model's matching On* method.
void Apply(CommandCenter& center, const ReplayMessage& message);

}  // namespace fireswarm::server
