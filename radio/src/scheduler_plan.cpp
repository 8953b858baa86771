// Who gets the next turn. Priorities, both modes: (1) report turns for vehicles known
// to hold unacknowledged fire reports, (2) owed FireReportAcks at the head of the
// burst, (3) the outstanding request of each vehicle, (4) telemetry, most overdue
// first. Poll mode gives one turn per burst; slots mode fills one SlotSchedule.
#include <algorithm>
#include <tuple>

#include "scheduler_state.hpp"

namespace fireswarm::radio::internal {
namespace {

constexpr Nanos kMicrosecond = std::chrono::microseconds(1);

Nanos AirtimeOf(const SchedulerState& state, std::size_t bytes) {
  return state.config.timing.AirtimeOf(bytes);
}

std::size_t FrameBytes(const SchedulerState& state, MessageId id, std::size_t entries = 0) {
  return MessageFrameSize(id, state.config.checksum, entries);
}

// A report turn is answered with telemetry when nothing is left to report.
std::size_t ReportReplyBytes(const SchedulerState& state) {
  return std::max(FrameBytes(state, MessageId::kFireReport),
                  FrameBytes(state, MessageId::kTelemetry));
}

std::uint32_t CeilMicros(Nanos t) {
  return static_cast<std::uint32_t>((t + kMicrosecond - Nanos{1}) / kMicrosecond);
}

void AppendFrom(SchedulerState& state, std::vector<std::uint8_t>& out, std::uint8_t receiver,
                Message message) {
  std::visit([&](auto& m) { m.header = MessageHeader{kServerId, state.next_sequence++}; }, message);
  if (AppendFrameFor(out, receiver, message, state.config.checksum, state.config.security.get()) !=
      SealStatus::kOk) {
    ++state.stats.seal_failures;
  }
}

void AppendOwedAcks(SchedulerState& state, std::vector<std::uint8_t>& out) {
  for (auto& [id, v] : state.vehicles) {
    for (const std::uint16_t report_id : v.acks_owed) {
      AppendFrom(state, out, id, FireReportAck{{}, id, report_id});
      ++state.stats.report_acks_sent;
    }
    v.acks_owed.clear();
  }
}

// The vehicle's outstanding request as a frame: its sequence number is taken when
// first sent and kept on every resend.
// A request that cannot be sealed (no key for the vehicle) is empty: it goes out as
// nothing, gets no ack and fails after its retries, as a lost one would.
std::vector<std::uint8_t> RequestFrame(SchedulerState& state, const VehicleState& v) {
  Message message = v.requests.front().message;
  if (!v.requests.front().sent) {
    std::visit([&](auto& m) { m.header.sequence = state.next_sequence; }, message);
  }
  std::vector<std::uint8_t> frame;
  if (AppendFrameFor(frame, v.id, message, state.config.checksum, state.config.security.get()) !=
      SealStatus::kOk) {
    ++state.stats.seal_failures;
  }
  return frame;
}

// Commits RequestFrame() to the burst planned at `now` (it starts one turnaround
// later): marks the request sent and says so; returns the ID of its ack.
MessageId MarkRequestSent(SchedulerState& state, VehicleState& v, Nanos now) {
  PendingRequest& request = v.requests.front();
  if (!request.sent) {
    std::visit([&](auto& m) { m.header.sequence = state.next_sequence++; }, request.message);
    request.sent = true;
  }
  ++state.stats.requests_sent;
  v.last_request_turn = now;
  state.events.emplace_back(
      RequestSent{request.id, v.id, request.retries, now + state.config.timing.turnaround});
  return *AckIdFor(IdOf(request.message));
}

// Vehicles to give a report turn, least recently served first (fair among them).
// Silent ones are left out: they would take a turn every cycle.
std::vector<VehicleState*> ReportCandidates(SchedulerState& state) {
  std::vector<VehicleState*> out;
  for (auto& [id, v] : state.vehicles) {
    if (v.reports_pending > 0 && !v.silent) out.push_back(&v);
  }
  std::sort(out.begin(), out.end(), [](const VehicleState* a, const VehicleState* b) {
    return std::tie(a->last_report_turn, a->id) < std::tie(b->last_report_turn, b->id);
  });
  return out;
}

std::vector<VehicleState*> RequestCandidates(SchedulerState& state) {
  std::vector<VehicleState*> out;
  for (auto& [id, v] : state.vehicles) {
    if (!v.requests.empty()) out.push_back(&v);
  }
  // Urgent ones first (a conflict's resolution), then round robin.
  std::sort(out.begin(), out.end(), [](const VehicleState* a, const VehicleState* b) {
    return std::tuple(!a->requests.front().urgent, a->last_request_turn, a->id) <
           std::tuple(!b->requests.front().urgent, b->last_request_turn, b->id);
  });
  return out;
}

// Vehicles due for telemetry by `now` (plus their early window when `early`), most
// overdue first.
std::vector<VehicleState*> TelemetryCandidates(SchedulerState& state, Nanos now, bool early) {
  std::vector<VehicleState*> out;
  for (auto& [id, v] : state.vehicles) {
    const Nanos horizon = early ? EarlyWindow(state.config, v) : Nanos::zero();
    if (v.next_telemetry_due <= now + horizon) out.push_back(&v);
  }
  std::sort(out.begin(), out.end(), [](const VehicleState* a, const VehicleState* b) {
    return std::tie(a->next_telemetry_due, a->id) < std::tie(b->next_telemetry_due, b->id);
  });
  return out;
}

void OpenExchange(SchedulerState& state, const Burst& burst, std::vector<Expectation> expected,
                  Nanos deadline) {
  const Nanos end = burst.start + AirtimeOf(state, burst.bytes.size());
  ExchangeTiming timing{burst.start, end, std::max(deadline, end), expected.size()};
  state.exchange = Exchange{timing, std::move(expected)};
}

enum class TurnKind : std::uint8_t { kNone, kReport, kRequest, kTelemetry };

struct PollTurn {
  TurnKind kind = TurnKind::kNone;
  VehicleState* vehicle = nullptr;
};

// One turn by priority. A request turn is followed by a due telemetry turn (when
// request_share > 0) so that a bulk upload does not blind the server to the fleet.
PollTurn ChoosePollTurn(SchedulerState& state, Nanos now) {
  for (VehicleState* v : RequestCandidates(state)) {
    if (v->requests.front().urgent) return {TurnKind::kRequest, v};
  }
  if (const auto reports = ReportCandidates(state); !reports.empty()) {
    return {TurnKind::kReport, reports.front()};
  }
  const auto requests = RequestCandidates(state);
  const auto due = TelemetryCandidates(state, now, false);
  const bool telemetry_first = state.last_turn_was_request && state.config.request_share > 0.0;
  if (!requests.empty() && !(telemetry_first && !due.empty())) {
    return {TurnKind::kRequest, requests.front()};
  }
  if (!due.empty()) return {TurnKind::kTelemetry, due.front()};
  return {};
}

std::optional<Burst> PlanPoll(SchedulerState& state, Nanos now) {
  Burst burst{now + state.config.timing.turnaround, {}};
  AppendOwedAcks(state, burst.bytes);
  const PollTurn turn = ChoosePollTurn(state, now);
  std::vector<Expectation> expected;
  std::size_t reply_bytes = 0;
  if (turn.kind == TurnKind::kReport) {
    AppendFrom(state, burst.bytes, turn.vehicle->id, Poll{{}, ReplyKind::kFireReport});
    ++state.stats.polls;
    turn.vehicle->last_report_turn = now;
    expected.push_back({turn.vehicle->id, ReplyKind::kFireReport});
    reply_bytes = ReportReplyBytes(state);
  } else if (turn.kind == TurnKind::kRequest) {
    const std::vector<std::uint8_t> frame = RequestFrame(state, *turn.vehicle);
    burst.bytes.insert(burst.bytes.end(), frame.begin(), frame.end());
    expected.push_back({turn.vehicle->id, ReplyKind::kAck});
    reply_bytes = FrameBytes(state, MarkRequestSent(state, *turn.vehicle, now));
  } else if (turn.kind == TurnKind::kTelemetry) {
    AppendFrom(state, burst.bytes, turn.vehicle->id, Poll{{}, ReplyKind::kTelemetry});
    ++state.stats.polls;
    expected.push_back({turn.vehicle->id, ReplyKind::kTelemetry});
    reply_bytes = FrameBytes(state, MessageId::kTelemetry);
  }
  state.last_turn_was_request = turn.kind == TurnKind::kRequest;
  if (burst.bytes.empty()) return std::nullopt;
  // The vehicle answers one turnaround after our last byte; the reply cannot be
  // longer than the largest frame it may send for this turn.
  const Nanos end = burst.start + AirtimeOf(state, burst.bytes.size());
  const Nanos deadline = expected.empty()
                             ? end
                             : end + state.config.timing.turnaround +
                                   AirtimeOf(state, reply_bytes) + state.config.reply_margin;
  state.stats.slots_granted += expected.size();
  OpenExchange(state, burst, std::move(expected), deadline);
  return burst;
}

// Slots of one cycle under the cycle airtime budget.
struct SlotsCycle {
  const SchedulerState& state;
  std::size_t head_bytes;  // acks and requests before the schedule
  std::vector<Slot> slots;
  Nanos slots_airtime{0};  // sum of (slot airtime + guard)

  bool Fits(std::size_t slot_bytes, std::size_t extra_head_bytes) const {
    if (slots.size() >= state.config.max_slots) return false;
    if (slots.empty()) return true;
    const std::size_t burst_bytes = head_bytes + extra_head_bytes +
                                    FrameBytes(state, MessageId::kSlotSchedule, slots.size() + 1);
    const Nanos cycle = AirtimeOf(state, burst_bytes) + state.config.timing.turnaround +
                        slots_airtime + AirtimeOf(state, slot_bytes) + state.config.slot_guard;
    return cycle <= state.config.max_cycle_airtime;
  }
  void Add(std::uint8_t vehicle, ReplyKind kind, std::size_t slot_bytes, std::size_t extra) {
    head_bytes += extra;
    slots_airtime += AirtimeOf(state, slot_bytes) + state.config.slot_guard;
    slots.push_back(Slot{vehicle, kind, static_cast<std::uint8_t>(slot_bytes)});
  }
};

void AddReportSlots(SchedulerState& state, SlotsCycle& cycle, Nanos now) {
  const std::size_t bytes = ReportReplyBytes(state);
  for (VehicleState* v : ReportCandidates(state)) {
    const auto turns = std::min<std::size_t>(static_cast<std::size_t>(v->reports_pending),
                                             state.config.max_report_slots_per_vehicle);
    for (std::size_t i = 0; i < turns; ++i) {
      if (!cycle.Fits(bytes, 0)) return;
      cycle.Add(v->id, ReplyKind::kFireReport, bytes, 0);
      v->last_report_turn = now;
    }
  }
}

// Urgent requests take their slots first and outside request_share; `urgent_only`
// adds only those, a later call the others.
void AddRequestSlots(SchedulerState& state, SlotsCycle& cycle, std::vector<std::uint8_t>& out,
                     Nanos now, bool urgent_only) {
  const auto share = Nanos{static_cast<std::int64_t>(
      state.config.request_share * static_cast<double>(state.config.max_cycle_airtime.count()))};
  Nanos used{0};  // request frames and their ack slots
  bool any = false;
  for (VehicleState* v : RequestCandidates(state)) {
    const bool urgent = v->requests.front().urgent;
    if (urgent_only && !urgent) return;  // the urgent ones come first
    const bool in_cycle = std::any_of(cycle.slots.begin(), cycle.slots.end(), [&](const Slot& s) {
      return s.receiver == v->id && s.reply == ReplyKind::kAck;
    });
    if (in_cycle) continue;
    const std::vector<std::uint8_t> frame = RequestFrame(state, *v);
    const std::size_t ack_bytes = FrameBytes(state, *AckIdFor(IdOf(v->requests.front().message)));
    const Nanos cost = AirtimeOf(state, frame.size() + ack_bytes) + state.config.slot_guard;
    if (!urgent && any && used + cost > share) return;
    if (!cycle.Fits(ack_bytes, frame.size())) return;
    out.insert(out.end(), frame.begin(), frame.end());
    MarkRequestSent(state, *v, now);
    cycle.Add(v->id, ReplyKind::kAck, ack_bytes, frame.size());
    used += cost;
    any = true;
  }
}

std::optional<Burst> PlanSlots(SchedulerState& state, Nanos now) {
  Burst burst{now + state.config.timing.turnaround, {}};
  AppendOwedAcks(state, burst.bytes);
  SlotsCycle cycle{state, burst.bytes.size(), {}, Nanos{0}};
  AddRequestSlots(state, cycle, burst.bytes, now, true);
  AddReportSlots(state, cycle, now);
  AddRequestSlots(state, cycle, burst.bytes, now, false);
  // Vehicles due soon fill the cycle now rather than open one of their own later.
  const std::size_t telemetry_bytes = FrameBytes(state, MessageId::kTelemetry);
  for (const VehicleState* v : TelemetryCandidates(state, now, true)) {
    if (!cycle.Fits(telemetry_bytes, 0)) break;
    cycle.Add(v->id, ReplyKind::kTelemetry, telemetry_bytes, 0);
  }
  if (cycle.slots.empty()) {
    if (burst.bytes.empty()) return std::nullopt;
    OpenExchange(state, burst, {}, Nanos{0});
    return burst;
  }
  SlotSchedule schedule;
  schedule.first_slot_delay_us = CeilMicros(state.config.timing.turnaround);
  schedule.guard_us = CeilMicros(state.config.slot_guard);
  schedule.slot_count = static_cast<std::uint8_t>(cycle.slots.size());
  std::copy(cycle.slots.begin(), cycle.slots.end(), schedule.slots.begin());
  AppendFrom(state, burst.bytes, kBroadcastId, schedule);
  ++state.stats.schedules;
  state.stats.slots_granted += cycle.slots.size();

  std::vector<Expectation> expected;
  for (const Slot& slot : cycle.slots) expected.push_back({slot.receiver, slot.reply});
  const Nanos end = burst.start + AirtimeOf(state, burst.bytes.size());
  const Nanos last_slot_end = SlotEnd(schedule, cycle.slots.size() - 1, end, state.config.timing);
  OpenExchange(state, burst, std::move(expected), last_slot_end + state.config.reply_margin);
  return burst;
}

}  // namespace

Nanos EarlyWindow(const SchedulerConfig& config, const VehicleState& vehicle) {
  return Nanos{static_cast<std::int64_t>(config.early_fraction *
                                         static_cast<double>(vehicle.period.count()))};
}

bool HasUrgentWork(const SchedulerState& state) {
  return std::any_of(state.vehicles.begin(), state.vehicles.end(), [](const auto& entry) {
    const VehicleState& v = entry.second;
    return !v.acks_owed.empty() || !v.requests.empty() || (v.reports_pending > 0 && !v.silent);
  });
}

Nanos EarliestTelemetryDue(const SchedulerState& state) {
  Nanos earliest = Nanos::max();
  for (const auto& [id, v] : state.vehicles) earliest = std::min(earliest, v.next_telemetry_due);
  return earliest;
}

std::optional<Burst> PlanBurst(SchedulerState& state, Nanos now) {
  return state.config.mode == LinkMode::kPoll ? PlanPoll(state, now) : PlanSlots(state, now);
}

}  // namespace fireswarm::radio::internal
