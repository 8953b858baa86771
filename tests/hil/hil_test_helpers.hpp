// Closed-loop test harness: agents::Vehicles flying in a sim2d Simulation through
// the HIL bridge, talking to a MasterScheduler (the server's radio core) over the
// simulated shared channel. Every step: physics, fire and cameras; the vehicles;
// then the radio runs event by event up to the step's end.
#pragma once

#include <algorithm>
#include <cmath>
#include <memory>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "fireswarm/agents/vehicle.hpp"
#include "fireswarm/common/time.hpp"
#include "fireswarm/hil/sim_bridge.hpp"
#include "fireswarm/radio/channel.hpp"
#include "fireswarm/radio/channel_loop.hpp"
#include "fireswarm/radio/master_scheduler.hpp"
#include "fireswarm/radio/mission_chunks.hpp"
#include "fireswarm/sim2d/simulation.hpp"

namespace fireswarm::hil::testing {

/// The search altitude the closed-loop tests fly at, metres above ground.
inline constexpr double kAltitudeM = 60.0;

using common::Nanos;

inline sim2d::VehicleConfig SimVehicleAt(int id, sim2d::Vec2 launch_m) {
  sim2d::VehicleConfig vehicle;
  vehicle.id = id;
  vehicle.launch_position_m = launch_m;
  return vehicle;
}

/// A 2 km square forest around the origin with one vehicle at `launch_m` carrying
/// the seed camera pointing straight down.
inline sim2d::SimulationConfig OneVehicleWorld(sim2d::Vec2 launch_m = sim2d::Vec2::Zero(),
                                               std::uint64_t seed = 11) {
  sim2d::SimulationConfig config;
  config.world.seed = seed;
  config.fire.origin_m = sim2d::Vec2(-1000.0, -1000.0);
  config.fire.width_m = 2000.0;
  config.fire.height_m = 2000.0;
  config.world.vehicles.push_back(SimVehicleAt(1, launch_m));
  sim2d::VehicleCamera camera;
  camera.vehicle_id = 1;
  camera.model = "seed";
  config.cameras.push_back(camera);
  return config;
}

/// The server end of the radio and the vehicles' radios on one SharedChannel.
class GroundLink {
 public:
  explicit GroundLink(const radio::ChannelConfig& channel = {},
                      const radio::SchedulerConfig& server = {})
      : server_(server), loop_(channel, /*seed=*/3, MasterStep()) {}

  /// Registers `vehicle` with telemetry at `telemetry_hz`.
  void Add(agents::Vehicle& vehicle, double telemetry_hz = 2.0) {
    loop_.AddVehicle([&vehicle](Nanos now, std::span<const std::uint8_t> received) {
      return vehicle.OnRadio(now, received);
    });
    server_.AddVehicle(vehicle.id(), telemetry_hz);
  }

  radio::MasterScheduler& server() { return server_; }
  const radio::SharedChannel& channel() const { return loop_.channel(); }

  /// Uploads `waypoints` as mission `mission_id` and queues its start (which the
  /// vehicle refuses until it has a GPS fix).
  void UploadAndStart(std::uint8_t vehicle, std::uint16_t mission_id,
                      const std::vector<radio::Waypoint>& waypoints) {
    for (const radio::MissionChunk& chunk : radio::SplitMission(mission_id, waypoints)) {
      server_.SendMissionChunk(vehicle, chunk);
    }
    radio::Command start;
    start.type = radio::CommandType::kStartMission;
    start.mission_id = mission_id;
    server_.SendCommand(vehicle, start);
  }

  /// Runs the channel, the server and the vehicles' radio sides up to `end`.
  void RunUntil(Nanos end) { loop_.RunUntil(end); }

  template <typename Event>
  std::vector<Event> EventsOf() const {
    std::vector<Event> out;
    for (const auto& event : events_) {
      if (const auto* typed = std::get_if<Event>(&event)) out.push_back(*typed);
    }
    return out;
  }

 private:
  // The server steps as the loop's master; its events are kept for EventsOf().
  radio::LoopMaster MasterStep() {
    return radio::LoopMaster{[this] { return server_.NextWakeup(); },
                             [this](Nanos now, std::span<const std::uint8_t> received) {
                               std::vector<radio::Burst> bursts = server_.Step(now, received);
                               for (auto& event : server_.TakeEvents()) {
                                 events_.push_back(std::move(event));
                               }
                               return bursts;
                             }};
  }

  radio::MasterScheduler server_;
  std::vector<radio::SchedulerEvent> events_;
  radio::ChannelLoop loop_;  // after server_ and events_, which its master step uses
};

/// A simulation, its vehicles and the ground link, stepped together.
struct Mission {
  explicit Mission(const sim2d::SimulationConfig& config, const radio::ChannelConfig& channel = {},
                   const radio::SchedulerConfig& server = {})
      : simulation(config), fleet(simulation), link(channel, server) {}

  agents::Vehicle& AddVehicle(agents::VehicleConfig config) {
    vehicles.push_back(std::make_unique<agents::Vehicle>(config));
    fleet.Add(*vehicles.back());
    link.Add(*vehicles.back());
    return *vehicles.back();
  }

  /// Steps until `time_s`, calling `each_step` after every step. With `radio_on`
  /// false the ground link is silent: nothing is sent or heard.
  template <typename F>
  void RunUntil(double time_s, F&& each_step) {
    while (simulation.time_s() < time_s - 1e-9) {
      fleet.Step();
      if (radio_on) link.RunUntil(fleet.now());
      each_step();
    }
  }
  void RunUntil(double time_s) {
    RunUntil(time_s, [] {});
  }

  const sim2d::VehicleTruth& Truth(int id) const { return simulation.world().Truth(id); }
  common::LatLon ToLatLon(sim2d::Vec2 point_m) const {
    return simulation.world().frame().ToGeodetic({point_m.x(), point_m.y()});
  }

  sim2d::Simulation simulation;
  LockstepFleet fleet;
  GroundLink link;
  std::vector<std::unique_ptr<agents::Vehicle>> vehicles;
  bool radio_on = true;
};

/// Steps `mission` until `done()` holds or `limit_s` of simulated time has passed.
template <typename Done>
void RunUntilOr(Mission& mission, double limit_s, Done&& done) {
  while (!done() && mission.simulation.time_s() < limit_s) {
    mission.RunUntil(mission.simulation.time_s() + 0.1);
  }
}

/// A waypoint at local point `point_m` of `mission`'s world.
inline radio::Waypoint WaypointAt(const Mission& mission, sim2d::Vec2 point_m, double altitude_m,
                                  bool lane_start = false) {
  const common::LatLon position = mission.ToLatLon(point_m);
  radio::Waypoint waypoint;
  waypoint.lat_deg = position.lat_deg;
  waypoint.lon_deg = position.lon_deg;
  waypoint.altitude_m = altitude_m;
  waypoint.flags = lane_start ? 1 : 0;
  return waypoint;
}

}  // namespace fireswarm::hil::testing
