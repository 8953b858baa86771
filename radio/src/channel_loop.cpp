#include "fireswarm/radio/channel_loop.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

namespace fireswarm::radio {

ChannelLoop::ChannelLoop(const ChannelConfig& config, std::uint64_t seed, LoopMaster master)
    : channel_(config, seed), master_radio_(channel_.AddRadio()), master_(std::move(master)) {}

RadioId ChannelLoop::AddVehicle(RadioStep step) {
  const RadioId radio = channel_.AddRadio();
  vehicles_.push_back(Vehicle{radio, std::move(step)});
  return radio;
}

Nanos ChannelLoop::NextEventTime() const {
  return std::max(channel_.now(),
                  std::min(master_.next_wakeup(), channel_.NextEventTime().value_or(Nanos::max())));
}

void ChannelLoop::StepAt(Nanos t) {
  steps_at_last_instant_ = t == last_step_ ? steps_at_last_instant_ + 1 : 0;
  last_step_ = t;
  if (steps_at_last_instant_ > kMaxStepsAtOneInstant) {
    throw std::logic_error("ChannelLoop: the master asks to be woken at " +
                           std::to_string(ToSeconds(t)) + " s again and again without progress");
  }
  channel_.AdvanceTo(t);
  received_.clear();
  channel_.Drain(master_radio_, received_);
  Transmit(master_radio_, t, master_.step(t, received_));
  for (const Vehicle& vehicle : vehicles_) {
    received_.clear();
    channel_.Drain(vehicle.radio, received_);
    // A vehicle that heard nothing has no turn: only the master speaks unasked.
    if (received_.empty()) continue;
    Transmit(vehicle.radio, t, vehicle.step(t, received_));
  }
}

void ChannelLoop::RunUntil(Nanos end) {
  while (true) {
    const Nanos t = NextEventTime();
    if (t > end) break;
    StepAt(t);
  }
  channel_.AdvanceTo(std::max(end, channel_.now()));
}

void ChannelLoop::Transmit(RadioId radio, Nanos now, const std::vector<Burst>& bursts) {
  for (const Burst& burst : bursts) channel_.Transmit(radio, now, burst.start, burst.bytes);
}

void RunLoopsUntil(std::span<ChannelLoop* const> loops, Nanos end) {
  while (true) {
    ChannelLoop* next = nullptr;
    Nanos t = Nanos::max();
    for (ChannelLoop* loop : loops) {
      const Nanos at = loop->NextEventTime();
      if (at < t) {
        t = at;
        next = loop;
      }
    }
    if (next == nullptr || t > end) break;
    next->StepAt(t);
  }
  for (ChannelLoop* loop : loops) loop->RunUntil(end);
}

}  // namespace fireswarm::radio
