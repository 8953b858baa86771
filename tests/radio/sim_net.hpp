// Test harness: the server and N vehicle endpoints on the real SharedChannel,
// stepped event by event by radio::ChannelLoop, with hooks for deterministic loss.
#pragma once

#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "fireswarm/radio/channel.hpp"
#include "fireswarm/radio/channel_loop.hpp"
#include "fireswarm/radio/master_scheduler.hpp"
#include "fireswarm/radio/vehicle_endpoint.hpp"
#include "radio/secure_link.hpp"

namespace fireswarm::radio::sim_test {

using std::chrono::milliseconds;
using std::chrono::seconds;

constexpr ChecksumMode kChecksum = ChecksumMode::kCrc16;
constexpr int kBaud = 57'600;
constexpr Nanos kTurnaround = milliseconds(5);

/// The channel every radio test shares: kBaud, kTurnaround and `loss`.
inline ChannelConfig TestChannelConfig(double loss = 0.0) {
  ChannelConfig config;
  config.baud = kBaud;
  config.turnaround = kTurnaround;
  config.loss = loss;
  return config;
}

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
  explicit SimVehicle(const VehicleEndpointConfig& config,
                      VehicleRequestHandler* external = nullptr)
      : endpoint(config, external != nullptr ? *external : handler) {}
  CountingHandler handler;
  VehicleEndpoint endpoint;
};

// The server and N vehicles on one ChannelLoop, stepped event by event.
// `drop_reply` and `drop_server_burst` see every burst and may keep it off the air:
// deterministic loss without mocks. Vehicle i (from 1) answers with handlers[i - 1]
// when given, else with its CountingHandler.
class SimNet {
 public:
  SimNet(const SchedulerConfig& config, int vehicles, double loss = 0.0,
         std::span<VehicleRequestHandler* const> handlers = {})
      : server_(config),
        loop_(TestChannelConfig(loss), /*seed=*/7,
              LoopMaster{[this] { return server_.NextWakeup(); },
                         [this](Nanos now, std::span<const std::uint8_t> received) {
                           return StepServer(now, received);
                         }}) {
    for (int i = 1; i <= vehicles; ++i) {
      VehicleEndpointConfig v;
      v.id = static_cast<std::uint8_t>(i);
      v.mode = config.mode;
      v.checksum = config.checksum;
      v.timing = config.timing;
      if (config.checksum == ChecksumMode::kSecure) {
        // Secure mode: vehicle i holds secure_test::TestKey(i) and the broadcast key.
        disks_.push_back(std::make_unique<secure_test::Disk>());
        v.security = secure_test::VehicleSecurity(v.id, *disks_.back());
      }
      const auto index = static_cast<std::size_t>(i - 1);
      vehicles_.push_back(
          std::make_unique<SimVehicle>(v, index < handlers.size() ? handlers[index] : nullptr));
      loop_.AddVehicle(
          [this, &vehicle = *vehicles_.back()](Nanos now, std::span<const std::uint8_t> received) {
            return StepVehicle(vehicle, now, received);
          });
    }
  }

  MasterScheduler& server() { return server_; }
  SimVehicle& vehicle(int id) { return *vehicles_.at(static_cast<std::size_t>(id - 1)); }
  const SharedChannel& channel() const { return loop_.channel(); }
  std::vector<SchedulerEvent>& events() { return events_; }

  std::function<bool(std::uint8_t vehicle, const Burst& burst)> drop_reply;
  std::function<bool(const Burst& burst)> drop_server_burst;

  void RunUntil(Nanos end) { loop_.RunUntil(end); }

  template <typename Event>
  std::vector<Event> EventsOf() const {
    std::vector<Event> out;
    for (const auto& e : events_) {
      if (const auto* typed = std::get_if<Event>(&e)) out.push_back(*typed);
    }
    return out;
  }

 private:
  // The hooks keep a dropped burst off the air; the events are collected after
  // every step so that their order is the scheduler's.
  std::vector<Burst> StepServer(Nanos now, std::span<const std::uint8_t> received) {
    std::vector<Burst> bursts = server_.Step(now, received);
    if (drop_server_burst) {
      std::erase_if(bursts, [this](const Burst& burst) { return drop_server_burst(burst); });
    }
    for (auto& e : server_.TakeEvents()) events_.push_back(std::move(e));
    return bursts;
  }

  std::vector<Burst> StepVehicle(SimVehicle& vehicle, Nanos now,
                                 std::span<const std::uint8_t> received) {
    std::vector<Burst> bursts = vehicle.endpoint.OnReceive(now, received);
    if (drop_reply) {
      std::erase_if(bursts, [&](const Burst& burst) {
        return drop_reply(vehicle.endpoint.config().id, burst);
      });
    }
    return bursts;
  }

  std::vector<std::unique_ptr<secure_test::Disk>> disks_;
  MasterScheduler server_;
  ChannelLoop loop_;  // after server_, which its master step uses
  std::vector<std::unique_ptr<SimVehicle>> vehicles_;
  std::vector<SchedulerEvent> events_;
};

}  // namespace fireswarm::radio::sim_test
