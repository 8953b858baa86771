// Test harness: the server and N vehicle endpoints on the real SharedChannel,
// stepped event by event as the radio bench does, with hooks for deterministic loss.
#pragma once

#include <algorithm>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "fireswarm/radio/channel.hpp"
#include "fireswarm/radio/link.hpp"
#include "fireswarm/radio/master_scheduler.hpp"
#include "fireswarm/radio/vehicle_endpoint.hpp"

namespace fireswarm::radio::sim_test {

using std::chrono::milliseconds;
using std::chrono::seconds;

constexpr ChecksumMode kChecksum = ChecksumMode::kCrc16;
constexpr int kBaud = 57'600;
constexpr Nanos kTurnaround = milliseconds(5);

class CountingHandler final : public VehicleRequestHandler {
 public:
  CommandResult OnCommand(const Command& /*command*/) override {
    ++executed;
    return CommandResult::kAccepted;
  }
  MissionAckStatus OnMissionChunk(const MissionChunk& /*chunk*/) override {
    ++executed;
    return MissionAckStatus::kAccepted;
  }
  ParamValue OnParamRead(const ParamRead& /*read*/) override { return {}; }
  ParamValue OnParamWrite(const ParamWrite& write) override {
    return ParamValue{{}, 0, write.value, ParamStatus::kOk};
  }
  int executed = 0;
};

inline SchedulerConfig ServerConfig(LinkMode mode) {
  SchedulerConfig config;
  config.mode = mode;
  config.checksum = kChecksum;
  config.timing = LinkTiming{kBaud, kBitsPerByte8N1, kTurnaround};
  return config;
}

// Answers with `handler` when given (it must outlive the vehicle), else with its own
// CountingHandler.
struct SimVehicle {
  SimVehicle(SharedChannel& channel, const VehicleEndpointConfig& config,
             VehicleRequestHandler* external = nullptr)
      : link(channel, channel.AddRadio()),
        endpoint(config, external != nullptr ? *external : handler) {}
  CountingHandler handler;
  SimLink link;
  VehicleEndpoint endpoint;
};

// The server and N vehicles on the real SharedChannel, stepped event by event.
// `drop_reply` and `drop_server_burst` see every burst and may keep it off the air:
// deterministic loss without mocks. Vehicle i (from 1) answers with handlers[i - 1]
// when given, else with its CountingHandler.
class SimNet {
 public:
  SimNet(const SchedulerConfig& config, int vehicles, double loss = 0.0,
         std::span<VehicleRequestHandler* const> handlers = {})
      : channel_(ChannelFor(loss), /*seed=*/7),
        server_link_(channel_, channel_.AddRadio()),
        server_(config) {
    for (int i = 1; i <= vehicles; ++i) {
      VehicleEndpointConfig v;
      v.id = static_cast<std::uint8_t>(i);
      v.mode = config.mode;
      v.checksum = config.checksum;
      v.timing = config.timing;
      const auto index = static_cast<std::size_t>(i - 1);
      vehicles_.push_back(std::make_unique<SimVehicle>(
          channel_, v, index < handlers.size() ? handlers[index] : nullptr));
    }
  }

  MasterScheduler& server() { return server_; }
  SimVehicle& vehicle(int id) { return *vehicles_.at(static_cast<std::size_t>(id - 1)); }
  const SharedChannel& channel() const { return channel_; }
  std::vector<SchedulerEvent>& events() { return events_; }

  std::function<bool(std::uint8_t vehicle, const Burst& burst)> drop_reply;
  std::function<bool(const Burst& burst)> drop_server_burst;

  void RunUntil(Nanos end) {
    while (true) {
      const Nanos t =
          std::min(server_.NextWakeup(), channel_.NextEventTime().value_or(Nanos::max()));
      if (t > end) break;
      channel_.AdvanceTo(t);
      StepServer(t);
      StepVehicles(t);
    }
    channel_.AdvanceTo(end);
  }

  template <typename Event>
  std::vector<Event> EventsOf() const {
    std::vector<Event> out;
    for (const auto& e : events_) {
      if (const auto* typed = std::get_if<Event>(&e)) out.push_back(*typed);
    }
    return out;
  }

 private:
  static ChannelConfig ChannelFor(double loss) {
    ChannelConfig c;
    c.baud = kBaud;
    c.turnaround = kTurnaround;
    c.loss = loss;
    return c;
  }

  void StepServer(Nanos t) {
    std::vector<std::uint8_t> bytes;
    server_link_.Receive(t, bytes);
    if (bytes.empty() && t < server_.NextWakeup()) return;
    for (const Burst& burst : server_.Step(t, bytes)) {
      if (drop_server_burst && drop_server_burst(burst)) continue;
      server_link_.Transmit(t, burst.start, burst.bytes);
    }
    for (auto& e : server_.TakeEvents()) events_.push_back(std::move(e));
  }

  void StepVehicles(Nanos t) {
    for (auto& v : vehicles_) {
      std::vector<std::uint8_t> bytes;
      v->link.Receive(t, bytes);
      if (bytes.empty()) continue;
      for (const Burst& burst : v->endpoint.OnReceive(t, bytes)) {
        if (drop_reply && drop_reply(v->endpoint.config().id, burst)) continue;
        v->link.Transmit(t, burst.start, burst.bytes);
      }
    }
  }

  SharedChannel channel_;
  SimLink server_link_;
  MasterScheduler server_;
  std::vector<std::unique_ptr<SimVehicle>> vehicles_;
  std::vector<SchedulerEvent> events_;
};

}  // namespace fireswarm::radio::sim_test
