// What became of each operator command the server accepted: an ID (from 1,
// unique for the server's life, a restored one included), its targets and, per
// target, how far the order got over the radio: queued (handed to the radio
// scheduler) -> sent (its request frame went out) -> acknowledged (the vehicle
// accepted it) | failed (refused by the vehicle, or unanswered after every
// resend). A pure record keeper fed with the scheduler's events; the server says
// which radio request carries the command to which target (Track), or sets a
// target's state itself where no single request does (a start: its uploads and
// start commands, server.hpp says how).
//
// Adapters learn what changed by version: every change stamps the record with
// the log's new version(), so an adapter that remembers the last version it
// published publishes the records stamped later.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "fireswarm/radio/master_scheduler.hpp"
#include "fireswarm/server/operator_command.hpp"

namespace fireswarm::server {

/// How far a command got to one target (command_status_t's STATE_* values).
enum class TargetState : std::uint8_t {
  kQueued = 0,        ///< accepted, waiting for the vehicle's radio turn
  kSent = 1,          ///< transmitted, no acknowledgement yet
  kAcknowledged = 2,  ///< the vehicle accepted it
  kFailed = 3,        ///< refused by the vehicle, or unanswered after every resend
};
/// "queued", "sent", "acknowledged", "failed".
const char* ToString(TargetState state);

/// One vehicle a command went to.
struct CommandTarget {
  std::uint8_t vehicle = 0;  ///< receiver ID
  TargetState state = TargetState::kQueued;
  std::string detail;  ///< kFailed: why ("refused by the vehicle: rejected", ...)
};

/// One accepted operator command.
struct CommandRecord {
  std::int32_t id = 0;  ///< from 1
  OperatorCommand::Kind kind = OperatorCommand::Kind::kStart;
  double issued_s = 0.0;               ///< mission time the server accepted it, s
  std::string reason;                  ///< the operator's free text
  std::vector<CommandTarget> targets;  ///< ascending receiver ID
  std::string operator_id;             ///< who signed it; empty: the server's own order
  std::int64_t nonce = 0;              ///< the signed command's nonce
  std::uint64_t version = 0;           ///< CommandLog::version() when it last changed

  /// The command as a whole: acknowledged when every target is (or it has none),
  /// failed once every target is acknowledged or failed and one failed, queued
  /// while every target is, sent otherwise.
  TargetState Summary() const;
};

class CommandLog {
 public:
  /// Records an accepted command with its targets (any order, no duplicates) all
  /// queued; returns its ID.
  std::int32_t Open(OperatorCommand::Kind kind, double issued_s, std::string reason,
                    std::vector<std::uint8_t> targets);
  /// `request` carries command `command_id` to `vehicle`: its RequestSent and
  /// RequestFinished events move that target.
  void Track(std::int32_t command_id, std::uint8_t vehicle, radio::RequestId request);
  /// Moves the targets of tracked requests (other events are ignored).
  void OnEvent(const radio::SchedulerEvent& event);
  /// Moves a target to `state` when that is forward (queued < sent < acknowledged
  /// or failed; a finished target stays as it is). Unknown IDs or vehicles are
  /// ignored.
  void Advance(std::int32_t command_id, std::uint8_t vehicle, TargetState state,
               std::string detail = {});
  /// Command `command_id` was signed by `operator_id` with `nonce` (unknown IDs
  /// are ignored).
  void Attribute(std::int32_t command_id, std::string operator_id, std::int64_t nonce);
  /// IDs up to `id` are taken (a restored journal's commands): the next is above.
  void Reserve(std::int32_t id);

  std::int32_t next_id() const { return next_id_; }
  /// The records in the order they were accepted.
  const std::vector<CommandRecord>& records() const { return records_; }
  /// The record with `id`, or null.
  const CommandRecord* Find(std::int32_t id) const;
  /// Rises with every change; 0 before any.
  std::uint64_t version() const { return version_; }

 private:
  CommandRecord* FindMutable(std::int32_t id);

  std::vector<CommandRecord> records_;
  std::map<radio::RequestId, std::pair<std::int32_t, std::uint8_t>> requests_;  // in flight
  std::int32_t next_id_ = 1;
  std::uint64_t version_ = 0;
};

}  // namespace fireswarm::server
