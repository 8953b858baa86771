// Radio-level vehicles for the server's tests: each is a VehicleEndpoint (the
// vehicle's real radio side) with a small handler that stores missions as the
// APOne mission store does, logs the commands it gets and can be given telemetry
// and fire reports, all on one simulated shared channel. No agents/: the server
// knows vehicles only through frames.
#pragma once

#include <memory>
#include <set>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "fireswarm/common/time.hpp"
#include "fireswarm/radio/channel.hpp"
#include "fireswarm/radio/channel_loop.hpp"
#include "fireswarm/radio/master_scheduler.hpp"
#include "fireswarm/radio/vehicle_endpoint.hpp"

namespace fireswarm::server::testing {

using common::Nanos;

// The radio side of a vehicle: stores chunks as the APOne mission store does
// (complete when every chunk is in) and refuses the start `refusals` times, as a
// vehicle without a GPS fix does.
class FakeVehicle final : public radio::VehicleRequestHandler {
 public:
  FakeVehicle(std::uint8_t id, radio::LinkMode mode, int refusals)
      : id_(id), endpoint_(Config(id, mode), *this), refusals_left_(refusals) {}
  std::uint8_t id() const { return id_; }

  radio::CommandResult OnCommand(const radio::Command& command) override {
    commands_.push_back(command);
    if (refused.contains(command.type)) return radio::CommandResult::kRejected;
    if (command.type != radio::CommandType::kStartMission) return radio::CommandResult::kAccepted;
    if (!complete_ || command.mission_id != mission_id_) return radio::CommandResult::kRejected;
    if (refusals_left_ > 0) {
      --refusals_left_;
      return radio::CommandResult::kRejected;
    }
    ++starts_accepted_;
    return radio::CommandResult::kAccepted;
  }
  radio::MissionAckStatus OnMissionChunk(const radio::MissionChunk& chunk) override {
    if (chunk.chunk_index >= chunk.chunk_count) return radio::MissionAckStatus::kRejected;
    mission_id_ = chunk.mission_id;
    waypoints_.resize(chunk.total_waypoints);
    for (std::size_t i = 0; i < chunk.waypoint_count; ++i) {
      waypoints_.at(chunk.first_waypoint + i) = chunk.waypoints[i];
    }
    chunks_.insert(chunk.chunk_index);
    complete_ = chunks_.size() == chunk.chunk_count;
    return complete_ ? radio::MissionAckStatus::kComplete : radio::MissionAckStatus::kAccepted;
  }
  radio::ParamValue OnParamRead(const radio::ParamRead&) override { return {}; }
  radio::ParamValue OnParamWrite(const radio::ParamWrite&) override { return {}; }

  radio::VehicleEndpoint& endpoint() { return endpoint_; }
  const std::vector<radio::Waypoint>& waypoints() const { return waypoints_; }
  bool complete() const { return complete_; }
  int starts_accepted() const { return starts_accepted_; }
  const std::vector<radio::Command>& commands() const { return commands_; }

  /// Commands of these types are refused (as a drone on the ground refuses a hold).
  std::set<radio::CommandType> refused;

 private:
  static radio::VehicleEndpointConfig Config(std::uint8_t id, radio::LinkMode mode) {
    radio::VehicleEndpointConfig config;
    config.id = id;
    config.mode = mode;
    return config;
  }
  std::uint8_t id_;
  radio::VehicleEndpoint endpoint_;
  int refusals_left_;
  std::uint16_t mission_id_ = 0;
  std::set<std::uint8_t> chunks_;
  std::vector<radio::Waypoint> waypoints_;
  bool complete_ = false;
  int starts_accepted_ = 0;
  std::vector<radio::Command> commands_;
};

// Fake vehicles on one radio::ChannelLoop with a server end, run event by event
// (no wall clock). The server end is anything with Step(now, bytes) -> bursts and
// NextWakeup(), given to each Run(); the loop's own check fails a server end that
// asks to be woken at the same instant again and again.
class Air {
 public:
  explicit Air(double loss, radio::LinkMode link_mode = radio::LinkMode::kSlots)
      : mode(link_mode),
        loop_(Channel(loss), /*seed=*/7,
              radio::LoopMaster{[this] { return server_.next_wakeup(); },
                                [this](Nanos now, std::span<const std::uint8_t> received) {
                                  return server_.step(now, received);
                                }}) {}
  FakeVehicle& Add(std::uint8_t id, int refusals = 0) {
    vehicles_.push_back(std::make_unique<FakeVehicle>(id, mode, refusals));
    loop_.AddVehicle(
        [this, &v = *vehicles_.back()](Nanos now, std::span<const std::uint8_t> received) {
          if (silent.contains(v.id())) return std::vector<radio::Burst>{};
          return v.endpoint().OnReceive(now, received);
        });
    return *vehicles_.back();
  }
  FakeVehicle& vehicle(std::uint8_t id) {
    for (auto& v : vehicles_) {
      if (v->id() == id) return *v;
    }
    throw std::out_of_range("no fake vehicle " + std::to_string(id));
  }
  const radio::SharedChannel& channel() const { return loop_.channel(); }

  // Runs until `done()` holds or the next event would pass `limit`.
  template <typename ServerEnd, typename Done>
  Nanos Run(ServerEnd& server, Nanos limit, Done&& done) {
    server_ = radio::MasterOf(server);
    while (!done()) {
      const Nanos t = loop_.NextEventTime();
      if (t > limit) break;
      loop_.StepAt(t);
    }
    return loop_.channel().now();
  }
  template <typename ServerEnd>
  void RunUntil(ServerEnd& server, Nanos end) {
    server_ = radio::MasterOf(server);
    loop_.RunUntil(end);
  }

  radio::LinkMode mode;
  std::set<std::uint8_t> silent;  ///< vehicles that neither hear nor answer (gone)

 private:
  static radio::ChannelConfig Channel(double loss) {
    radio::ChannelConfig channel_config;
    channel_config.loss = loss;
    return channel_config;
  }

  radio::LoopMaster server_;  // the server end of the current Run()
  radio::ChannelLoop loop_;   // after server_, which its master steps through
  std::vector<std::unique_ptr<FakeVehicle>> vehicles_;
};

}  // namespace fireswarm::server::testing
