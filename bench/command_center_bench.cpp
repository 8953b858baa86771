// The command center's model at fleet scale: 250 drones whose vehicle_state_t all
// arrive at the web rate (5 Hz, the worst case: the LCM feed is 2 Hz), each tick
// followed by the delta the WebSocket sends, serialised. The counter
// `cpu_fraction` is the share of one core the model takes at 5 Hz (target: a
// few per cent); a snapshot (a page connecting) is measured apart.
//   build/bin/command_center_bench [--benchmark_filter=...]
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "fireswarm/common/local_frame.hpp"
#include "fireswarm/server/command_center.hpp"

namespace {

using fireswarm::vehicle_state_t;
using fireswarm::common::EastNorth;
using fireswarm::common::LatLon;
using fireswarm::common::LocalFrame;
using fireswarm::server::CommandCenter;

constexpr double kWebHz = 5.0;
constexpr double kSpacingM = 40.0;  // apart on a grid: no separation alerts
constexpr double kStepM = 3.0;      // flown between two ticks (15 m/s at 5 Hz)

struct Fleet {
  explicit Fleet(int drones) : frame(LatLon{46.5, 6.6}) {
    const int side = static_cast<int>(std::ceil(std::sqrt(drones)));
    for (int i = 0; i < drones; ++i) {
      vehicle_state_t m{};
      m.receiver_id = static_cast<std::int16_t>(i + 1);
      m.has_position = true;
      m.altitude_m = 60.0;
      m.velocity_east_mps = kStepM * kWebHz;
      m.heading_deg = 90.0;
      m.battery_percent = 90.0;
      m.flight_mode = vehicle_state_t::MODE_SEARCH;
      m.link_state = vehicle_state_t::LINK_OK;
      m.telemetry_hz = 2.0;
      m.task = vehicle_state_t::TASK_LANE;
      m.lane_index = 1;
      m.lane_count = 10;
      states.push_back(m);
      start.push_back({kSpacingM * (i % side), kSpacingM * (i / side)});
    }
  }
  // Every drone's message at tick `tick`: moved, a little older telemetry, less battery.
  void Advance(int tick) {
    for (std::size_t i = 0; i < states.size(); ++i) {
      vehicle_state_t& m = states[i];
      const LatLon p = frame.ToGeodetic({start[i].east_m + kStepM * tick, start[i].north_m});
      m.utime = static_cast<std::int64_t>(tick * 1e6 / kWebHz);
      m.lat_deg = p.lat_deg;
      m.lon_deg = p.lon_deg;
      m.telemetry_age_s = 0.1 * (tick % 5);
      m.battery_percent = 90.0 - 0.001 * tick;
      m.progress_fraction = 0.001 * tick;
    }
  }
  LocalFrame frame;
  std::vector<vehicle_state_t> states;
  std::vector<EastNorth> start;
};

void BM_TickWithDelta(benchmark::State& state) {
  Fleet fleet(static_cast<int>(state.range(0)));
  CommandCenter center({});
  // Ticks are precomputed in a ring so the benchmark times the model, not the
  // projection (at the wrap the drones jump back: a long trail step, nothing more).
  constexpr int kRing = 50;
  std::vector<std::vector<vehicle_state_t>> ticks;
  for (int t = 0; t < kRing; ++t) {
    fleet.Advance(t);
    ticks.push_back(fleet.states);
  }
  int tick = 0;
  std::size_t bytes = 0;
  for (auto _ : state) {
    const std::vector<vehicle_state_t>& messages = ticks[static_cast<std::size_t>(tick % kRing)];
    for (const vehicle_state_t& m : messages) center.OnVehicleState(m);
    const std::optional<nlohmann::json> delta = center.TakeDelta();
    if (delta) bytes += delta->dump().size();
    ++tick;
  }
  state.counters["delta_bytes"] =
      benchmark::Counter(static_cast<double>(bytes) / static_cast<double>(tick));
  // Seconds per tick x ticks per second = share of one core.
  state.counters["cpu_fraction"] =
      benchmark::Counter(static_cast<double>(state.iterations()) / kWebHz,
                         benchmark::Counter::kIsRate | benchmark::Counter::kInvert);
}
BENCHMARK(BM_TickWithDelta)->Arg(10)->Arg(250)->Unit(benchmark::kMicrosecond);

void BM_Snapshot(benchmark::State& state) {
  Fleet fleet(static_cast<int>(state.range(0)));
  CommandCenter center({});
  for (int t = 0; t < 200; ++t) {  // full trails
    fleet.Advance(t);
    for (const vehicle_state_t& m : fleet.states) center.OnVehicleState(m);
  }
  std::size_t bytes = 0;
  for (auto _ : state) {
    const std::string text = center.State().dump();
    bytes = text.size();
    benchmark::DoNotOptimize(text.data());
  }
  state.counters["snapshot_bytes"] = benchmark::Counter(static_cast<double>(bytes));
}
BENCHMARK(BM_Snapshot)->Arg(250)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
