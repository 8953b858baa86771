// separation_bench: the coordination figures of README.md ("Keeping the drones
// apart"). Flies a scenario (default bench/scenarios/separation120.yaml) once
// per seed S..S+N-1, with the server's tactical resolution and sequenced
// take-offs and, with --compare, again without both (separation.resolve and
// sequence_takeoffs false, the same layers), and prints per seed and pooled:
// collisions, the minimum separation, conflicts predicted, orders sent,
// conflicts lost, take-off clearances held, the time until the last drone
// landed, the distance flown, the fleet's time in the air, and the real-time
// factor. The added flight time of resolution is the pooled time in the air
// with against without (the makespan's change is printed too). --check exits 1 when
// a run with resolution collides or comes closer than the limit.
//
//   separation_bench [--scenario FILE] [--seeds N] [--first-seed S] [--compare]
//                    [--check] [--count N] [--duration-s S]
// --count and --duration-s change the scenario's fleet size and duration (the
// smoke test flies a few drones for two minutes).
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <limits>
#include <optional>
#include <string>

#include "fireswarm/run/runner.hpp"
#include "fireswarm/run/scenario.hpp"

namespace {

namespace fr = fireswarm::run;

struct Tally {
  int runs = 0;
  std::size_t collisions = 0;
  double min_separation_m = std::numeric_limits<double>::infinity();
  std::uint64_t conflicts = 0;
  std::uint64_t orders = 0;
  std::uint64_t lost = 0;
  std::uint64_t held = 0;
  double makespan_s = 0.0;
  double airborne_h = 0.0;
  double distance_km = 0.0;
  double sim_s = 0.0;
  double wall_s = 0.0;

  void Add(const fr::Report& report) {
    ++runs;
    collisions += report.collisions.size();
    if (report.min_separation_m) {
      min_separation_m = std::min(min_separation_m, *report.min_separation_m);
    }
    conflicts += report.separation.conflicts;
    orders += report.separation.orders;
    lost += report.separation.lost_separation;
    held += report.separation.takeoffs_held;
    makespan_s += report.sim_seconds;
    for (const auto& [id, vehicle] : report.vehicles) {
      distance_km += vehicle.distance_m / 1'000.0;
      airborne_h += vehicle.airborne_s / 3'600.0;
    }
    sim_s += report.sim_seconds;
    wall_s += report.wall_seconds;
  }
  void Add(const Tally& other) {
    runs += other.runs;
    collisions += other.collisions;
    min_separation_m = std::min(min_separation_m, other.min_separation_m);
    conflicts += other.conflicts;
    orders += other.orders;
    lost += other.lost;
    held += other.held;
    makespan_s += other.makespan_s;
    airborne_h += other.airborne_h;
    distance_km += other.distance_km;
    sim_s += other.sim_s;
    wall_s += other.wall_s;
  }
  void Print(const std::string& label) const {
    const double per_run = runs > 0 ? 1.0 / runs : 0.0;
    std::printf("%-12s %4d %6zu %8.2f %9llu %7llu %5llu %6llu %10.0f %9.1f %8.2f %6.1f\n",
                label.c_str(), runs, collisions, min_separation_m,
                static_cast<unsigned long long>(conflicts), static_cast<unsigned long long>(orders),
                static_cast<unsigned long long>(lost), static_cast<unsigned long long>(held),
                makespan_s * per_run, distance_km * per_run, airborne_h * per_run,
                wall_s > 0.0 ? sim_s / wall_s : 0.0);
  }
};

[[noreturn]] void Usage(const char* problem) {
  std::fprintf(stderr,
               "separation_bench: %s\nusage: separation_bench [--scenario FILE] [--seeds N] "
               "[--first-seed S] [--compare] [--check] [--count N] [--duration-s S]\n",
               problem);
  std::exit(2);
}

long IntegerArg(const char* text, long low, long high, const char* flag) {
  char* end = nullptr;
  const long n = std::strtol(text, &end, 10);
  if (*end != '\0' || n < low || n > high) {
    Usage((std::string(flag) + ": an integer in " + std::to_string(low) + ".." +
           std::to_string(high))
              .c_str());
  }
  return n;
}

}  // namespace

int main(int argc, char** argv) {
  std::string path = "bench/scenarios/separation120.yaml";
  int seeds = 10;
  std::optional<std::uint64_t> first_seed;
  std::optional<int> count;
  std::optional<int> duration_s;
  bool compare = false;
  bool check = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--scenario" && i + 1 < argc) {
      path = argv[++i];
    } else if (arg == "--seeds" && i + 1 < argc) {
      seeds = static_cast<int>(IntegerArg(argv[++i], 1, 1000, "--seeds"));
    } else if (arg == "--first-seed" && i + 1 < argc) {
      first_seed = static_cast<std::uint64_t>(IntegerArg(argv[++i], 0, 1'000'000'000, "--first-seed"));
    } else if (arg == "--count" && i + 1 < argc) {
      count = static_cast<int>(IntegerArg(argv[++i], 1, 254, "--count"));
    } else if (arg == "--duration-s" && i + 1 < argc) {
      duration_s = static_cast<int>(IntegerArg(argv[++i], 1, 86'400, "--duration-s"));
    } else if (arg == "--compare") {
      compare = true;
    } else if (arg == "--check") {
      check = true;
    } else {
      Usage(("unknown or incomplete argument: " + arg).c_str());
    }
  }
  try {
    fr::Scenario scenario = fr::LoadScenario(path);
    if (count) {
      scenario.fleet.count = *count;
      // Faults of drones no longer in the fleet go with them.
      const int last_id = scenario.fleet.first_id + *count - 1;
      std::erase_if(scenario.faults, [&](const fr::FaultSpec& f) { return f.vehicle > last_id; });
    }
    if (duration_s) scenario.duration_s = *duration_s;
    const std::uint64_t first = first_seed.value_or(scenario.seed);
    std::printf("%s: %d drones, %d seeds from %llu, limit %.1f m\n", path.c_str(),
                scenario.fleet.count, seeds, static_cast<unsigned long long>(first),
                scenario.separation.separation_m);
    std::printf("%-12s %4s %6s %8s %9s %7s %5s %6s %10s %9s %8s %6s\n", "seed", "runs", "coll",
                "min sep", "conflicts", "orders", "lost", "held", "makespan s", "km/run",
                "air h/run", "x real");
    Tally with_all;
    Tally without_all;
    for (int k = 0; k < seeds; ++k) {
      scenario.seed = first + static_cast<std::uint64_t>(k);
      scenario.separation.resolve = true;
      scenario.separation.sequence_takeoffs = true;
      Tally with;
      with.Add(fr::RunScenario(scenario).report);
      with.Print(std::to_string(scenario.seed));
      with_all.Add(with);
      if (compare) {
        scenario.separation.resolve = false;
        scenario.separation.sequence_takeoffs = false;
        Tally without;
        without.Add(fr::RunScenario(scenario).report);
        without.Print(std::to_string(scenario.seed) + " unres.");
        without_all.Add(without);
      }
    }
    with_all.Print("all");
    if (compare) {
      without_all.Print("all unres.");
      std::printf("added flight time (time in the air, with against without): %+.2f %%\n",
                  100.0 * (with_all.airborne_h / without_all.airborne_h - 1.0));
      std::printf("added makespan: %+.2f %%\n",
                  100.0 * (with_all.makespan_s / without_all.makespan_s - 1.0));
      std::printf("added distance: %+.2f %%\n",
                  100.0 * (with_all.distance_km / without_all.distance_km - 1.0));
    }
    if (check && (with_all.collisions > 0 ||
                  with_all.min_separation_m < scenario.separation.separation_m)) {
      std::printf("FAIL: %zu collision(s), minimum separation %.2f m (limit %.1f m)\n",
                  with_all.collisions, with_all.min_separation_m,
                  scenario.separation.separation_m);
      return 1;
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "separation_bench: %s\n", e.what());
    return 2;
  }
}
