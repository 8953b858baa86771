// The sweep file of `fireswarm sweep` (YAML): a base scenario, the seeds to fly it
// with and the scenario keys to vary, expanded into a deterministic list of runs
// (docs/sweep.md). Pure: reading the files is LoadSweep's only I/O; running the
// runs is the app's job (app/sweep_command.cpp).
#pragma once

#include <cstdint>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>
#include <vector>

namespace fireswarm::run {

/// At most this many runs in one sweep (seeds x combinations of the axes).
inline constexpr std::size_t kMaxSweepRuns = 100'000;

/// One varied scenario key and its values, in the file's order.
struct SweepAxis {
  std::string key;                  ///< a dotted scenario key path, e.g. "fleet.count"
  std::vector<std::string> values;  ///< each value as YAML flow text, e.g. "5", "0.1"
};

/// A sweep file, checked: every combination of the axes makes a valid scenario.
struct SweepSpec {
  std::string source;  ///< the file name errors carry
  std::string name;    ///< defaults to the file's stem
  std::filesystem::path
      scenario_path;                 ///< the base scenario, resolved against the sweep's directory
  std::string scenario_text;         ///< the base scenario's YAML
  std::vector<std::uint64_t> seeds;  ///< each combination runs once per seed, in this order
  std::vector<SweepAxis> axes;
  /// "Every fire confirmed within T of its ignition", s: the summary's success
  /// rate. Default: the base scenario's expect.all_fires_confirmed_within_s, else
  /// its duration_s.
  double confirm_within_s = 0.0;
  /// Times the summary gives the coverage at, s, ascending. Default: a quarter,
  /// half, three quarters and all of the longest duration_s.
  std::vector<double> coverage_at_s;
  double duration_s = 0.0;  ///< the longest duration_s of any combination
};

/// One run of a sweep.
struct SweepRun {
  std::size_t id = 0;           ///< 0-based, in expansion order
  std::size_t combination = 0;  ///< index of its combination of axis values
  std::uint64_t seed = 0;
  std::vector<std::string> values;  ///< one per axis, as SweepAxis::values
};

/// What the summary needs of a sweep, written to DIR/plan.json before any run
/// starts, so that `--collect DIR` and a resumed sweep read the same plan.
struct SweepPlan {
  std::string name;
  std::vector<std::string> axes;  ///< the axis keys
  double confirm_within_s = 0.0;
  std::vector<double> coverage_at_s;
  double duration_s = 0.0;
  std::vector<SweepRun> runs;  ///< ordered by id
};

/// Parses sweep YAML `text`; the base scenario's path is resolved against
/// `base_dir`. Throws ScenarioError "<file>:<line>:<column>: <key>: <problem>" on
/// malformed YAML, an unknown or missing key, a bad seed range, an axis that is
/// not a list, an axis key that is not a scenario key or a value the scenario
/// refuses (naming the axis's or the value's line and the scenario's complaint),
/// or more than kMaxSweepRuns runs; and when the base scenario cannot be read.
SweepSpec ParseSweep(std::string_view text, const std::string& source_name,
                     const std::filesystem::path& base_dir);

/// Reads and parses the sweep file at `path`. Throws ScenarioError as ParseSweep.
SweepSpec LoadSweep(const std::filesystem::path& path);

/// Every run: combinations in the order of the axes (the first axis varies
/// slowest, each axis's values in the file's order), each with every seed.
SweepPlan MakePlan(const SweepSpec& spec);

/// The scenario YAML of `run`: the base scenario with `seed` and each axis key
/// set, relative GeoJSON paths made absolute (the file is written elsewhere).
std::string RunScenarioYaml(const SweepSpec& spec, const SweepRun& run);

/// "00042": the run's directory name under DIR/runs/.
std::string RunName(std::size_t id);

/// "fleet.count=5 radio.loss=0.1" ("all" for a sweep without axes).
std::string CombinationLabel(const std::vector<std::string>& axes,
                             const std::vector<std::string>& values);

/// The plan as JSON (keys in a fixed order) and back. PlanFromJson throws
/// std::runtime_error on a plan it cannot read.
nlohmann::ordered_json ToJson(const SweepPlan& plan);
SweepPlan PlanFromJson(const nlohmann::json& json);

}  // namespace fireswarm::run
