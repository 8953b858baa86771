// World::Step cost for a fleet in flight: N multirotors on a 10 m grid at 20 m,
// all circling the same way (pitched forward, yawing), with the default sensors
// (GPS 10 Hz, baro 25 Hz, attitude 100 Hz, battery 5 Hz) and near-miss tracking.
// The real-time factor is step_s / time per step.
//   build/bin/world_bench [--benchmark_filter=...]
#include <benchmark/benchmark.h>

#include <cmath>

#include "fireswarm/sim2d/world.hpp"

namespace {

using fireswarm::sim2d::ActuatorCommand;
using fireswarm::sim2d::Vec2;
using fireswarm::sim2d::World;
using fireswarm::sim2d::WorldConfig;

constexpr double kGridSpacingM = 10.0;
constexpr double kClimbTimeS = 15.0;

World FleetInFlight(int count) {
  World world(WorldConfig{});
  const int side = static_cast<int>(std::ceil(std::sqrt(count)));
  for (int i = 0; i < count; ++i) {
    world.AddVehicle(i + 1, Vec2(kGridSpacingM * (i % side), kGridSpacingM * (i / side)));
  }
  ActuatorCommand climb;
  climb.armed = true;
  climb.climb_rate_mps = 2.0;
  for (int i = 0; i < count; ++i) world.SetCommand(i + 1, climb);
  world.RunFor(10.0);
  ActuatorCommand circle;
  circle.armed = true;
  circle.pitch_rad = -0.15;
  circle.yaw_rate_radps = 0.3;
  for (int i = 0; i < count; ++i) world.SetCommand(i + 1, circle);
  world.RunFor(kClimbTimeS - 10.0);
  return world;
}

void BM_WorldStep(benchmark::State& state) {
  const int count = static_cast<int>(state.range(0));
  World world = FleetInFlight(count);
  for (auto _ : state) {
    world.Step();
    benchmark::DoNotOptimize(world.Truths().data());
  }
  state.SetItemsProcessed(state.iterations() * count);
  state.counters["real_time_factor"] = benchmark::Counter(
      world.step_s() * static_cast<double>(state.iterations()), benchmark::Counter::kIsRate);
}
BENCHMARK(BM_WorldStep)->Arg(100)->Arg(1000)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
