// MasterScheduler API: configuration, vehicles, requests, and Step(), which glues
// replies in (scheduler_receive.cpp) to the next burst (scheduler_plan.cpp).
#include "fireswarm/radio/master_scheduler.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "scheduler_state.hpp"

namespace fireswarm::radio {
namespace {

using internal::SchedulerState;
using internal::VehicleState;

// SlotSchedule carries first_slot_delay_us and guard_us as u16 microseconds.
constexpr Nanos kMaxWireMicros = std::chrono::microseconds(65'535);

[[noreturn]] void ThrowConfig(const std::string& field, const std::string& requirement) {
  throw std::invalid_argument("SchedulerConfig." + field + " must be " + requirement);
}

Nanos PeriodOf(double telemetry_hz) {
  if (!(std::isfinite(telemetry_hz) && telemetry_hz > 0.0)) {
    throw std::invalid_argument("telemetry rate must be a finite number of Hz > 0, got " +
                                std::to_string(telemetry_hz));
  }
  return Nanos{static_cast<std::int64_t>(std::llround(1e9 / telemetry_hz))};
}

const SchedulerConfig& Validated(const SchedulerConfig& config) {
  config.Validate();
  return config;
}

}  // namespace

void SchedulerConfig::Validate() const {
  if (timing.baud <= 0) ThrowConfig("timing.baud", "> 0");
  if (timing.bits_per_byte <= 0) ThrowConfig("timing.bits_per_byte", "> 0");
  if (timing.turnaround < Nanos::zero()) ThrowConfig("timing.turnaround", ">= 0");
  if (mode == LinkMode::kSlots && timing.turnaround > kMaxWireMicros) {
    ThrowConfig("timing.turnaround", "<= 65.535 ms in slots mode (u16 us on the wire)");
  }
  if (slot_guard < Nanos::zero() || slot_guard > kMaxWireMicros) {
    ThrowConfig("slot_guard", "in [0, 65.535] ms");
  }
  if (reply_margin < Nanos::zero()) ThrowConfig("reply_margin", ">= 0");
  if (max_retries < 0) ThrowConfig("max_retries", ">= 0");
  if (!(std::isfinite(default_telemetry_hz) && default_telemetry_hz > 0.0)) {
    ThrowConfig("default_telemetry_hz", "> 0");
  }
  if (max_slots == 0 || max_slots > kMaxSlots) ThrowConfig("max_slots", "in 1..64");
  if (max_cycle_airtime <= Nanos::zero()) ThrowConfig("max_cycle_airtime", "> 0");
  if (!(early_fraction >= 0.0 && early_fraction < 1.0)) ThrowConfig("early_fraction", "in [0, 1)");
  if (!(request_share >= 0.0 && request_share <= 1.0)) ThrowConfig("request_share", "in [0, 1]");
  if (max_report_slots_per_vehicle == 0) ThrowConfig("max_report_slots_per_vehicle", ">= 1");
  if (silent_after_missed_replies < 1) ThrowConfig("silent_after_missed_replies", ">= 1");
  if (checksum == ChecksumMode::kSecure && !security) ThrowConfig("security", "set in secure mode");
}

MasterScheduler::MasterScheduler(const SchedulerConfig& config)
    : state_(std::make_unique<SchedulerState>(Validated(config))) {}

MasterScheduler::~MasterScheduler() = default;

void MasterScheduler::AddVehicle(std::uint8_t vehicle, double telemetry_hz, Nanos first_due) {
  if (vehicle < kFirstVehicleId || vehicle > kLastVehicleId) {
    throw std::invalid_argument("vehicle ID must be in 1..254, got " + std::to_string(vehicle));
  }
  if (state_->vehicles.contains(vehicle)) {
    throw std::invalid_argument("vehicle " + std::to_string(vehicle) + " is already registered");
  }
  VehicleState added;
  added.id = vehicle;
  added.period = PeriodOf(telemetry_hz > 0.0 ? telemetry_hz : state_->config.default_telemetry_hz);
  added.next_telemetry_due = first_due;
  state_->vehicles.emplace(vehicle, std::move(added));
}

void MasterScheduler::SetTelemetryRate(std::uint8_t vehicle, double telemetry_hz) {
  const auto found = state_->vehicles.find(vehicle);
  if (found == state_->vehicles.end()) {
    throw std::invalid_argument("unknown vehicle " + std::to_string(vehicle));
  }
  VehicleState& v = found->second;
  const Nanos period = PeriodOf(telemetry_hz);
  // Re-anchor the grid on the last turn so a slower rate takes effect at once.
  v.next_telemetry_due += period - v.period;
  v.period = period;
}

double MasterScheduler::TelemetryRateHz(std::uint8_t vehicle) const {
  const auto found = state_->vehicles.find(vehicle);
  if (found == state_->vehicles.end()) {
    throw std::invalid_argument("unknown vehicle " + std::to_string(vehicle));
  }
  return 1e9 / static_cast<double>(found->second.period.count());
}

namespace {

RequestId Enqueue(SchedulerState& state, std::uint8_t vehicle, Message request,
                  bool urgent = false) {
  const auto found = state.vehicles.find(vehicle);
  if (found == state.vehicles.end()) {
    throw std::invalid_argument("request for unknown vehicle " + std::to_string(vehicle));
  }
  const RequestId id = state.next_request_id++;
  std::visit([](auto& payload) { payload.header = MessageHeader{kServerId, 0}; }, request);
  std::deque<internal::PendingRequest>& queue = found->second.requests;
  internal::PendingRequest pending{id, std::move(request), false, 0, urgent};
  if (!urgent) {
    queue.push_back(std::move(pending));
    return id;
  }
  // Behind the one in flight and the urgent ones already queued.
  auto at = queue.begin();
  while (at != queue.end() && (at->sent || at->urgent)) ++at;
  queue.insert(at, std::move(pending));
  return id;
}

}  // namespace

RequestId MasterScheduler::SendCommand(std::uint8_t vehicle, const Command& command, bool urgent) {
  return Enqueue(*state_, vehicle, command, urgent);
}

RequestId MasterScheduler::SendMissionChunk(std::uint8_t vehicle, const MissionChunk& chunk) {
  if (chunk.waypoint_count > kMaxWaypointsPerChunk) {
    throw std::invalid_argument("MissionChunk.waypoint_count must be <= 20, got " +
                                std::to_string(chunk.waypoint_count));
  }
  return Enqueue(*state_, vehicle, chunk);
}

RequestId MasterScheduler::ReadParam(std::uint8_t vehicle, std::uint16_t param_id) {
  return Enqueue(*state_, vehicle, ParamRead{{}, param_id});
}

RequestId MasterScheduler::WriteParam(std::uint8_t vehicle, std::uint16_t param_id, float value) {
  return Enqueue(*state_, vehicle, ParamWrite{{}, param_id, value});
}

std::vector<Burst> MasterScheduler::Step(Nanos now, std::span<const std::uint8_t> received) {
  SchedulerState& state = *state_;
  internal::ReceiveReplies(state, now, received);
  if (state.exchange) {
    // The last expected reply ends the exchange early; otherwise the deadline does.
    if (!internal::AllRepliesIn(*state.exchange)) {
      if (now < state.exchange->timing.deadline) return {};
      internal::FlushReplies(state, now);
    }
    internal::CloseExchange(state, now);
  }
  if (now < state.ready_at) return {};
  if (!internal::HasUrgentWork(state) && internal::EarliestTelemetryDue(state) > now) return {};
  std::optional<Burst> burst = internal::PlanBurst(state, now);
  if (!burst) return {};
  ++state.stats.bursts;
  std::vector<Burst> out;
  out.push_back(std::move(*burst));
  return out;
}

Nanos MasterScheduler::NextWakeup() const {
  const SchedulerState& state = *state_;
  if (state.exchange) return state.exchange->timing.deadline;
  if (internal::HasUrgentWork(state)) return state.ready_at;
  const Nanos due = internal::EarliestTelemetryDue(state);
  return due == Nanos::max() ? due : std::max(due, state.ready_at);
}

std::vector<SchedulerEvent> MasterScheduler::TakeEvents() {
  return std::exchange(state_->events, {});
}

std::optional<ExchangeTiming> MasterScheduler::exchange() const {
  if (!state_->exchange) return std::nullopt;
  return state_->exchange->timing;
}

const SchedulerStats& MasterScheduler::stats() const {
  return state_->stats;
}
const ParserStats& MasterScheduler::parser_stats() const {
  return state_->parser.stats();
}
const SchedulerConfig& MasterScheduler::config() const {
  return state_->config;
}

std::uint16_t MasterScheduler::next_sequence() const {
  return state_->next_sequence;
}

}  // namespace fireswarm::radio
