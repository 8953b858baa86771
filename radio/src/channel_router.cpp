// One MasterScheduler per channel, requests routed by vehicle (issue 21).
#include "fireswarm/radio/channel_router.hpp"

#include <algorithm>
#include <cassert>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>

namespace fireswarm::radio {

namespace {

// Global request IDs interleave the channels' own: with one channel they are the
// scheduler's IDs unchanged.
RequestId GlobalId(RequestId local, std::size_t channel, std::size_t channels) {
  return static_cast<RequestId>((local - 1) * channels + channel + 1);
}

std::optional<std::uint8_t> HeardFrom(const SchedulerEvent& event) {
  if (const auto* telemetry = std::get_if<TelemetryReceived>(&event)) return telemetry->vehicle;
  if (const auto* report = std::get_if<FireReportReceived>(&event)) return report->vehicle;
  if (const auto* finished = std::get_if<RequestFinished>(&event)) {
    if (finished->status == RequestStatus::kCompleted) return finished->vehicle;
  }
  return std::nullopt;
}

Nanos TimeOf(const SchedulerEvent& event) {
  return std::visit(
      [](const auto& e) -> Nanos {
        using T = std::decay_t<decltype(e)>;
        if constexpr (std::is_same_v<T, TelemetryReceived> ||
                      std::is_same_v<T, FireReportReceived>) {
          return e.received;
        } else if constexpr (std::is_same_v<T, RequestSent>) {
          return e.sent;
        } else if constexpr (std::is_same_v<T, RequestFinished>) {
          return e.finished;
        } else {
          return e.last_heard;
        }
      },
      event);
}

}  // namespace

ChannelRouter::ChannelRouter(const std::vector<SchedulerConfig>& configs) {
  if (configs.empty() || configs.size() > kMaxChannels) {
    throw std::invalid_argument("radio channels: " + std::to_string(configs.size()) +
                                ", must be 1.." + std::to_string(kMaxChannels));
  }
  for (std::size_t k = 0; k < configs.size(); ++k) {
    try {
      channels_.push_back(std::make_unique<MasterScheduler>(configs[k]));
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("radio channel " + std::to_string(k) + ": " + e.what());
    }
  }
  health_.resize(configs.size());
  bytes_.resize(configs.size());
}

ChannelRouter::~ChannelRouter() = default;

std::size_t ChannelRouter::AddVehicle(std::uint8_t vehicle, double telemetry_hz, Nanos first_due,
                                      std::optional<std::size_t> channel) {
  if (channel_of_.contains(vehicle)) {
    throw std::invalid_argument("vehicle " + std::to_string(vehicle) + " is already registered");
  }
  if (channel && *channel >= channels_.size()) {
    throw std::invalid_argument("vehicle " + std::to_string(vehicle) + ": channel " +
                                std::to_string(*channel) + " out of range (" +
                                std::to_string(channels_.size()) + " channels)");
  }
  std::size_t chosen = channel.value_or(0);
  if (!channel) {
    std::vector<std::size_t> counts(channels_.size(), 0);
    for (const auto& [id, k] : channel_of_) ++counts[k];
    chosen = static_cast<std::size_t>(std::ranges::min_element(counts) - counts.begin());
  }
  channels_[chosen]->AddVehicle(vehicle, telemetry_hz, first_due);
  channel_of_[vehicle] = chosen;
  silent_[vehicle] = false;
  return chosen;
}

std::size_t ChannelRouter::ChannelOf(std::uint8_t vehicle) const {
  const auto found = channel_of_.find(vehicle);
  if (found == channel_of_.end()) {
    throw std::invalid_argument("unknown vehicle " + std::to_string(vehicle));
  }
  return found->second;
}

void ChannelRouter::SetTelemetryRate(std::uint8_t vehicle, double telemetry_hz) {
  channels_[ChannelOf(vehicle)]->SetTelemetryRate(vehicle, telemetry_hz);
}

double ChannelRouter::TelemetryRateHz(std::uint8_t vehicle) const {
  return channels_[ChannelOf(vehicle)]->TelemetryRateHz(vehicle);
}

RequestId ChannelRouter::SendCommand(std::uint8_t vehicle, const Command& command, bool urgent) {
  const std::size_t k = ChannelOf(vehicle);
  return GlobalId(channels_[k]->SendCommand(vehicle, command, urgent), k, channels_.size());
}

RequestId ChannelRouter::SendMissionChunk(std::uint8_t vehicle, const MissionChunk& chunk) {
  const std::size_t k = ChannelOf(vehicle);
  return GlobalId(channels_[k]->SendMissionChunk(vehicle, chunk), k, channels_.size());
}

RequestId ChannelRouter::ReadParam(std::uint8_t vehicle, std::uint16_t param_id) {
  const std::size_t k = ChannelOf(vehicle);
  return GlobalId(channels_[k]->ReadParam(vehicle, param_id), k, channels_.size());
}

RequestId ChannelRouter::WriteParam(std::uint8_t vehicle, std::uint16_t param_id, float value) {
  const std::size_t k = ChannelOf(vehicle);
  return GlobalId(channels_[k]->WriteParam(vehicle, param_id, value), k, channels_.size());
}

std::vector<Burst> ChannelRouter::Step(Nanos now, std::size_t channel,
                                       std::span<const std::uint8_t> received) {
  assert(channel < channels_.size());
  std::vector<Burst> bursts = channels_[channel]->Step(now, received);
  bytes_[channel].received += received.size();
  for (const Burst& burst : bursts) bytes_[channel].sent += burst.bytes.size();
  for (SchedulerEvent& event : channels_[channel]->TakeEvents()) {
    if (auto* sent = std::get_if<RequestSent>(&event)) {
      sent->id = GlobalId(sent->id, channel, channels_.size());
    } else if (auto* finished = std::get_if<RequestFinished>(&event)) {
      finished->id = GlobalId(finished->id, channel, channels_.size());
    }
    Track(channel, event);
    events_.push_back(std::move(event));
  }
  return bursts;
}

void ChannelRouter::Track(std::size_t channel, const SchedulerEvent& event) {
  if (const std::optional<std::uint8_t> heard = HeardFrom(event)) {
    silent_[*heard] = false;
    if (health_[channel].silent) health_[channel] = ChannelHealth{false, TimeOf(event)};
    return;
  }
  const auto* silent = std::get_if<VehicleSilent>(&event);
  if (silent == nullptr) return;
  silent_[silent->vehicle] = true;
  if (health_[channel].silent) return;
  const std::vector<std::uint8_t> on = VehiclesOn(channel);
  if (std::ranges::all_of(on, [&](std::uint8_t id) { return silent_.at(id); })) {
    health_[channel] = ChannelHealth{true, channels_[channel]->exchange()
                                               ? channels_[channel]->exchange()->burst_start
                                               : TimeOf(event)};
  }
}

Nanos ChannelRouter::NextWakeup() const {
  Nanos next = Nanos::max();
  for (const auto& channel : channels_) next = std::min(next, channel->NextWakeup());
  return next;
}

Nanos ChannelRouter::NextWakeup(std::size_t channel) const {
  return this->channel(channel).NextWakeup();
}

std::vector<SchedulerEvent> ChannelRouter::TakeEvents() {
  return std::exchange(events_, {});
}

const MasterScheduler& ChannelRouter::channel(std::size_t channel) const {
  assert(channel < channels_.size());
  return *channels_[channel];
}

std::vector<std::uint8_t> ChannelRouter::VehiclesOn(std::size_t channel) const {
  std::vector<std::uint8_t> out;
  for (const auto& [id, k] : channel_of_) {
    if (k == channel) out.push_back(id);
  }
  return out;
}

const ChannelHealth& ChannelRouter::health(std::size_t channel) const {
  assert(channel < health_.size());
  return health_[channel];
}

const ChannelBytes& ChannelRouter::bytes(std::size_t channel) const {
  assert(channel < bytes_.size());
  return bytes_[channel];
}

SchedulerStats ChannelRouter::stats() const {
  SchedulerStats sum;
  for (const auto& channel : channels_) {
    const SchedulerStats& s = channel->stats();
    sum.bursts += s.bursts;
    sum.polls += s.polls;
    sum.schedules += s.schedules;
    sum.slots_granted += s.slots_granted;
    sum.requests_sent += s.requests_sent;
    sum.retries += s.retries;
    sum.requests_completed += s.requests_completed;
    sum.requests_failed += s.requests_failed;
    sum.replies += s.replies;
    sum.missed_replies += s.missed_replies;
    sum.telemetry += s.telemetry;
    sum.fire_reports += s.fire_reports;
    sum.duplicate_reports += s.duplicate_reports;
    sum.report_acks_sent += s.report_acks_sent;
    sum.payload_bytes += s.payload_bytes;
    sum.decode_errors += s.decode_errors;
    sum.unknown_senders += s.unknown_senders;
    sum.out_of_turn += s.out_of_turn;
    sum.refused_frames += s.refused_frames;
    sum.seal_failures += s.seal_failures;
  }
  return sum;
}

ParserStats ChannelRouter::parser_stats() const {
  ParserStats sum;
  for (const auto& channel : channels_) {
    const ParserStats& s = channel->parser_stats();
    sum.frames += s.frames;
    sum.bytes += s.bytes;
    sum.skipped_bytes += s.skipped_bytes;
    sum.checksum_errors += s.checksum_errors;
    sum.truncated_frames += s.truncated_frames;
  }
  return sum;
}

}  // namespace fireswarm::radio
