// The APOne vehicle's cost: one control step, one detector frame, and whole
// fleets of vehicles flying lawnmower missions in sim2d through the HIL bridge
// (the real-time factor of closed-loop swarm simulation, without the radio).
#include <benchmark/benchmark.h>

#include <memory>
#include <vector>

#include "fireswarm/agents/fire_detector.hpp"
#include "fireswarm/agents/vehicle.hpp"
#include "fireswarm/bench/bench_scenario.hpp"
#include "fireswarm/hil/sim_bridge.hpp"
#include "fireswarm/radio/mission_chunks.hpp"
#include "fireswarm/sim2d/lane_pilot.hpp"

namespace fireswarm {
namespace {

using sim2d::Vec2;

constexpr double kAreaKm2 = 4.0;
constexpr double kAltitudeM = 60.0;
constexpr double kLaneSpacingM = 80.0;  // about the seed camera's footprint at 60 m

// N vehicles on sim-bench's scenario (a square with fires and hot rocks), each
// given a lawnmower mission over its own strip, flying.
struct Fleet {
  explicit Fleet(int drones)
      : scenario(MakeScenario(drones)), simulation(scenario.config), lockstep(simulation) {
    const double side_m = std::sqrt(kAreaKm2) * 1000.0;
    const double strip_m = side_m / drones;
    for (const sim2d::VehicleConfig& config : scenario.config.world.vehicles) {
      agents::VehicleConfig vehicle;
      vehicle.id = static_cast<std::uint8_t>(config.id);
      vehicles.push_back(std::make_unique<agents::Vehicle>(vehicle));
      lockstep.Add(*vehicles.back());
    }
    lockstep.RunUntil(1.0);  // a GPS fix
    for (std::size_t i = 0; i < vehicles.size(); ++i) {
      agents::Vehicle& vehicle = *vehicles[i];
      // No server here: keep the vehicles from returning for want of one.
      radio::ParamWrite patience;
      patience.param_id = static_cast<std::uint16_t>(agents::ParamId::kLinkLostTimeoutS);
      patience.value = 600.0F;
      vehicle.OnParamWrite(patience);
      const Vec2 launch = scenario.config.world.vehicles[i].launch_position_m;
      std::vector<radio::Waypoint> mission;
      for (const Vec2& point : sim2d::LawnmowerLanes(
               Vec2(launch.x() - strip_m / 2, launch.y()),
               Vec2(launch.x() + strip_m / 2, launch.y() + side_m), kLaneSpacingM)) {
        const common::LatLon position =
            simulation.world().frame().ToGeodetic({point.x(), point.y()});
        radio::Waypoint waypoint;
        waypoint.lat_deg = position.lat_deg;
        waypoint.lon_deg = position.lon_deg;
        waypoint.altitude_m = kAltitudeM + 5.0 * static_cast<double>(i % 4);
        waypoint.flags = 1;
        mission.push_back(waypoint);
      }
      for (const radio::MissionChunk& chunk : radio::SplitMission(1, mission)) {
        vehicle.OnMissionChunk(chunk);
      }
      radio::Command start;
      start.type = radio::CommandType::kStartMission;
      start.mission_id = 1;
      vehicle.OnCommand(start);
    }
    lockstep.RunUntil(40.0);  // take-off done, searching
  }

  static bench::BenchScenario MakeScenario(int drones) {
    bench::BenchScenarioSpec spec;
    spec.drones = drones;
    spec.area_km2 = kAreaKm2;
    return bench::MakeBenchScenario(spec);
  }

  bench::BenchScenario scenario;
  sim2d::Simulation simulation;
  hil::LockstepFleet lockstep;
  std::vector<std::unique_ptr<agents::Vehicle>> vehicles;
};

// One simulated second per iteration: the rate counter is the real-time factor.
void BM_FleetClosedLoop(benchmark::State& state) {
  Fleet fleet(static_cast<int>(state.range(0)));
  const auto steps = static_cast<int>(1.0 / fleet.simulation.world().step_s());
  for (auto _ : state) {
    for (int i = 0; i < steps; ++i) fleet.lockstep.Step();
  }
  state.counters["real_time_factor"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
  std::size_t searching = 0;
  for (const auto& vehicle : fleet.vehicles) {
    if (vehicle->mode() == radio::FlightMode::kSearch) ++searching;
  }
  state.counters["searching"] = static_cast<double>(searching);
}
BENCHMARK(BM_FleetClosedLoop)->Arg(10)->Arg(100)->Unit(benchmark::kMillisecond);

// The same fleets flown by sim2d's truth-flying LanePilot: the simulator alone.
void BM_FleetLanePilots(benchmark::State& state) {
  bench::BenchScenario scenario = Fleet::MakeScenario(static_cast<int>(state.range(0)));
  sim2d::Simulation simulation(scenario.config);
  const auto steps = static_cast<int>(1.0 / simulation.world().step_s());
  const auto fly = [&] {
    for (std::size_t v = 0; v < scenario.pilots.size(); ++v) {
      simulation.world().SetCommandAt(v,
                                      scenario.pilots[v].Command(simulation.world().Truths()[v]));
    }
    simulation.Step();
  };
  for (int i = 0; i < 40 * steps; ++i) fly();
  for (auto _ : state) {
    for (int i = 0; i < steps; ++i) fly();
  }
  state.counters["real_time_factor"] =
      benchmark::Counter(static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_FleetLanePilots)->Arg(10)->Arg(100)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace fireswarm

BENCHMARK_MAIN();
