// The statistics of a sweep: per combination of axis values, over its seeds,
// from each run's record and report. Pure and deterministic: nothing depends on
// wall time, job count or the order runs finished in, so the same sweep gives
// the same bytes from one job, many jobs or a Slurm array (docs/sweep.md lists
// every key).
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "fireswarm/run/sweep.hpp"

namespace fireswarm::run {

/// How one run of a sweep ended.
enum class RunStatus : std::uint8_t {
  kDone,      ///< "done": `fireswarm run` exited 0 or 1 with a report
  kCrashed,   ///< "crashed": killed by a signal
  kTimedOut,  ///< "timed_out": over the sweep's --timeout, killed
  kError,     ///< "error": any other exit (bad input, no report)
};
std::string_view ToString(RunStatus status);

/// DIR/runs/<id>/record.json: written once the run ended; its presence is what
/// makes the run done for a resumed sweep.
struct RunRecord {
  std::size_t id = 0;
  std::uint64_t seed = 0;
  RunStatus status = RunStatus::kError;
  std::optional<int> exit_code;  ///< when it exited
  std::optional<int> signal;     ///< when a signal ended it
  double wall_s = 0.0;           ///< never in the summary
  std::string detail;            ///< why it crashed or failed, for people
};

nlohmann::ordered_json ToJson(const RunRecord& record);
/// Throws std::runtime_error on a record it cannot read.
RunRecord RecordFromJson(const nlohmann::json& json);

/// What the summary reads of one run: both absent for a run not yet recorded.
struct RunFiles {
  std::optional<RunRecord> record;
  std::optional<nlohmann::json> report;  ///< DIR/runs/<id>/report.json, when done
};

/// A share with its Wilson score 95 % interval; rate and bounds absent when
/// there were no trials.
struct Rate {
  std::size_t successes = 0;
  std::size_t trials = 0;
  std::optional<double> rate;
  std::optional<double> low;
  std::optional<double> high;
};
Rate WilsonRate(std::size_t successes, std::size_t trials);

/// The `p` quantile (0..1) of ascending `sorted` by linear interpolation between
/// closest ranks (Hyndman-Fan type 7, numpy's default); absent when empty.
std::optional<double> Percentile(const std::vector<double>& sorted, double p);

/// One combination of axis values over its seeds.
struct GroupSummary {
  std::string label;                ///< CombinationLabel
  std::vector<std::string> values;  ///< one per axis
  std::size_t runs = 0;
  std::size_t done = 0;
  std::size_t crashed = 0;
  std::size_t timed_out = 0;
  std::size_t errors = 0;
  std::size_t missing = 0;  ///< not recorded (yet)
  Rate expectations_hold;   ///< done runs whose every `expect` held
  Rate all_confirmed;       ///< done runs with every fire confirmed within confirm_within_s
  Rate fires_confirmed;     ///< fires of done runs confirmed at all
  std::vector<double> time_to_confirm_s;  ///< ignition to confirmation, ascending
  std::vector<double> fused_error_m;      ///< confirmed fires, ascending
  /// Per SweepPlan::coverage_at_s, each done run's coverage then, ascending.
  std::vector<std::vector<double>> coverage_at;
  std::vector<double> coverage_curve;  ///< mean coverage at SweepSummary::curve_t_s
  std::size_t collisions = 0;
  Rate runs_with_collision;
  double flight_hours = 0.0;             ///< summed airborne time of every vehicle
  std::vector<double> min_separation_m;  ///< per done run where measured, ascending
  std::size_t false_tracks = 0;
  std::vector<double> radio_busy_fraction;   ///< per done run, ascending
  std::vector<double> report_latency_p50_s;  ///< per done run where measured, ascending
  std::uint64_t retries = 0;
  std::uint64_t reports_lost = 0;
};

struct SweepSummary {
  std::string name;
  std::vector<std::string> axes;
  double confirm_within_s = 0.0;
  std::vector<double> coverage_at_s;
  std::vector<double> curve_t_s;  ///< the coverage curve's times, 0..duration_s
  std::size_t runs = 0;
  std::size_t done = 0;
  std::size_t crashed = 0;
  std::size_t timed_out = 0;
  std::size_t errors = 0;
  std::vector<std::size_t> missing;  ///< run ids not recorded
  std::vector<GroupSummary> groups;  ///< by combination index
};

/// The summary of `plan` from `files` (indexed by run id, as many as plan.runs).
/// Throws std::runtime_error naming the run whose report lacks a key it reads.
SweepSummary Summarize(const SweepPlan& plan, const std::vector<RunFiles>& files);

/// summary.json: keys in a fixed order, numbers as the shortest text that
/// reads back to the same double.
nlohmann::ordered_json ToJson(const SweepSummary& summary);
/// summary.csv: a header, then one row per combination.
std::string SummaryCsv(const SweepSummary& summary);
/// summary.html: the table and three plots (SVG inline): the CDF of the time
/// from ignition to confirmation, coverage against time and the CDF of the
/// fused error, one line per combination. Each line is a
/// `<polyline class="series" data-label="...">` whose points are in data units
/// (seconds or metres, fraction) under a transform, so the plot holds the data.
std::string SummaryHtml(const SweepSummary& summary);

}  // namespace fireswarm::run
