// The vehicle's side of the poll-and-answer discipline (seed 5.3.1.1): the vehicle
// is the slave and never transmits unless the server gave it the turn, by a Poll
// addressed to it, a SlotSchedule naming it, or (poll mode) a request addressed to
// it. A pure core: bytes and the time in, bursts out; no clock, no socket.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "fireswarm/radio/discipline.hpp"
#include "fireswarm/radio/frame_security.hpp"
#include "fireswarm/radio/messages.hpp"
#include "fireswarm/radio/parser.hpp"
#include "fireswarm/radio/time.hpp"

namespace fireswarm::radio {

/// What the vehicle does with the server's requests. Called from OnReceive(), once
/// per new request (a retry of the last one is answered from the cache). Must not throw.
class VehicleRequestHandler {
 public:
  virtual ~VehicleRequestHandler() = default;
  virtual CommandResult OnCommand(const Command& command) = 0;
  virtual MissionAckStatus OnMissionChunk(const MissionChunk& chunk) = 0;
  /// Returns the value and status; the endpoint fills in header and param_id.
  virtual ParamValue OnParamRead(const ParamRead& read) = 0;
  /// Writes (and persists) the parameter; returns the value now held and the status.
  virtual ParamValue OnParamWrite(const ParamWrite& write) = 0;
  /// Called on every telemetry reply, before it is sent: fills in what the
  /// handler leaves out of SetTelemetry() because it costs more to keep current
  /// than to work out once per reply (the vehicle's latitude and longitude: it
  /// updates its telemetry ten times a second, and a crowded channel asks for it
  /// every few seconds).
  virtual void CompleteTelemetry(Telemetry& /*telemetry*/) const {}
};

struct VehicleEndpointConfig {
  std::uint8_t id = 1;  ///< this vehicle's receiver ID, 1..254
  /// kPoll: a request addressed to this vehicle gives it the turn at once.
  /// kSlots: the answer waits for a kAck slot. Must match the server's mode.
  LinkMode mode = LinkMode::kSlots;
  ChecksumMode checksum = ChecksumMode::kCrc16;
  /// Secure mode: this vehicle's keys, counter and replay windows (self_id == id).
  /// Required when checksum is kSecure; shared so the owner can persist and inspect it.
  std::shared_ptr<FrameSecurity> security;
  LinkTiming timing;
  /// Unacknowledged fire reports kept; beyond it the oldest is dropped (counted).
  std::size_t max_queued_reports = 256;
  /// Throws std::invalid_argument naming the field when a value is out of range.
  void Validate() const;
};

struct VehicleEndpointStats {
  std::uint64_t frames_for_me = 0;         ///< valid frames addressed to this vehicle
  std::uint64_t broadcast_frames = 0;      ///< valid frames addressed to 255
  std::uint64_t payload_bytes_for_me = 0;  ///< data bytes of frames addressed to this vehicle
  std::uint64_t decode_errors = 0;         ///< frames for me whose payload did not decode
  /// Secure mode: frames for me refused (bad tag, replay, no key); not handled.
  std::uint64_t refused_frames = 0;
  /// Secure mode: replies not sent because they could not be sealed.
  std::uint64_t seal_failures = 0;
  std::uint64_t replies_sent = 0;        ///< frames transmitted
  std::uint64_t requests_handled = 0;    ///< requests passed to the handler
  std::uint64_t duplicate_requests = 0;  ///< retries answered from the cached ack
  std::uint64_t reports_queued = 0;
  std::uint64_t reports_acked = 0;
  std::uint64_t reports_dropped = 0;  ///< overflowed max_queued_reports
  std::uint64_t turns_skipped = 0;    ///< turns not taken: late, overlapping or too small
};

/// The last request a vehicle handled and its answer: a retry of it (same message
/// ID and sequence) is answered from here, not executed again.
struct HandledRequest {
  MessageId id{};
  std::uint16_t sequence = 0;
  Message ack;
};

/// What a vehicle keeps across a restart of its software (its non-volatile
/// storage, agents::NonVolatileStore): the counters the server tells its frames
/// and reports apart by, the fire reports not yet acknowledged (re-sent with
/// their IDs after the restart) and the last request handled (a retry of it is
/// not executed twice).
struct VehicleEndpointState {
  std::uint16_t next_report_id = 0;
  std::uint16_t next_sequence = 0;
  std::vector<FireReport> reports;  ///< oldest first, unacknowledged
  std::optional<HandledRequest> last_request;
};

class VehicleEndpoint {
 public:
  /// `handler` must outlive the endpoint. Throws std::invalid_argument when the
  /// configuration is invalid.
  VehicleEndpoint(const VehicleEndpointConfig& config, VehicleRequestHandler& handler);

  /// Feeds the bytes received up to `now` (the end of their reception) and returns
  /// the replies this vehicle was given turns for, in start order: a Poll or (poll
  /// mode) a request -> now + turnaround; a SlotSchedule slot -> its computed start,
  /// if the reply fits in slot_bytes and the start is at least now + turnaround.
  /// A turn in a frame that surfaces only in a later call (the parser held it back
  /// behind a corrupted length) has passed and is not taken. Never throws.
  std::vector<Burst> OnReceive(Nanos now, std::span<const std::uint8_t> bytes);

  /// Latest vehicle state, sent when given a telemetry turn. The endpoint sets the
  /// header, kReportPending and pending_reports.
  void SetTelemetry(const Telemetry& telemetry);

  /// Queues a fire report until the server acknowledges it; resends keep its ID.
  /// Returns the report_id assigned (per vehicle, counting from 0); the header and
  /// report_id of `report` are overwritten.
  std::uint16_t QueueFireReport(const FireReport& report);

  std::size_t pending_reports() const { return reports_.size(); }

  /// The state a restart must keep (see VehicleEndpointState).
  VehicleEndpointState state() const;
  /// Takes over `state` kept from before a restart. Never throws; reports beyond
  /// max_queued_reports are dropped oldest first (counted).
  void Restore(const VehicleEndpointState& state);
  /// Counts every change of state(): a caller that keeps it saves it when this moved.
  std::uint64_t state_changes() const { return state_changes_; }
  const VehicleEndpointConfig& config() const { return config_; }
  const VehicleEndpointStats& stats() const { return stats_; }
  const ParserStats& parser_stats() const { return parser_.stats(); }

 private:
  struct Received {
    Message message;
    Nanos frame_end;  // when its last byte arrived
    bool for_me;      // addressed to this vehicle (else broadcast)
    bool fresh;       // its last byte came in this call: a turn it gives is still open
  };

  std::vector<Received> Parse(Nanos now, std::span<const std::uint8_t> bytes);
  void Handle(const Received& frame, Nanos now, std::vector<Burst>& out);
  void HandleRequest(const Message& request);
  void HandleSchedule(const SlotSchedule& schedule, Nanos schedule_end, Nanos now,
                      std::vector<Burst>& out);
  std::optional<Message> ReplyFor(ReplyKind kind, std::size_t report_index) const;
  void Send(Message reply, Nanos start, std::size_t max_bytes, Nanos now, std::vector<Burst>& out);
  Message AckFor(const Message& request);

  VehicleEndpointConfig config_;
  VehicleRequestHandler& handler_;
  FrameParser parser_;
  std::vector<std::uint8_t> opened_;  // secure mode: the decrypted data of the current frame
  Telemetry telemetry_;
  std::deque<FireReport> reports_;  // oldest first, unacknowledged
  std::uint16_t next_report_id_ = 0;
  std::uint16_t next_sequence_ = 0;
  std::optional<HandledRequest> last_request_;
  Nanos transmitting_until_{0};  // end of the latest burst handed out
  std::uint64_t state_changes_ = 0;
  VehicleEndpointStats stats_;
};

}  // namespace fireswarm::radio
