// soak_bench: the soak figures of README.md (issue 19). Flies a patrol scenario
// (default bench/scenarios/soak50.yaml: 50 drones, a round every hour, a whole
// simulated day) in one process and samples, every simulated hour (--sample-s), the
// process's memory (resident set and the bytes malloc holds in use) and the size
// of every store of the server's that could grow with time: fire tracks and the
// reports they keep, the report IDs the duplicate check remembers, conflicts, operator commands,
// investigations, and the journal a restart would read.
//
// --check exits 1 when the memory in use grew by more than --max-growth (5 %
// by default) from the end of the first hour to the end, or a report was lost, or
// two drones collided.
//
//   soak_bench [--scenario FILE] [--hours H] [--count N] [--every-s S]
//              [--sample-s S] [--max-growth F] [--check]
// --hours, --count and --every-s change the scenario's duration, fleet size and
// patrol interval; --sample-s the sampling interval (an hour). The smoke test
// flies 2 drones for a quarter of an hour.
#include <malloc.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <fstream>
#include <optional>
#include <string>
#include <vector>

#include "fireswarm/run/runner.hpp"
#include "fireswarm/run/scenario.hpp"
#include "fireswarm/server/server.hpp"

namespace {

namespace fr = fireswarm::run;

constexpr double kHourS = 3'600.0;
constexpr double kMiB = 1024.0 * 1024.0;

// One hourly sample.
struct Sample {
  double sim_h = 0.0;
  double wall_s = 0.0;
  double resident_mib = 0.0;
  double in_use_mib = 0.0;  // malloc's bytes handed out and not freed
  int round = 0;
  std::size_t tracks = 0;
  std::size_t track_reports = 0;
  std::size_t remembered = 0;  // report IDs the duplicate check holds
  std::size_t conflicts = 0;
  std::size_t commands = 0;
  std::size_t investigations = 0;
  std::size_t journal = 0;
};

double ResidentMib() {
  std::ifstream statm("/proc/self/statm");
  long pages_total = 0;
  long pages_resident = 0;
  statm >> pages_total >> pages_resident;
  return static_cast<double>(pages_resident) * static_cast<double>(sysconf(_SC_PAGESIZE)) / kMiB;
}

double InUseMib() {
  const struct mallinfo2 info = mallinfo2();
  // Small blocks from the arenas and large ones mapped on their own.
  return static_cast<double>(info.uordblks + info.hblkhd) / kMiB;
}

void PrintHeader() {
  std::printf("%6s %7s %5s %8s %8s %6s %8s %8s %9s %8s %6s %8s\n", "sim h", "wall s", "round",
              "RSS MiB", "use MiB", "tracks", "t.rep", "seen", "conflicts", "commands", "invest",
              "journal");
}

void Print(const Sample& s) {
  std::printf("%6.1f %7.0f %5d %8.1f %8.2f %6zu %8zu %8zu %9zu %8zu %6zu %8zu\n", s.sim_h, s.wall_s,
              s.round, s.resident_mib, s.in_use_mib, s.tracks, s.track_reports, s.remembered,
              s.conflicts, s.commands, s.investigations, s.journal);
  std::fflush(stdout);
}

[[noreturn]] void Usage(const char* problem) {
  std::fprintf(stderr,
               "soak_bench: %s\nusage: soak_bench [--scenario FILE] [--hours H] [--count N] "
               "[--every-s S] [--sample-s S] [--max-growth F] [--check]\n",
               problem);
  std::exit(2);
}

double NumberArg(const char* text, double low, double high, const char* flag) {
  char* end = nullptr;
  const double x = std::strtod(text, &end);
  if (*end != '\0' || !(x >= low && x <= high)) {
    Usage((std::string(flag) + ": a number in [" + std::to_string(low) + ", " +
           std::to_string(high) + "]")
              .c_str());
  }
  return x;
}

}  // namespace

int main(int argc, char** argv) {
  std::string path = "bench/scenarios/soak50.yaml";
  std::optional<double> hours;
  std::optional<int> count;
  std::optional<double> every_s;
  double sample_s = kHourS;
  double max_growth = 0.05;
  bool check = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--scenario" && i + 1 < argc) {
      path = argv[++i];
    } else if (arg == "--hours" && i + 1 < argc) {
      hours = NumberArg(argv[++i], 0.1, 24.0, "--hours");
    } else if (arg == "--count" && i + 1 < argc) {
      count = static_cast<int>(NumberArg(argv[++i], 1, 254, "--count"));
    } else if (arg == "--every-s" && i + 1 < argc) {
      every_s = NumberArg(argv[++i], 60.0, 86'400.0, "--every-s");
    } else if (arg == "--sample-s" && i + 1 < argc) {
      sample_s = NumberArg(argv[++i], 60.0, 86'400.0, "--sample-s");
    } else if (arg == "--max-growth" && i + 1 < argc) {
      max_growth = NumberArg(argv[++i], 0.0, 10.0, "--max-growth");
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
      const int last_id = scenario.fleet.first_id + *count - 1;
      std::erase_if(scenario.faults, [&](const fr::FaultSpec& f) { return f.vehicle > last_id; });
    }
    if (hours) scenario.duration_s = *hours * kHourS;
    if (every_s) scenario.patrol = fr::PatrolSpec{*every_s};
    if (!scenario.patrol) Usage("the scenario has no patrol: a soak flies round after round");
    std::printf("%s: %d drones, a round every %.0f s, %.1f simulated hours\n", path.c_str(),
                scenario.fleet.count, scenario.patrol->every_s, scenario.duration_s / kHourS);
    PrintHeader();

    std::vector<Sample> samples;
    const auto wall_start = std::chrono::steady_clock::now();
    // The server of the latest step (a restart replaces it), sampled with the
    // runner's progress, which knows the journal.
    const fireswarm::server::Server* server = nullptr;
    fr::RunOptions options;
    options.on_step = [&](double, const fireswarm::server::Server& now) { server = &now; };
    options.progress_interval_s = sample_s;
    options.progress = [&](const fr::RunProgress& progress) {
      if (server == nullptr ||
          progress.sim_s < sample_s * static_cast<double>(samples.size() + 1) - 1e-6)
        return;
      Sample s;
      s.sim_h = progress.sim_s / kHourS;
      s.wall_s =
          std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
      s.resident_mib = ResidentMib();
      s.in_use_mib = InUseMib();
      s.round = progress.missions;
      s.tracks = server->fusion().tracks().size();
      for (const auto& track : server->fusion().tracks()) s.track_reports += track.reports.size();
      s.remembered = server->fusion().state().seen.size();
      s.conflicts = server->traffic().conflicts().size();
      s.commands = server->commands().size();
      s.investigations = server->investigations().size();
      s.journal = progress.journal_entries;
      samples.push_back(s);
      Print(s);
    };
    const fr::RunResult result = fr::RunScenario(scenario, options);
    const fr::Report& report = result.report;
    std::printf(
        "%d rounds, %.0f simulated s in %.0f wall s (x%.0f), reports lost %llu, "
        "collisions %zu, min separation %.2f m\n",
        result.missions, report.sim_seconds, report.wall_seconds, report.real_time_factor,
        static_cast<unsigned long long>(report.radio.reports_lost), report.collisions.size(),
        report.min_separation_m.value_or(0.0));
    if (samples.size() < 2) {
      std::printf("fewer than two samples: no growth figure\n");
      return check ? 1 : 0;
    }
    // From the end of the first interval (the first round has built every table
    // it needs) to the end.
    const double growth = samples.back().in_use_mib / samples.front().in_use_mib - 1.0;
    const double rss_growth = samples.back().resident_mib / samples.front().resident_mib - 1.0;
    std::printf(
        "memory in use after hour 1 -> end: %.2f -> %.2f MiB (%+.2f %%); resident "
        "%.1f -> %.1f MiB (%+.2f %%)\n",
        samples.front().in_use_mib, samples.back().in_use_mib, 100.0 * growth,
        samples.front().resident_mib, samples.back().resident_mib, 100.0 * rss_growth);
    if (check &&
        (growth > max_growth || report.radio.reports_lost > 0 || !report.collisions.empty())) {
      std::printf("FAIL: growth %+.2f %% (limit %+.2f %%), %llu report(s) lost, %zu collision(s)\n",
                  100.0 * growth, 100.0 * max_growth,
                  static_cast<unsigned long long>(report.radio.reports_lost),
                  report.collisions.size());
      return 1;
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "soak_bench: %s\n", e.what());
    return 2;
  }
}
