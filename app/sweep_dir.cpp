#include "sweep_dir.hpp"

#include <cmath>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <system_error>

#include "cli.hpp"
#include "fireswarm/common/atomic_file.hpp"
#include "fireswarm/common/output_files.hpp"

namespace fireswarm::app {
namespace {

namespace fs = std::filesystem;

std::string ReadFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::optional<nlohmann::json> ReadJson(const fs::path& path) {
  if (!fs::is_regular_file(path)) return std::nullopt;
  try {
    return nlohmann::json::parse(ReadFile(path));
  } catch (const nlohmann::json::exception&) {
    return std::nullopt;
  }
}

std::string LastLine(const fs::path& path) {
  std::ifstream in(path);
  std::string line;
  std::string last;
  while (std::getline(in, line)) {
    if (!line.empty()) last = line;
  }
  return last;
}

std::string SignalText(int signal) {
  const char* abbrev = sigabbrev_np(signal);
  return "killed by signal " + std::to_string(signal) +
         (abbrev != nullptr ? " (SIG" + std::string(abbrev) + ")" : std::string());
}

// One line per combination: the headline figures of summary.html's table.
void PrintGroup(const run::GroupSummary& group, double confirm_within_s) {
  const auto percent = [](const std::optional<double>& fraction) {
    return fraction ? FlagText(std::round(1000.0 * *fraction) / 10.0) + " %" : std::string("-");
  };
  const auto seconds = [](const std::optional<double>& value) {
    return value ? FlagText(std::round(*value)) + " s" : std::string("-");
  };
  std::cout << "  " << group.label << ": " << group.done << "/" << group.runs
            << " done, every fire confirmed within " << FlagText(confirm_within_s) << " s in "
            << percent(group.all_confirmed.rate) << " [" << percent(group.all_confirmed.low) << ", "
            << percent(group.all_confirmed.high) << "], time to confirm p50 "
            << seconds(run::Percentile(group.time_to_confirm_s, 0.5)) << ", p90 "
            << seconds(run::Percentile(group.time_to_confirm_s, 0.9)) << "\n";
}

}  // namespace

fs::path RunDir(const fs::path& out, std::size_t id) {
  return out / "runs" / run::RunName(id);
}

std::optional<run::RunRecord> ReadRecord(const fs::path& out, std::size_t id) {
  const std::optional<nlohmann::json> json = ReadJson(RunDir(out, id) / "record.json");
  if (!json) return std::nullopt;
  try {
    run::RunRecord record = run::RecordFromJson(*json);
    if (record.id != id) return std::nullopt;
    return record;
  } catch (const std::runtime_error&) {
    return std::nullopt;
  }
}

run::RunRecord MakeRecord(const run::SweepRun& sweep_run, const ChildEnd& end, const fs::path& dir,
                          std::optional<double> timeout_s) {
  run::RunRecord record;
  record.id = sweep_run.id;
  record.seed = sweep_run.seed;
  record.exit_code = end.exit_code;
  record.signal = end.signal;
  record.wall_s = end.wall_s;
  if (end.timed_out) {
    record.status = run::RunStatus::kTimedOut;
    record.detail = "over --timeout " + FlagText(timeout_s.value_or(0.0)) + " s, killed";
  } else if (end.signal) {
    record.status = run::RunStatus::kCrashed;
    record.detail = SignalText(*end.signal);
  } else if ((end.exit_code == kExitOk || end.exit_code == kExitCheckFailed) &&
             fs::is_regular_file(dir / "report.json")) {
    record.status = run::RunStatus::kDone;
  } else {
    record.status = run::RunStatus::kError;
    record.detail = "exit code " + std::to_string(end.exit_code.value_or(-1)) + ": " +
                    LastLine(dir / "output.txt");
  }
  return record;
}

// DIR/plan.json: written once; a sweep started on a DIR that holds another
// sweep's plan is refused, so no run of one is mistaken for a run of the other.
void WritePlan(const fs::path& out, const run::SweepPlan& plan) {
  std::error_code error;
  fs::create_directories(out / "runs", error);
  if (error) throw UsageError("fireswarm sweep: --out " + out.string() + ": " + error.message());
  const std::string text = run::ToJson(plan).dump(1) + "\n";
  const fs::path path = out / "plan.json";
  if (fs::exists(path)) {
    if (ReadFile(path) != text) {
      throw UsageError("fireswarm sweep: --out " + out.string() +
                       " holds the runs of another sweep (its plan.json differs from this "
                       "sweep's): give another --out, or remove it");
    }
    return;
  }
  common::WriteFileAtomically(path, text);
}

int Collect(const fs::path& out) {
  const std::optional<nlohmann::json> plan_json = ReadJson(out / "plan.json");
  if (!plan_json) {
    throw UsageError("fireswarm sweep: " + (out / "plan.json").string() +
                     ": missing or unreadable: not a sweep's --out directory");
  }
  run::SweepPlan plan;
  try {
    plan = run::PlanFromJson(*plan_json);
  } catch (const std::runtime_error& e) {
    throw UsageError("fireswarm sweep: " + (out / "plan.json").string() + ": " + e.what());
  }
  std::vector<run::RunFiles> files(plan.runs.size());
  for (const run::SweepRun& r : plan.runs) {
    files[r.id].record = ReadRecord(out, r.id);
    if (files[r.id].record && files[r.id].record->status == run::RunStatus::kDone) {
      files[r.id].report = ReadJson(RunDir(out, r.id) / "report.json");
      if (!files[r.id].report) files[r.id].record.reset();  // done again on resume
    }
  }
  const run::SweepSummary summary = run::Summarize(plan, files);
  common::OutputFiles output;
  output.Stage(out / "summary.json", run::ToJson(summary).dump(1) + "\n");
  output.Stage(out / "summary.csv", run::SummaryCsv(summary));
  output.Stage(out / "summary.html", run::SummaryHtml(summary));
  output.Commit();
  std::cout << "fireswarm sweep: " << summary.runs << " runs: " << summary.done << " done, "
            << summary.crashed << " crashed, " << summary.timed_out << " timed out, "
            << summary.errors << " errors, " << summary.missing.size() << " missing\n"
            << "  summary: " << (out / "summary.json").string() << ", summary.csv, summary.html\n";
  for (const run::GroupSummary& group : summary.groups) PrintGroup(group, summary.confirm_within_s);
  if (!summary.missing.empty()) {
    std::cerr << "fireswarm sweep: runs without a result:";
    for (const std::size_t id : summary.missing) std::cerr << " " << run::RunName(id);
    std::cerr << "\n";
  }
  const bool complete = summary.missing.empty() && summary.done == summary.runs;
  return complete ? kExitOk : kExitCheckFailed;
}

}  // namespace fireswarm::app
