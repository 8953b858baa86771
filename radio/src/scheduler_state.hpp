// Private state of the MasterScheduler and the free functions over it, split by
// concern: scheduler_receive.cpp (replies in, exchanges closed), scheduler_plan.cpp
// (who gets the next turn), master_scheduler.cpp (API and Step()).
#pragma once

#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <set>
#include <span>
#include <vector>

#include "fireswarm/radio/master_scheduler.hpp"

namespace fireswarm::radio::internal {

struct PendingRequest {
  RequestId id = 0;
  Message message;  // header.sequence is set when first sent, kept on resends
  bool sent = false;
  int retries = 0;
  bool urgent = false;  // goes before every report and every other request
};

struct VehicleState {
  std::uint8_t id = 0;
  Nanos period{0};              // between telemetry turns
  Nanos next_telemetry_due{0};  // on the grid first_due + k * period while kept up
  int reports_pending = 0;      // estimate: unacknowledged reports the vehicle holds
  Nanos last_report_turn = Nanos::min();
  Nanos last_request_turn = Nanos::min();
  std::vector<std::uint16_t> acks_owed;  // report IDs to acknowledge in the next burst
  std::set<std::uint16_t> reports_seen;
  std::deque<PendingRequest> requests;  // front is the outstanding one
  Nanos last_heard{-1};
  int consecutive_missed = 0;
  bool silent = false;
};

struct Expectation {
  std::uint8_t vehicle = 0;
  ReplyKind kind = ReplyKind::kTelemetry;
  bool met = false;
};

struct Exchange {
  ExchangeTiming timing;
  std::vector<Expectation> expected;
};

struct SchedulerState {
  explicit SchedulerState(const SchedulerConfig& c)
      : config(c), parser(c.checksum), next_sequence(c.first_sequence) {}

  SchedulerConfig config;
  FrameParser parser;
  std::vector<std::uint8_t> opened;  // secure mode: the decrypted data of the current frame
  std::map<std::uint8_t, VehicleState> vehicles;  // ordered: deterministic iteration
  std::optional<Exchange> exchange;
  Nanos ready_at{0};                   // no burst may be decided before this
  bool last_turn_was_request = false;  // poll mode: alternate requests with telemetry
  std::uint16_t next_sequence;
  RequestId next_request_id = 1;
  std::vector<SchedulerEvent> events;
  SchedulerStats stats;
};

// --- scheduler_receive.cpp
/// Parses `bytes` and applies every reply addressed to the server.
void ReceiveReplies(SchedulerState& state, Nanos now, std::span<const std::uint8_t> bytes);
/// End of the replies' window: a partial frame still buffered (a corrupted length
/// makes the parser wait for bytes that will not come) is dropped, and the valid
/// frames it held back are applied.
void FlushReplies(SchedulerState& state, Nanos now);
/// True when every expected reply of the exchange arrived (false for none expected).
bool AllRepliesIn(const Exchange& exchange);
/// Ends the exchange: missing replies are counted, requests retried or failed.
void CloseExchange(SchedulerState& state, Nanos now);

// --- scheduler_plan.cpp
/// Reports pending, acks owed or requests queued: a reason to transmit at once.
bool HasUrgentWork(const SchedulerState& state);
/// Earliest telemetry due time over all vehicles; Nanos::max() with none.
Nanos EarliestTelemetryDue(const SchedulerState& state);
/// How early a vehicle may be served with telemetry (slots mode) or counted as
/// served (both modes): early_fraction of its period.
Nanos EarlyWindow(const SchedulerConfig& config, const VehicleState& vehicle);
/// Builds the next burst and opens its exchange; nullopt when there is nothing to send.
std::optional<Burst> PlanBurst(SchedulerState& state, Nanos now);

}  // namespace fireswarm::radio::internal
