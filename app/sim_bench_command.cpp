// `fireswarm sim-bench`: N vehicles with thermal cameras fly lawnmower lanes over
// a burning square; prints how many simulated seconds pass per wall second and
// where the time goes (physics, fire, cameras), as a table or one JSON object.
#include <chrono>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cli.hpp"
#include "commands.hpp"
#include "fireswarm/bench/bench_scenario.hpp"
#include "fireswarm/sim2d/simulation.hpp"

namespace fireswarm::app {
namespace {

namespace po = boost::program_options;
using Clock = std::chrono::steady_clock;

constexpr const char* kName = "sim-bench";
constexpr double kMaxSeconds = 86'400.0;

struct Figures {
  double sim_seconds = 0.0;
  double wall_seconds = 0.0;
  double pilots_s = 0.0;
  double physics_s = 0.0;
  double fire_s = 0.0;
  double cameras_s = 0.0;
  std::int64_t steps = 0;
  std::int64_t camera_frames = 0;
  std::size_t collisions = 0;
  std::size_t near_misses = 0;
  double min_separation_m = 0.0;
  std::size_t burning_cells = 0;
  double burned_area_m2 = 0.0;
  std::uint64_t state_hash = 0;
};

double Since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

// Steps the simulation for `seconds`, timing each part on the wall clock.
Figures Fly(bench::BenchScenario& scenario, double seconds) {
  sim2d::Simulation sim(scenario.config);
  sim2d::World& world = sim.world();
  const auto steps = static_cast<std::int64_t>(std::llround(seconds / world.step_s()));
  Figures f;
  const Clock::time_point start = Clock::now();
  for (std::int64_t step = 0; step < steps; ++step) {
    Clock::time_point t = Clock::now();
    const auto truths = world.Truths();
    for (std::size_t i = 0; i < scenario.pilots.size(); ++i) {
      world.SetCommandAt(i, scenario.pilots[i].Command(truths[i]));
    }
    f.pilots_s += Since(t);
    t = Clock::now();
    sim.StepPhysics();
    f.physics_s += Since(t);
    t = Clock::now();
    sim.StepFire();
    f.fire_s += Since(t);
    t = Clock::now();
    sim.StepCameras();
    f.cameras_s += Since(t);
  }
  f.wall_seconds = Since(start);
  f.steps = steps;
  f.sim_seconds = sim.time_s();
  f.camera_frames = sim.camera_frames();
  f.collisions = world.events().count(sim2d::EventKind::kCollision);
  f.near_misses = world.events().count(sim2d::EventKind::kNearMiss);
  f.min_separation_m = world.min_separation_m();
  f.burning_cells = sim.fire().burning_count();
  f.burned_area_m2 = sim.fire().BurnedAreaM2();
  f.state_hash = sim.StateHash();
  return f;
}

std::string HexHash(std::uint64_t hash) {
  std::ostringstream out;
  out << std::hex << std::setw(16) << std::setfill('0') << hash;
  return out.str();
}

nlohmann::ordered_json ToJson(const bench::BenchScenarioSpec& spec, const Figures& f) {
  nlohmann::ordered_json j;
  j["drones"] = spec.drones;
  j["camera"] = spec.camera;
  j["area_km2"] = spec.area_km2;
  j["seed"] = spec.seed;
  j["sim_seconds"] = f.sim_seconds;
  j["wall_seconds"] = f.wall_seconds;
  j["real_time_factor"] = f.sim_seconds / f.wall_seconds;
  j["steps"] = f.steps;
  j["camera_frames"] = f.camera_frames;
  j["wall_seconds_by_part"] = {{"pilots", f.pilots_s},
                               {"physics", f.physics_s},
                               {"fire", f.fire_s},
                               {"cameras", f.cameras_s}};
  j["collisions"] = f.collisions;
  j["near_misses"] = f.near_misses;
  j["min_separation_m"] = std::isfinite(f.min_separation_m)
                              ? nlohmann::ordered_json(f.min_separation_m)
                              : nlohmann::ordered_json(nullptr);
  j["burning_cells"] = f.burning_cells;
  j["burned_area_m2"] = f.burned_area_m2;
  j["state_hash"] = HexHash(f.state_hash);
  return j;
}

void PrintTable(const bench::BenchScenarioSpec& spec, const Figures& f) {
  std::cout << std::fixed << std::setprecision(3);
  std::cout << "sim-bench: " << spec.drones << " drones, camera " << spec.camera << ", "
            << spec.area_km2 << " km^2, " << f.sim_seconds << " simulated s, seed " << spec.seed
            << "\n";
  const auto row = [](const char* name, const auto& value) {
    std::cout << "  " << std::left << std::setw(30) << name << value << "\n";
  };
  const auto share = [&](double part_s) {
    std::ostringstream out;
    out << std::fixed << std::setprecision(3) << part_s << " s (" << std::setprecision(1)
        << 100.0 * part_s / f.wall_seconds << " %)";
    return out.str();
  };
  row("real-time factor", f.sim_seconds / f.wall_seconds);
  row("wall time (s)", f.wall_seconds);
  row("  pilots", share(f.pilots_s));
  row("  physics", share(f.physics_s));
  row("  fire", share(f.fire_s));
  row("  cameras", share(f.cameras_s));
  row("camera frames", f.camera_frames);
  row("collisions / near misses",
      std::to_string(f.collisions) + " / " + std::to_string(f.near_misses));
  row("burning cells at end", f.burning_cells);
  row("state hash", HexHash(f.state_hash));
}

}  // namespace

int RunSimBench(const std::vector<std::string>& args) {
  bench::BenchScenarioSpec spec;
  double seconds = 60.0;
  bool json = false;
  po::options_description options("sim-bench options");
  auto add = options.add_options();
  add("drones", po::value(&spec.drones)->default_value(spec.drones), "number of vehicles, 1..1000");
  add("camera", po::value(&spec.camera)->default_value(spec.camera),
      "thermal camera on every vehicle: seed|amg8833|lepton35|none");
  add("area-km2", po::value(&spec.area_km2)->default_value(spec.area_km2),
      "area of the burning square, km^2");
  add("seconds", po::value(&seconds)->default_value(seconds), "simulated seconds");
  add("fires", po::value(&spec.fires)->default_value(spec.fires), "random ignitions at t = 0");
  add("distractors", po::value(&spec.distractors)->default_value(spec.distractors),
      "random hot rocks (40-70 C)");
  add("altitude-m", po::value(&spec.altitude_m)->default_value(spec.altitude_m),
      "lowest lane altitude above ground");
  add("speed-mps", po::value(&spec.speed_mps)->default_value(spec.speed_mps), "lane speed");
  add("seed", po::value(&spec.seed)->default_value(spec.seed), "random seed");
  add("json", po::bool_switch(&json), "print one JSON object instead of the table");
  po::variables_map values;
  if (!ParseCommandLine(kName, "[options]", options, {}, args, values)) return kExitOk;
  if (!(seconds > 0.0 && seconds <= kMaxSeconds)) {
    throw UsageError("fireswarm sim-bench: --seconds must be in (0, 86400], got " +
                     std::to_string(seconds));
  }
  bench::BenchScenario scenario;
  try {
    scenario = bench::MakeBenchScenario(spec);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("fireswarm sim-bench: ") + e.what());
  }
  const Figures figures = Fly(scenario, seconds);
  if (json) {
    std::cout << ToJson(spec, figures).dump() << "\n";
  } else {
    PrintTable(spec, figures);
  }
  return kExitOk;
}

}  // namespace fireswarm::app
