// The run loop of `fireswarm serve`: the pure server core (server::Server) on the
// wall clock against a real link, with its edges: the journal every entry is
// appended to (durable before the next step), the LCM bridge, and one JSON line
// on stdout per mission event.
//
// The mission clock is the steady clock since the loop started plus an offset: 0
// for a new mission; for a server restored from its journal, the time of the
// journal's last record, so the restored server's clock goes on where the killed
// one's stopped (investigation deadlines and track times stay in one time line).
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "fireswarm/common/time.hpp"
#include "fireswarm/radio/frame.hpp"
#include "fireswarm/radio/frame_security.hpp"
#include "fireswarm/radio/link.hpp"
#include "fireswarm/radio/parser.hpp"
#include "fireswarm/server/journal.hpp"
#include "fireswarm/server/journal_format.hpp"
#include "fireswarm/server/lcm_bridge.hpp"
#include "fireswarm/server/server.hpp"

namespace fireswarm::app {

struct ServeOptions {
  common::Nanos clock_offset{0};     ///< mission clock when the loop starts
  std::optional<double> duration_s;  ///< stop after this much wall time, s
  bool until_complete = false;       ///< stop once the mission is complete or aborted
  /// Called after every step with the mission clock and the LCM utime of now and
  /// of mission time 0 (the web feed); it may hand the server operator commands.
  /// Empty: none.
  std::function<void(common::Nanos now, std::int64_t utime, std::int64_t utime_at_zero)> on_step;
  /// The loop wakes at least this often (the web feed's period), s.
  double max_wait_s = 0.05;
};

/// Why the loop stopped.
enum class ServeStop : std::uint8_t { kSignal, kDuration, kComplete, kAborted };
const char* ToString(ServeStop stop);

class ServeLoop {
 public:
  /// Everything given must outlive the loop; `journal` and `bridge` may be null.
  /// `links`: one per radio channel of the server (link k carries channel k).
  /// A link whose reads fail (a modem unplugged) is reported on stdout
  /// ({"event": "link_failed", "channel": k, ...}) and no longer used: its channel
  /// goes silent and its vehicles lost, the other channels fly on.
  ServeLoop(server::Server& server, std::vector<radio::IoLink*> links, server::Journal* journal,
            server::LcmBridge* bridge);

  /// Appends the server's pending journal entries (and prints them), at `t_s`.
  /// Throws as Journal::Append.
  void FlushJournal();

  /// Runs until a stop condition holds. Throws as the link, the journal and the bridge.
  ServeStop Run(const ServeOptions& options);

  /// The figures at the end: state, per-vehicle phase, tracks, frames sent by type,
  /// radio counters, wall time.
  nlohmann::ordered_json Summary() const;

 private:
  void CountFrames(const radio::Burst& burst);
  // Secure mode: says on stderr when a vehicle's frames start or stop failing
  // authentication (wrong or missing key), so it is not mistaken for a silent link.
  void WatchAuthentication(common::Nanos now);
  void HandleOperatorCommands(common::Nanos now);
  // One channel's bytes in, its bursts out; a failed link is reported once.
  void StepChannel(std::size_t channel, common::Nanos now, std::vector<std::uint8_t>& received);
  // Waits until a link has bytes or `timeout` passes.
  void WaitReadable(common::Nanos timeout);

  server::Server& server_;
  std::vector<radio::IoLink*> links_;
  std::vector<bool> failed_;  // per link: its reads failed
  server::Journal* journal_;
  server::LcmBridge* bridge_;
  radio::FrameParser sent_parser_;                    // the server's own bursts, to count them
  std::map<std::string, std::uint64_t> frames_sent_;  // by message name
  std::map<std::uint8_t, radio::KeyLinkState> auth_states_;  // last reported, per vehicle
  std::uint64_t journal_appended_ = 0;
  double wall_seconds_ = 0.0;
  double clock_s_ = 0.0;  // mission clock at the end
};

/// The JSON line printed for a journal entry: {"event": kind, "t_s": ..., ...}
/// with phases and states by name; a mission by its drones' waypoint counts.
nlohmann::ordered_json EventLine(const server::JournalEntry& entry);

}  // namespace fireswarm::app
