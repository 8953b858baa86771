// `fireswarm run SCENARIO.yaml`: flies a scenario headless in lockstep on simulated
// time (the runner in run/), writes the report (JSON), and optionally a JUnit
// file, an SVG map, an LCM log and live LCM traffic. Exit 0 when every `expect`
// holds, 1 when one fails, 2 on bad input (the scenario error names the file, key
// and problem). A progress line goes to stderr only when stderr is a terminal.
//
// LCM (--log, --lcm): the server is published through server::LcmBridge after
// every lockstep step, at the bridge's rates in simulated time, every `utime` being
// kUtimeAtSimZero + simulated microseconds: the same scenario gives the same log.
// Operator commands arriving on --lcm are not taken (the scenario is the script).
//
// The command center (--http, web_flags.hpp): the page and its API served while
// the run goes; its commands reach the server at the step's simulated time.
// --pace K holds simulated time to K times the wall clock, so a person can watch.
// When the run ends, one JSON line {"event": "web_cpu", ...} on stdout gives the
// web adapter's CPU against the process's (WebFeed::CpuFigures).
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

#include "cli.hpp"
#include "commands.hpp"
#include "fireswarm/common/output_files.hpp"
#include "fireswarm/common/time.hpp"
#include "fireswarm/run/junit.hpp"
#include "fireswarm/run/report_json.hpp"
#include "fireswarm/run/runner.hpp"
#include "fireswarm/run/scenario.hpp"
#include "fireswarm/run/svg_map.hpp"
#include "fireswarm/server/lcm_bridge.hpp"
#include "fireswarm/server/operator_keys.hpp"
#include "web_feed.hpp"
#include "web_flags.hpp"

namespace fireswarm::app {
namespace {

namespace po = boost::program_options;
namespace fs = std::filesystem;

constexpr const char* kName = "run";
/// LCM utime of simulated time 0, us: the Unix epoch, so a run's utimes are its
/// simulated microseconds (1970-01-01 to a tool that shows them as dates).
constexpr std::int64_t kUtimeAtSimZero = 0;
constexpr int kBarWidth = 30;
/// --pace above this is no pacing at all (a run goes at ~1000x on its own).
constexpr double kMaxPace = 1e6;
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

struct Flags {
  std::string scenario;
  std::string report;
  std::string junit;
  std::string svg;
  std::string log;      ///< LCM event log, empty = none
  std::string lcm_url;  ///< LCM provider to publish on, empty = none
  WebFlags web;
  std::optional<double> pace;  ///< simulated s per wall s
  std::string keys;            ///< key store whose operators may command the run (--http)
};

// --pace K: simulated time t is due at wall_start + t / K; a step ahead of that
// waits for it.
class Pacer {
 public:
  explicit Pacer(double pace) : pace_(pace), start_(std::chrono::steady_clock::now()) {}
  void WaitFor(double t_s) const {
    std::this_thread::sleep_until(start_ + std::chrono::duration_cast<std::chrono::nanoseconds>(
                                               std::chrono::duration<double>(t_s / pace_)));
  }

 private:
  double pace_;
  std::chrono::steady_clock::time_point start_;
};

// Bad flags end the command before the scenario is read or anything is written.
void CheckFlags(const Flags& f, const po::variables_map& values) {
  for (const auto& [flag, path] : {std::pair{"report", &f.report}, std::pair{"junit", &f.junit},
                                   std::pair{"svg", &f.svg}, std::pair{"log", &f.log}}) {
    if (values.count(flag) != 0 && path->empty()) {
      throw UsageError(std::string("fireswarm run: --") + flag + " needs a file name");
    }
  }
  CheckWebFlags(kName, f.web);
  if (f.pace) CheckFlagRange(kName, "pace", *f.pace, {0.0, kMaxPace, true});
  if (values.count("lcm") != 0 && f.lcm_url.empty()) {
    throw UsageError("fireswarm run: --lcm needs a URL, e.g. udpm://239.255.76.67:7667?ttl=0");
  }
}

// --log and --lcm: the server published through server::LcmBridge on simulated
// time. The bridge writes the log to a temporary of the run's OutputFiles, renamed
// into place with the other outputs, so a run that fails or is cut short leaves
// no log, and a reader never sees half of one.
class RunLcmOutput {
 public:
  /// Opens the LCM URL and the log's temporary `scratch` (empty: no log). Throws
  /// UsageError naming --log or --lcm when either cannot be opened.
  RunLcmOutput(const std::string& log_path, const fs::path& scratch, const std::string& url)
      : log_path_(log_path), url_(url) {
    server::LcmBridgeConfig config;
    config.url = url;
    if (!log_path.empty()) {
      // Created here, so that a failure of the bridge below can only be the URL's.
      if (!std::ofstream(scratch)) {
        throw UsageError("fireswarm run: --log " + log_path + ": cannot create " +
                         scratch.string() + ": " + std::strerror(errno));
      }
      config.log_path = scratch;
    }
    try {
      bridge_.emplace(config);
    } catch (const std::exception& e) {
      throw UsageError(std::string("fireswarm run: ") + (url.empty() ? "--log: " : "--lcm: ") +
                       e.what());
    }
  }
  RunLcmOutput(const RunLcmOutput&) = delete;
  RunLcmOutput& operator=(const RunLcmOutput&) = delete;

  /// Publishes what is due at `t_s` (simulated s). Throws std::runtime_error when
  /// the log cannot be written.
  void Publish(double t_s, const server::Server& server) {
    const std::int64_t utime =
        kUtimeAtSimZero + static_cast<std::int64_t>(std::llround(t_s * common::kMicrosPerSecond));
    bridge_->Publish(server, t_s, utime, kUtimeAtSimZero);
  }

  /// Closes the log's temporary; OutputFiles::Commit() moves it into place.
  void Finish() {
    published_ = bridge_->published();
    bridge_.reset();
  }

  /// What Finish() ended with: the messages published (and logged), where.
  void PrintSummary() const {
    if (!log_path_.empty()) {
      std::cout << "  LCM log " << log_path_.string() << ": " << published_
                << " messages, utime = simulated us\n";
    }
    if (!url_.empty()) {
      std::cout << "  LCM: " << published_ << " messages published on " << url_ << "\n";
    }
  }

 private:
  fs::path log_path_;
  std::string url_;
  std::optional<server::LcmBridge> bridge_;
  std::uint64_t published_ = 0;
};

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
  if (result.missions > 1) std::cout << "  patrol: " << result.missions << " rounds started\n";
  if (result.server_restarts > 0) {
    std::cout << "  server restarted from its journal " << result.server_restarts << " times\n";
  }
  if (result.vehicle_reboots > 0) {
    std::cout << "  vehicles rebooted from their non-volatile storage " << result.vehicle_reboots
              << " times\n";
  }
  int planned = 0;
  int flown = 0;
  int swaps = 0;
  for (const auto& [id, vehicle] : report.vehicles) {
    planned += vehicle.sorties_planned;
    flown += vehicle.sorties_flown;
    swaps += vehicle.battery_swaps;
  }
  if (planned > static_cast<int>(report.vehicles.size())) {
    std::cout << "  sorties flown " << flown << " / " << planned << " planned, battery swaps "
              << swaps << "\n";
  }
  for (const run::ExpectOutcome& e : report.expect) {
    std::cout << "  " << (e.passed ? "pass" : "FAIL") << "  " << e.name << ": " << e.value
              << " (limit " << e.limit << ")";
    if (!e.passed && !e.detail.empty()) std::cout << ": " << e.detail;
    std::cout << "\n";
  }
}

// Flies the scenario, publishing on LCM when `lcm` is given and serving the page
// when `web` is; paced when `pace` is; a progress line on a terminal.
run::RunResult Fly(const run::Scenario& scenario, RunLcmOutput* lcm, server::WebServer* web,
                   std::optional<double> pace, std::map<std::string, common::SecretKey> operators) {
  run::RunOptions run_options;
  run_options.operators = std::move(operators);
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
  std::optional<Pacer> pacer;
  if (pace) pacer.emplace(*pace);
  std::optional<WebFeed> feed;
  if (web != nullptr) feed.emplace(*web, "simulated");
  if (lcm != nullptr || feed || pacer) {
    run_options.on_step = [&](double t_s, server::Server& server) {
      if (lcm != nullptr) lcm->Publish(t_s, server);
      if (feed) {
        feed->Step(server, common::FromSeconds(t_s),
                   kUtimeAtSimZero + std::llround(t_s * common::kMicrosPerSecond), kUtimeAtSimZero);
      }
      if (pacer) pacer->WaitFor(t_s);
    };
  }
  run::RunResult result = run::RunScenario(scenario, run_options);
  if (run_options.progress) {
    DrawProgress(last);
    std::fputc('\n', stderr);
  }
  // The web adapter's share of the run's CPU (bench/web/command_center_bench.mjs).
  if (feed) std::cout << feed->CpuFigures().dump() << std::endl;
  return result;
}

}  // namespace

int RunRun(const std::vector<std::string>& args) {
  Flags f;
  po::options_description options("run options");
  auto add = options.add_options();
  add("report", po::value(&f.report), "write the report (JSON) to this file");
  add("junit", po::value(&f.junit), "write the expectations as a JUnit XML file");
  add("svg", po::value(&f.svg), "write a map of the run (SVG)");
  add("log", po::value(&f.log)->value_name("FILE"),
      "write an LCM log (for lcm-logplayer) of what the server publishes; utime = simulated us");
  add("lcm", po::value(&f.lcm_url)->value_name("URL"),
      (std::string("publish the same on LCM as the run goes (memq://, ") + server::kDefaultLcmUrl +
       ", ...)")
          .c_str());
  AddWebOptions(options, f.web);
  add("keys", po::value(&f.keys)->value_name("DIR"),
      "fleet key store: the page's commands (--http) must be signed with a key in "
      "DIR/operators/NAME.key (without it every command is refused)");
  add("pace", po::value<double>()->notifier([&f](double v) { f.pace = v; })->value_name("K"),
      "run simulated time at K times the wall clock (e.g. 1 to watch a run live on --http)");
  add("scenario", po::value(&f.scenario)->required(), "the scenario file (YAML)");
  po::positional_options_description positional;
  positional.add("scenario", 1);
  po::variables_map values;
  if (!ParseCommandLine(kName,
                        "SCENARIO.yaml [--report out.json] [--junit out.xml] [--svg map.svg] "
                        "[--log out.lcmlog] [--lcm URL] [--http HOST:PORT [--pace K] [--keys DIR]]",
                        options, positional, args, values)) {
    return kExitOk;
  }
  CheckFlags(f, values);
  const std::vector<OutputFlag> outputs{
      {"report", f.report}, {"junit", f.junit}, {"svg", f.svg}, {"log", f.log}};
  CheckOutputFlags(kName, outputs, {f.scenario});

  run::Scenario scenario;
  run::RunResult result;
  common::OutputFiles output;  // destroyed last: removes the temporaries of a failed run
  std::optional<RunLcmOutput> lcm;
  try {
    scenario = run::LoadScenario(f.scenario);
    // The scenario's GeoJSON files are inputs too.
    CheckOutputFlags(kName, outputs,
                     {f.scenario, scenario.area_geojson.value_or(fs::path()),
                      scenario.no_fly_geojson.value_or(fs::path())});
    if (!f.log.empty() || !f.lcm_url.empty()) {
      lcm.emplace(f.log, f.log.empty() ? fs::path() : output.Reserve(f.log), f.lcm_url);
    }
    std::map<std::string, common::SecretKey> operators;
    if (!f.keys.empty()) {
      try {
        operators = server::LoadOperatorKeys(f.keys);
      } catch (const std::runtime_error& e) {
        throw UsageError(std::string("fireswarm run: --keys: ") + e.what());
      }
    } else if (!f.web.http.empty()) {
      std::cerr << "fireswarm run: WARNING: no --keys: every command from the page is refused"
                << std::endl;
    }
    const std::unique_ptr<server::WebServer> web = StartWebServer(kName, f.web, false);
    result = Fly(scenario, lcm ? &*lcm : nullptr, web.get(), f.pace, std::move(operators));
  } catch (const run::ScenarioError& e) {
    throw UsageError(std::string("fireswarm run: ") + e.what());
  }
  if (lcm) lcm->Finish();
  // All outputs or none: each is staged beside its target, then all are renamed.
  if (!f.report.empty()) output.Stage(f.report, run::ToJson(result.report).dump(2) + "\n");
  if (!f.junit.empty()) output.Stage(f.junit, run::JunitXml(result.report));
  if (!f.svg.empty()) output.Stage(f.svg, run::SvgMap(result.report, scenario));
  output.Commit();
  PrintSummary(result);
  if (lcm) lcm->PrintSummary();
  return result.report.AllExpectationsHold() ? kExitOk : kExitCheckFailed;
}

}  // namespace fireswarm::app
