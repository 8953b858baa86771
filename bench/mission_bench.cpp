// mission_bench: the real-time factor of whole missions (issue 16: >= 200 x on
// one core for real forest boundaries of 30-80 km^2 with 10-20 drones). Runs a
// scenario (default bench/scenarios/gory10.yaml) N times through the same
// runner as `fireswarm run` and prints, per run and as the median: simulated
// seconds, wall and CPU seconds of the whole run and of its lockstep loop alone
// (the run less the planning and set-up before the first step), and the
// real-time factors. The CPU figures are this process's (CLOCK_PROCESS_CPUTIME_ID),
// steadier than wall time on a shared machine. Each run's final state hash is
// printed: runs of one binary must agree, and a change that keeps it keeps the
// results. --min-loop-rtf X exits 1 when the median loop real-time factor
// (CPU) is below X.
//
//   mission_bench [--scenario FILE] [--runs N] [--duration-s S] [--min-loop-rtf X]
#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <exception>
#include <optional>
#include <string>
#include <vector>

#include "fireswarm/run/runner.hpp"
#include "fireswarm/run/scenario.hpp"

namespace {

namespace fr = fireswarm::run;

// Wall (monotonic) and this process's CPU time, s.
struct Clocks {
  double wall_s = 0.0;
  double cpu_s = 0.0;

  static Clocks Now() {
    const auto seconds = [](clockid_t id) {
      timespec t{};
      clock_gettime(id, &t);
      return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
    };
    return {seconds(CLOCK_MONOTONIC), seconds(CLOCK_PROCESS_CPUTIME_ID)};
  }
  Clocks operator-(const Clocks& other) const {
    return {wall_s - other.wall_s, cpu_s - other.cpu_s};
  }
};

struct Figures {
  double sim_s = 0.0;
  Clocks whole;
  Clocks loop;  // from the first lockstep step on
  std::uint64_t state_hash = 0;

  double LoopRtfCpu() const { return loop.cpu_s > 0.0 ? sim_s / loop.cpu_s : 0.0; }
};

Figures RunOnce(const fr::Scenario& scenario) {
  const Clocks start = Clocks::Now();
  std::optional<Clocks> first_step;
  fr::RunOptions options;
  options.on_step = [&](double, fireswarm::server::Server&) {
    if (!first_step) first_step = Clocks::Now();
  };
  const fr::RunResult result = fr::RunScenario(scenario, options);
  const Clocks end = Clocks::Now();
  Figures figures;
  figures.sim_s = result.report.sim_seconds;
  figures.whole = end - start;
  figures.loop = end - first_step.value_or(start);
  figures.state_hash = result.state_hash;
  return figures;
}

double Ratio(double sim_s, double spent_s) {
  return spent_s > 0.0 ? sim_s / spent_s : 0.0;
}

void Print(const char* label, const Figures& f) {
  std::printf("%-7s %8.1f  %7.2f %7.2f  %7.2f %7.2f  %7.1f %7.1f  %7.1f %7.1f  %016" PRIx64 "\n",
              label, f.sim_s, f.whole.wall_s, f.whole.cpu_s, f.loop.wall_s, f.loop.cpu_s,
              Ratio(f.sim_s, f.whole.wall_s), Ratio(f.sim_s, f.whole.cpu_s),
              Ratio(f.sim_s, f.loop.wall_s), Ratio(f.sim_s, f.loop.cpu_s), f.state_hash);
}

// The median of one figure over the runs (the upper one of an even count).
template <typename Figure>
double Median(const std::vector<Figures>& runs, Figure figure) {
  std::vector<double> values;
  for (const Figures& f : runs) values.push_back(figure(f));
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

[[noreturn]] void Usage(const char* problem) {
  std::fprintf(stderr,
               "mission_bench: %s\nusage: mission_bench [--scenario FILE] [--runs N] "
               "[--duration-s S] [--min-loop-rtf X]\n",
               problem);
  std::exit(2);
}

double PositiveNumber(const char* text, const char* flag) {
  char* end = nullptr;
  const double value = std::strtod(text, &end);
  if (*end != '\0' || !(value > 0.0)) Usage((std::string(flag) + ": a number > 0").c_str());
  return value;
}

}  // namespace

int main(int argc, char** argv) {
  std::string path = "bench/scenarios/gory10.yaml";
  int runs = 3;
  std::optional<double> duration_s;
  std::optional<double> min_loop_rtf;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--scenario" && i + 1 < argc) {
      path = argv[++i];
    } else if (arg == "--runs" && i + 1 < argc) {
      char* end = nullptr;
      const long n = std::strtol(argv[++i], &end, 10);
      if (*end != '\0' || n < 1 || n > 100) Usage("--runs: an integer in 1..100");
      runs = static_cast<int>(n);
    } else if (arg == "--duration-s" && i + 1 < argc) {
      duration_s = PositiveNumber(argv[++i], "--duration-s");
    } else if (arg == "--min-loop-rtf" && i + 1 < argc) {
      min_loop_rtf = PositiveNumber(argv[++i], "--min-loop-rtf");
    } else {
      Usage(("unknown or incomplete argument: " + arg).c_str());
    }
  }
  try {
    fr::Scenario scenario = fr::LoadScenario(path);
    if (duration_s) scenario.duration_s = *duration_s;
    std::printf("%s: %d run(s), %d drones\n", path.c_str(), runs, scenario.fleet.count);
    std::printf(
        "run        sim s  whole s: wall     cpu  loop s: wall     cpu  x whole: wall     cpu  "
        "x loop: wall     cpu  state hash\n");
    std::vector<Figures> all;
    for (int k = 0; k < runs; ++k) {
      all.push_back(RunOnce(scenario));
      Print(std::to_string(k + 1).c_str(), all.back());
    }
    Figures median;
    median.sim_s = all.front().sim_s;
    median.whole.wall_s = Median(all, [](const Figures& f) { return f.whole.wall_s; });
    median.whole.cpu_s = Median(all, [](const Figures& f) { return f.whole.cpu_s; });
    median.loop.wall_s = Median(all, [](const Figures& f) { return f.loop.wall_s; });
    median.loop.cpu_s = Median(all, [](const Figures& f) { return f.loop.cpu_s; });
    median.state_hash = all.front().state_hash;
    Print("median", median);
    const bool same = std::all_of(all.begin(), all.end(), [&](const Figures& f) {
      return f.state_hash == all.front().state_hash && f.sim_s == all.front().sim_s;
    });
    if (!same) {
      std::printf("FAIL: the runs differ (state hash or simulated time): not deterministic\n");
      return 1;
    }
    if (min_loop_rtf && median.LoopRtfCpu() < *min_loop_rtf) {
      std::printf("FAIL: loop real-time factor (CPU) x%.1f under x%.1f\n", median.LoopRtfCpu(),
                  *min_loop_rtf);
      return 1;
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "mission_bench: %s\n", e.what());
    return 2;
  }
}
