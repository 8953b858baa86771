// `fireswarm run SCENARIO.yaml`: flies a scenario headless in lockstep on simulated
// time (the runner in server/run), writes the report (JSON), and optionally a JUnit
// file and an SVG map. Exit 0 when every `expect` holds, 1 when one fails, 2 on bad
// input (the scenario error names the file, key and problem). A progress line goes
// to stderr only when stderr is a terminal.
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include "cli.hpp"
#include "commands.hpp"
#include "fireswarm/common/atomic_file.hpp"
#include "fireswarm/run/junit.hpp"
#include "fireswarm/run/report_json.hpp"
#include "fireswarm/run/runner.hpp"
#include "fireswarm/run/scenario.hpp"
#include "fireswarm/run/svg_map.hpp"

namespace fireswarm::app {
namespace {

namespace po = boost::program_options;

constexpr const char* kName = "run";
constexpr int kBarWidth = 30;
/// The progress line is redrawn at most this often (a small run goes at ~1000x).
constexpr std::chrono::milliseconds kRedrawPeriod{100};

void DrawProgress(const run::RunProgress& p) {
  const double fraction = p.duration_s > 0.0 ? std::min(1.0, p.sim_s / p.duration_s) : 1.0;
  const int filled = static_cast<int>(fraction * kBarWidth);
  const std::string bar = std::string(static_cast<std::size_t>(filled), '#') +
                          std::string(static_cast<std::size_t>(kBarWidth - filled), '.');
  std::fprintf(stderr, "\r[%s] %6.0f / %.0f s  coverage %5.1f %%  fires confirmed %zu / %zu ",
               bar.c_str(), p.sim_s, p.duration_s, 100.0 * p.coverage, p.fires_confirmed,
               p.fires_total);
  std::fflush(stderr);
}

void PrintSummary(const run::RunResult& result) {
  const run::Report& report = result.report;
  std::size_t confirmed = 0;
  for (const run::FireOutcome& fire : report.fires) confirmed += fire.confirmed_s ? 1U : 0U;
  std::cout << "fireswarm run: " << report.scenario << ": " << report.sim_seconds
            << " simulated s (" << run::ToString(result.stop) << ") in " << report.wall_seconds
            << " wall s, x" << report.real_time_factor << " real time\n";
  std::cout << "  fires confirmed " << confirmed << " / " << report.fires.size()
            << ", false tracks " << report.false_tracks.size() << ", coverage "
            << 100.0 * report.coverage << " %, collisions " << report.collisions.size() << "\n";
  for (const run::ExpectOutcome& e : report.expect) {
    std::cout << "  " << (e.passed ? "pass" : "FAIL") << "  " << e.name << ": " << e.value
              << " (limit " << e.limit << ")";
    if (!e.passed && !e.detail.empty()) std::cout << ": " << e.detail;
    std::cout << "\n";
  }
}

}  // namespace

int RunRun(const std::vector<std::string>& args) {
  std::string scenario_path;
  std::string report_path;
  std::string junit_path;
  std::string svg_path;
  po::options_description options("run options");
  options.add_options()("report", po::value(&report_path), "write the report (JSON) to this file")(
      "junit", po::value(&junit_path), "write the expectations as a JUnit XML file")(
      "svg", po::value(&svg_path), "write a map of the run (SVG)")(
      "scenario", po::value(&scenario_path)->required(), "the scenario file (YAML)");
  po::positional_options_description positional;
  positional.add("scenario", 1);
  po::variables_map values;
  if (!ParseCommandLine(kName,
                        "SCENARIO.yaml [--report out.json] [--junit out.xml] [--svg map.svg]",
                        options, positional, args, values)) {
    return kExitOk;
  }
  for (const auto& [flag, path] : {std::pair{"report", &report_path},
                                   std::pair{"junit", &junit_path}, std::pair{"svg", &svg_path}}) {
    if (values.count(flag) != 0 && path->empty()) {
      throw UsageError(std::string("fireswarm run: --") + flag + " needs a file name");
    }
  }

  run::Scenario scenario;
  run::RunResult result;
  try {
    scenario = run::LoadScenario(scenario_path);
    run::RunOptions run_options;
    run::RunProgress last;
    std::chrono::steady_clock::time_point drawn{};
    if (isatty(STDERR_FILENO) != 0) {
      run_options.progress = [&](const run::RunProgress& progress) {
        last = progress;
        const auto now = std::chrono::steady_clock::now();
        if (now - drawn < kRedrawPeriod) return;
        drawn = now;
        DrawProgress(progress);
      };
    }
    result = run::RunScenario(scenario, run_options);
    if (run_options.progress) {
      DrawProgress(last);
      std::fputc('\n', stderr);
    }
  } catch (const run::ScenarioError& e) {
    throw UsageError(std::string("fireswarm run: ") + e.what());
  }
  if (!report_path.empty()) {
    common::WriteFileAtomically(report_path, run::ToJson(result.report).dump(2) + "\n");
  }
  if (!junit_path.empty()) run::WriteJunit(result.report, junit_path);
  if (!svg_path.empty()) run::WriteSvgMap(result.report, scenario, svg_path);
  PrintSummary(result);
  return result.report.AllExpectationsHold() ? kExitOk : kExitCheckFailed;
}

}  // namespace fireswarm::app
