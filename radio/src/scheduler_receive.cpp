// Replies in: telemetry, fire reports and acks update the vehicle's state and the
// exchange's expectations; an exchange that ends with replies missing counts them,
// and retries or fails the requests they answered.
#include <algorithm>
#include <initializer_list>
#include <variant>

#include "scheduler_state.hpp"

namespace fireswarm::radio::internal {
namespace {

// Marks the first unmet expectation of `vehicle` among `kinds` (in that order of
// preference) as met. Telemetry also answers a report turn: it is what a vehicle
// sends there when it has nothing left to report.
void MarkMet(SchedulerState& state, std::uint8_t vehicle, std::initializer_list<ReplyKind> kinds) {
  if (!state.exchange) return;
  for (const ReplyKind kind : kinds) {
    for (Expectation& e : state.exchange->expected) {
      if (!e.met && e.vehicle == vehicle && e.kind == kind) {
        e.met = true;
        return;
      }
    }
  }
}

void OnTelemetry(SchedulerState& state, VehicleState& v, const Telemetry& telemetry, Nanos now) {
  ++state.stats.telemetry;
  // The vehicle still counts reports whose ack is in our next burst.
  const int owed = static_cast<int>(v.acks_owed.size());
  v.reports_pending = std::max(0, int{telemetry.pending_reports} - owed);
  // Served on time or early (within the window): advance on the period grid so the
  // rate holds. A vehicle late by more than a period does not catch up the backlog.
  std::optional<Nanos> served_due;
  if (now >= v.next_telemetry_due - EarlyWindow(state.config, v)) {
    served_due = v.next_telemetry_due;
    v.next_telemetry_due = std::max(v.next_telemetry_due + v.period, now);
  }
  MarkMet(state, v.id, {ReplyKind::kTelemetry, ReplyKind::kFireReport});
  state.events.emplace_back(TelemetryReceived{v.id, now, telemetry, served_due});
}

void OnFireReport(SchedulerState& state, VehicleState& v, const FireReport& report, Nanos now) {
  // Every receipt is acknowledged, a resend too: it means our last ack was lost.
  if (std::find(v.acks_owed.begin(), v.acks_owed.end(), report.report_id) == v.acks_owed.end()) {
    v.acks_owed.push_back(report.report_id);
  }
  v.reports_pending = std::max(0, v.reports_pending - 1);
  if (v.reports_seen.insert(report.report_id).second) {
    ++state.stats.fire_reports;
    state.events.emplace_back(FireReportReceived{v.id, now, report});
  } else {
    ++state.stats.duplicate_reports;
  }
  MarkMet(state, v.id, {ReplyKind::kFireReport});
}

// Whether `ack` answers `request`; a stale ack (the vehicle answers a kAck turn
// with its cached ack when our request was lost) must not complete the new one.
bool AckMatches(const Message& request, const Message& ack) {
  if (const auto* command = std::get_if<Command>(&request)) {
    const auto* command_ack = std::get_if<CommandAck>(&ack);
    return command_ack != nullptr && command_ack->acked_sequence == command->header.sequence;
  }
  if (const auto* chunk = std::get_if<MissionChunk>(&request)) {
    const auto* mission_ack = std::get_if<MissionAck>(&ack);
    return mission_ack != nullptr && mission_ack->mission_id == chunk->mission_id &&
           mission_ack->chunk_index == chunk->chunk_index;
  }
  const auto* value = std::get_if<ParamValue>(&ack);
  if (value == nullptr) return false;
  if (const auto* read = std::get_if<ParamRead>(&request)) return value->param_id == read->param_id;
  return value->param_id == std::get<ParamWrite>(request).param_id;
}

void OnAck(SchedulerState& state, VehicleState& v, const Message& ack, Nanos now) {
  if (v.requests.empty() || !v.requests.front().sent) return;
  const PendingRequest& request = v.requests.front();
  if (!AckMatches(request.message, ack)) return;
  state.events.emplace_back(
      RequestFinished{request.id, v.id, RequestStatus::kCompleted, ack, request.retries, now});
  ++state.stats.requests_completed;
  v.requests.pop_front();
  MarkMet(state, v.id, {ReplyKind::kAck});
}

// Whether the current exchange gave `vehicle` a turn (a slot or a poll).
bool HasTurn(const SchedulerState& state, std::uint8_t vehicle) {
  return state.exchange &&
         std::any_of(state.exchange->expected.begin(), state.exchange->expected.end(),
                     [&](const Expectation& e) { return e.vehicle == vehicle; });
}

void OnFrame(SchedulerState& state, const FrameView& frame, Nanos now) {
  if (frame.receiver != kServerId) return;
  const OpenedData opened =
      OpenFrameData(frame, state.config.checksum, state.config.security.get(), state.opened);
  if (opened.status != OpenStatus::kOk) {
    ++state.stats.refused_frames;
    return;
  }
  state.stats.payload_bytes += opened.data.size();
  const DecodeResult decoded = DecodePayload(frame.message_id, opened.data);
  if (!decoded.message) {
    ++state.stats.decode_errors;
    return;
  }
  const Message& message = *decoded.message;
  const std::uint8_t sender = HeaderOf(message).sender;
  // A vehicle's key speaks only for that vehicle: a captured vehicle cannot pose
  // as another one.
  if (state.config.checksum == ChecksumMode::kSecure && sender != FrameSecurity::KeyIdOf(frame)) {
    ++state.stats.refused_frames;
    return;
  }
  const auto found = state.vehicles.find(sender);
  if (found == state.vehicles.end()) {
    ++state.stats.unknown_senders;
    return;
  }
  if (!HasTurn(state, sender)) {
    ++state.stats.out_of_turn;
    return;
  }
  VehicleState& v = found->second;
  ++state.stats.replies;
  v.last_heard = now;
  v.consecutive_missed = 0;
  v.silent = false;
  if (const auto* telemetry = std::get_if<Telemetry>(&message)) {
    OnTelemetry(state, v, *telemetry, now);
  } else if (const auto* report = std::get_if<FireReport>(&message)) {
    OnFireReport(state, v, *report, now);
  } else if (std::holds_alternative<CommandAck>(message) ||
             std::holds_alternative<MissionAck>(message) ||
             std::holds_alternative<ParamValue>(message)) {
    OnAck(state, v, message, now);
  }
}

void RetryOrFail(SchedulerState& state, VehicleState& v, Nanos now) {
  if (v.requests.empty() || !v.requests.front().sent) return;
  PendingRequest& request = v.requests.front();
  if (request.retries < state.config.max_retries) {
    // Resent with the same sequence number, so the vehicle does not execute it twice.
    ++request.retries;
    ++state.stats.retries;
    return;
  }
  state.events.emplace_back(RequestFinished{request.id, v.id, RequestStatus::kFailed, std::nullopt,
                                            request.retries, now});
  ++state.stats.requests_failed;
  v.requests.pop_front();
}

}  // namespace

void ReceiveReplies(SchedulerState& state, Nanos now, std::span<const std::uint8_t> bytes) {
  state.parser.Feed(bytes, [&](const FrameView& frame) { OnFrame(state, frame, now); });
}

void FlushReplies(SchedulerState& state, Nanos now) {
  state.parser.Finish([&](const FrameView& frame) { OnFrame(state, frame, now); });
}

bool AllRepliesIn(const Exchange& exchange) {
  return !exchange.expected.empty() &&
         std::all_of(exchange.expected.begin(), exchange.expected.end(),
                     [](const Expectation& e) { return e.met; });
}

void CloseExchange(SchedulerState& state, Nanos now) {
  for (const Expectation& e : state.exchange->expected) {
    if (e.met) continue;
    ++state.stats.missed_replies;
    VehicleState& v = state.vehicles.at(e.vehicle);
    if (++v.consecutive_missed >= state.config.silent_after_missed_replies && !v.silent) {
      v.silent = true;
      state.events.emplace_back(VehicleSilent{v.id, v.last_heard});
    }
    // A missing telemetry or report reply leaves the vehicle due; a missing ack
    // costs the request a retry.
    if (e.kind == ReplyKind::kAck) RetryOrFail(state, v, now);
  }
  state.exchange.reset();
  state.ready_at = now;
}

}  // namespace fireswarm::radio::internal
