// `fireswarm sweep SWEEP.yaml --out DIR`: many seeded runs of a scenario and its
// variants (run/sweep.hpp), each a child `fireswarm run` writing its report into
// DIR/runs/<id>/, then the summary (run/sweep_summary.hpp). A run's record is
// committed atomically once it ended, so an interrupted sweep started again
// redoes only the runs without one. `--emit slurm` writes a Slurm job-array
// script instead of running; `--chunk K --chunks N` runs one array task's share;
// `--collect DIR` writes the summary from what the runs left (docs/sweep.md).
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "child_pool.hpp"
#include "cli.hpp"
#include "commands.hpp"
#include "fireswarm/common/atomic_file.hpp"
#include "fireswarm/run/scenario.hpp"
#include "fireswarm/run/sweep.hpp"
#include "fireswarm/run/sweep_summary.hpp"
#include "sweep_dir.hpp"

namespace fireswarm::app {
namespace {

namespace po = boost::program_options;
namespace fs = std::filesystem;

constexpr const char* kName = "sweep";
constexpr int kMaxJobs = 1024;
/// Runs per Slurm array task when --chunks is not given.
constexpr std::size_t kDefaultRunsPerChunk = 10;
constexpr int kBarWidth = 30;
constexpr std::chrono::milliseconds kRedrawPeriod{200};

struct Flags {
  std::string sweep;
  std::string out;
  std::optional<int> jobs;
  std::optional<double> timeout_s;
  std::string emit;
  std::optional<int> chunk;
  std::optional<int> chunks;
  std::string collect;
};

// What a terminal shows while the runs go; one line per run start and end otherwise.
class Progress {
 public:
  Progress(std::size_t total, std::size_t recorded)
      : total_(total),
        finished_(recorded),
        tty_(isatty(STDERR_FILENO) != 0),
        start_(std::chrono::steady_clock::now()) {}

  void Started(const run::SweepRun& r, pid_t pid) {
    ++running_;
    if (!tty_)
      std::cout << "run " << run::RunName(r.id) << " started (pid " << pid << ")\n" << std::flush;
  }
  void Ended(const run::RunRecord& record) {
    --running_;
    ++finished_;
    ++done_now_;
    if (record.status != run::RunStatus::kDone) ++failed_;
    if (!tty_) {
      std::cout << "run " << run::RunName(record.id) << " " << run::ToString(record.status)
                << (record.detail.empty() ? "" : ": " + record.detail) << " [" << finished_ << "/"
                << total_ << "]\n"
                << std::flush;
    }
    Draw(true);
  }
  void Draw(bool force) {
    if (!tty_) return;
    const auto now = std::chrono::steady_clock::now();
    if (!force && now - drawn_ < kRedrawPeriod) return;
    drawn_ = now;
    const double fraction =
        total_ > 0 ? static_cast<double>(finished_) / static_cast<double>(total_) : 1.0;
    const int filled = static_cast<int>(fraction * kBarWidth);
    const double elapsed_s = std::chrono::duration<double>(now - start_).count();
    const std::size_t left = total_ - finished_;
    const double eta_s =
        done_now_ > 0 ? elapsed_s / static_cast<double>(done_now_) * static_cast<double>(left)
                      : 0.0;
    std::fprintf(stderr,
                 "\r[%s%s] %zu / %zu runs, %zu running, %zu not done, %.0f s, ~%.0f s left ",
                 std::string(static_cast<std::size_t>(filled), '#').c_str(),
                 std::string(static_cast<std::size_t>(kBarWidth - filled), '.').c_str(), finished_,
                 total_, running_, failed_, elapsed_s, eta_s);
    std::fflush(stderr);
  }
  void Finish() const {
    if (tty_) std::fputc('\n', stderr);
  }

 private:
  std::size_t total_;
  std::size_t finished_;
  std::size_t running_ = 0;
  std::size_t failed_ = 0;
  std::size_t done_now_ = 0;
  bool tty_;
  std::chrono::steady_clock::time_point start_;
  std::chrono::steady_clock::time_point drawn_{};
};

std::string ShellQuote(const std::string& text) {
  std::string quoted = "'";
  for (const char c : text) {
    if (c == '\'') {
      quoted += "'\\''";
    } else {
      quoted += c;
    }
  }
  return quoted + "'";
}

fs::path SelfExe() {
  std::error_code error;
  const fs::path self = fs::read_symlink("/proc/self/exe", error);
  if (error) throw std::runtime_error("cannot read /proc/self/exe: " + error.message());
  return self;
}

int EmitSlurm(const Flags& f, const run::SweepPlan& plan) {
  const std::size_t runs = plan.runs.size();
  const std::size_t chunks = f.chunks ? static_cast<std::size_t>(*f.chunks)
                                      : (runs + kDefaultRunsPerChunk - 1) / kDefaultRunsPerChunk;
  if (chunks > runs) {
    ThrowBadFlag(kName, "chunks", "at most the sweep's " + std::to_string(runs) + " runs",
                 std::to_string(chunks));
  }
  const int jobs = f.jobs.value_or(1);
  const fs::path out = fs::absolute(f.out).lexically_normal();
  fs::create_directories(out / "slurm");
  std::string command = ShellQuote(SelfExe().string()) + " sweep " +
                        ShellQuote(fs::absolute(f.sweep).lexically_normal().string()) + " --out " +
                        ShellQuote(out.string()) + " --chunk \"$SLURM_ARRAY_TASK_ID\" --chunks " +
                        std::to_string(chunks) + " --jobs \"${SLURM_CPUS_PER_TASK:-" +
                        std::to_string(jobs) + "}\"";
  if (f.timeout_s) command += " --timeout " + FlagText(*f.timeout_s);
  const std::string script =
      "#!/bin/bash\n"
      "# fireswarm sweep '" +
      plan.name + "': " + std::to_string(runs) + " runs in " + std::to_string(chunks) +
      " array tasks. The binary, the sweep and scenario files and this directory must be\n"
      "# at the same paths on every node (a shared file system). Submit, then collect:\n"
      "#   sbatch " +
      ShellQuote((out / "sweep.sbatch").string()) +
      "\n"
      "#   fireswarm sweep --collect " +
      ShellQuote(out.string()) +
      "\n"
      "# Options given to sbatch (--partition, --time, --account, ...) override these.\n"
      "#SBATCH --job-name=fireswarm-sweep\n"
      "#SBATCH --array=0-" +
      std::to_string(chunks - 1) +
      "\n"
      "#SBATCH --ntasks=1\n"
      "#SBATCH --cpus-per-task=" +
      std::to_string(jobs) +
      "\n"
      "#SBATCH --output=" +
      (out / "slurm" / "%A_%a.out").string() +
      "\n"
      "set -eu\n"
      "exec " +
      command + "\n";
  common::WriteFileAtomically(out / "sweep.sbatch", script, 0755);
  std::cout << "fireswarm sweep: " << runs << " runs in " << chunks
            << " Slurm array tasks: " << (out / "sweep.sbatch").string() << "\n  submit:  sbatch "
            << (out / "sweep.sbatch").string() << "\n  then:    fireswarm sweep --collect "
            << out.string() << "\n";
  return kExitOk;
}

// Runs the plan's runs of this chunk that have no record; false when interrupted.
bool RunPending(const Flags& f, const run::SweepSpec& spec, const run::SweepPlan& plan,
                bool& all_done) {
  const fs::path out(f.out);
  const std::size_t chunks = static_cast<std::size_t>(f.chunks.value_or(1));
  const std::size_t chunk = static_cast<std::size_t>(f.chunk.value_or(0));
  // Chunk k holds the runs [k * R / N, (k + 1) * R / N): contiguous, sizes within one.
  const std::size_t first = chunk * plan.runs.size() / chunks;
  const std::size_t last = (chunk + 1) * plan.runs.size() / chunks;
  std::vector<const run::SweepRun*> todo;
  std::size_t recorded = 0;
  for (std::size_t id = first; id < last; ++id) {
    const std::optional<run::RunRecord> record = ReadRecord(out, id);
    // A done run's report is part of its result: without it the run is done again.
    if (record && (record->status != run::RunStatus::kDone ||
                   fs::is_regular_file(RunDir(out, id) / "report.json"))) {
      ++recorded;
      if (record->status != run::RunStatus::kDone) all_done = false;
      continue;
    }
    todo.push_back(&plan.runs[id]);
  }
  const int parallel =
      f.jobs.value_or(static_cast<int>(std::max(1U, std::thread::hardware_concurrency())));
  std::cout << "fireswarm sweep: " << spec.name << ": " << (last - first) << " runs"
            << (f.chunk ? " in chunk " + std::to_string(chunk) + " of " + std::to_string(chunks)
                        : std::string())
            << ", " << recorded << " already recorded, " << todo.size() << " to run on " << parallel
            << " jobs\n"
            << std::flush;
  const std::string exe = SelfExe().string();
  std::vector<ChildJob> jobs;
  for (const run::SweepRun* r : todo) {
    const fs::path dir = RunDir(out, r->id);
    fs::create_directories(dir);
    fs::remove(dir / "report.json");  // a killed attempt's, if any
    common::WriteFileAtomically(dir / "scenario.yaml", run::RunScenarioYaml(spec, *r));
    jobs.push_back(
        {{exe, "run", (dir / "scenario.yaml").string(), "--report", (dir / "report.json").string()},
         dir / "output.txt"});
  }
  Progress progress(last - first, recorded);
  ChildPoolCallbacks callbacks;
  callbacks.started = [&](std::size_t job, pid_t pid) { progress.Started(*todo[job], pid); };
  callbacks.ended = [&](std::size_t job, const ChildEnd& end) {
    const run::SweepRun& r = *todo[job];
    const fs::path dir = RunDir(out, r.id);
    const run::RunRecord record = MakeRecord(r, end, dir, f.timeout_s);
    common::WriteFileAtomically(dir / "record.json", run::ToJson(record).dump(1) + "\n");
    if (record.status != run::RunStatus::kDone) all_done = false;
    progress.Ended(record);
  };
  callbacks.tick = [&] { progress.Draw(false); };
  const bool finished = RunChildren(jobs, parallel, f.timeout_s, callbacks);
  progress.Finish();
  return finished;
}

void CheckFlags(const Flags& f, const po::variables_map& values) {
  if (f.jobs) CheckFlagRange(kName, "jobs", *f.jobs, {1, kMaxJobs});
  if (f.timeout_s)
    CheckFlagRange(kName, "timeout", *f.timeout_s, {0.0, kMaxCommandDurationS, true});
  if (f.chunks)
    CheckFlagRange(kName, "chunks", *f.chunks, {1, static_cast<double>(run::kMaxSweepRuns)});
  if (f.chunk && !f.chunks) throw UsageError("fireswarm sweep: --chunk needs --chunks");
  if (f.chunk) CheckFlagRange(kName, "chunk", *f.chunk, {0, static_cast<double>(*f.chunks - 1)});
  if (values.count("emit") != 0 && f.emit != "slurm") {
    ThrowBadFlag(kName, "emit", "slurm", f.emit);
  }
  if (!f.emit.empty() && f.chunk)
    throw UsageError("fireswarm sweep: --emit and --chunk exclude each other");
  if (!f.collect.empty()) {
    if (!f.sweep.empty() || !f.out.empty() || !f.emit.empty() || f.chunk) {
      throw UsageError(
          "fireswarm sweep: --collect DIR takes no sweep file, --out, --emit or --chunk");
    }
    return;
  }
  if (f.sweep.empty()) throw UsageError("fireswarm sweep: the sweep file is missing (SWEEP.yaml)");
  if (f.out.empty()) throw UsageError("fireswarm sweep: --out DIR is missing");
  if (f.chunks && f.emit.empty() && !f.chunk) {
    throw UsageError("fireswarm sweep: --chunks needs --chunk K (or --emit slurm)");
  }
}

}  // namespace

int RunSweep(const std::vector<std::string>& args) {
  Flags f;
  po::options_description options("sweep options");
  auto add = options.add_options();
  add("out", po::value(&f.out)->value_name("DIR"),
      "the sweep's directory: plan, runs/<id>/ (scenario, report, record, output), summary");
  add("jobs", po::value<int>()->notifier([&f](int v) { f.jobs = v; })->value_name("N"),
      "runs at once (default: every core; with --emit slurm: CPUs per array task, default 1)");
  add("timeout",
      po::value<double>()->notifier([&f](double v) { f.timeout_s = v; })->value_name("S"),
      "kill a run after S wall seconds and record it as timed out");
  add("emit", po::value(&f.emit)->value_name("slurm"),
      "write DIR/sweep.sbatch, a Slurm job-array script, instead of running");
  add("chunks", po::value<int>()->notifier([&f](int v) { f.chunks = v; })->value_name("N"),
      "split the runs into N chunks (one Slurm array task each; default: 10 runs a chunk)");
  add("chunk", po::value<int>()->notifier([&f](int v) { f.chunk = v; })->value_name("K"),
      "run only chunk K (0-based) of --chunks N; no summary (--collect writes it)");
  add("collect", po::value(&f.collect)->value_name("DIR"),
      "write DIR's summary from the runs recorded there, naming the missing ones");
  add("sweep", po::value(&f.sweep), "the sweep file (YAML)");
  po::positional_options_description positional;
  positional.add("sweep", 1);
  po::variables_map values;
  if (!ParseCommandLine(kName,
                        "SWEEP.yaml --out DIR [--jobs N] [--timeout S] [--emit slurm [--chunks N]] "
                        "[--chunk K --chunks N]  |  --collect DIR",
                        options, positional, args, values)) {
    return kExitOk;
  }
  CheckFlags(f, values);
  if (!f.collect.empty()) return Collect(f.collect);

  run::SweepSpec spec;
  try {
    spec = run::LoadSweep(f.sweep);
  } catch (const run::ScenarioError& e) {
    throw UsageError(std::string("fireswarm sweep: ") + e.what());
  }
  const run::SweepPlan plan = run::MakePlan(spec);
  WritePlan(f.out, plan);
  if (!f.emit.empty()) return EmitSlurm(f, plan);
  bool all_done = true;
  if (!RunPending(f, spec, plan, all_done)) {
    std::cerr << "fireswarm sweep: interrupted; the runs recorded so far are kept: run the same "
                 "command again to resume\n";
    return kExitCheckFailed;
  }
  if (f.chunk) return all_done ? kExitOk : kExitCheckFailed;
  return Collect(f.out);
}

}  // namespace fireswarm::app
