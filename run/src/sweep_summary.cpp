// The sweep's statistics from its runs' records and reports. Every sum runs in
// run-id order, so the result never depends on the order runs finished in.
#include "fireswarm/run/sweep_summary.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace fireswarm::run {
namespace {

/// z for a two-sided 95 % interval.
constexpr double kZ95 = 1.959963984540054;
/// Points of the coverage-against-time curve, 0 .. duration_s.
constexpr std::size_t kCurvePoints = 61;
constexpr double kSecondsPerFlightHour = 3'600.0;

constexpr std::array<std::string_view, 4> kStatusNames{"done", "crashed", "timed_out", "error"};

// The coverage a run had reached at `t_s`: its latest sample at or before it
// (a run that stopped earlier keeps its final coverage).
double CoverageAt(const nlohmann::json& series, double t_s) {
  double fraction = 0.0;
  for (const nlohmann::json& sample : series) {
    if (sample.at(0).is_null() || sample.at(0).get<double>() > t_s) break;
    if (!sample.at(1).is_null()) fraction = sample.at(1).get<double>();
  }
  return fraction;
}

std::optional<double> OptionalNumber(const nlohmann::json& value) {
  if (value.is_null()) return std::nullopt;
  return value.get<double>();
}

void SortAll(GroupSummary& group) {
  for (std::vector<double>* values :
       {&group.time_to_confirm_s, &group.fused_error_m, &group.min_separation_m,
        &group.radio_busy_fraction, &group.report_latency_p50_s}) {
    std::sort(values->begin(), values->end());
  }
  for (std::vector<double>& values : group.coverage_at) std::sort(values.begin(), values.end());
}

// Counters the rates are made of, kept while the group's runs are read.
struct Counts {
  std::size_t expectations_hold = 0;
  std::size_t all_confirmed = 0;
  std::size_t fires = 0;
  std::size_t fires_confirmed = 0;
  std::size_t runs_with_collision = 0;
  std::vector<double> curve_sum;
};

void AddReport(const SweepPlan& plan, const SweepSummary& summary, const RunRecord& record,
               const nlohmann::json& report, GroupSummary& group, Counts& counts) {
  counts.expectations_hold += record.exit_code == 0 ? 1U : 0U;
  bool all_within = true;
  for (const nlohmann::json& fire : report.at("fires")) {
    ++counts.fires;
    const std::optional<double> confirmed_s = OptionalNumber(fire.at("confirmed_s"));
    if (!confirmed_s) {
      all_within = false;
      continue;
    }
    ++counts.fires_confirmed;
    const double delay_s = *confirmed_s - fire.at("start_s").get<double>();
    group.time_to_confirm_s.push_back(delay_s);
    if (delay_s > plan.confirm_within_s) all_within = false;
    if (const std::optional<double> error_m = OptionalNumber(fire.at("error_m"))) {
      group.fused_error_m.push_back(*error_m);
    }
  }
  counts.all_confirmed += all_within ? 1U : 0U;
  const nlohmann::json& series = report.at("coverage_over_time");
  for (std::size_t k = 0; k < plan.coverage_at_s.size(); ++k) {
    group.coverage_at[k].push_back(CoverageAt(series, plan.coverage_at_s[k]));
  }
  for (std::size_t k = 0; k < summary.curve_t_s.size(); ++k) {
    counts.curve_sum[k] += CoverageAt(series, summary.curve_t_s[k]);
  }
  const std::size_t collisions = report.at("collisions").size();
  group.collisions += collisions;
  counts.runs_with_collision += collisions > 0 ? 1U : 0U;
  for (const auto& [id, vehicle] : report.at("vehicles").items()) {
    group.flight_hours += vehicle.at("airborne_s").get<double>() / kSecondsPerFlightHour;
  }
  if (const std::optional<double> m = OptionalNumber(report.at("min_separation_m"))) {
    group.min_separation_m.push_back(*m);
  }
  group.false_tracks += report.at("false_tracks").size();
  const nlohmann::json& radio = report.at("radio");
  group.radio_busy_fraction.push_back(radio.at("busy_fraction").get<double>());
  if (const std::optional<double> p50 = OptionalNumber(radio.at("report_latency_s").at("p50"))) {
    group.report_latency_p50_s.push_back(*p50);
  }
  group.retries += radio.at("retries").get<std::uint64_t>();
  group.reports_lost += radio.at("reports_lost").get<std::uint64_t>();
}

}  // namespace

std::string_view ToString(RunStatus status) {
  return kStatusNames.at(static_cast<std::size_t>(status));
}

nlohmann::ordered_json ToJson(const RunRecord& record) {
  nlohmann::ordered_json j;
  j["id"] = record.id;
  j["seed"] = record.seed;
  j["status"] = ToString(record.status);
  j["exit_code"] = record.exit_code ? nlohmann::json(*record.exit_code) : nlohmann::json(nullptr);
  j["signal"] = record.signal ? nlohmann::json(*record.signal) : nlohmann::json(nullptr);
  j["wall_s"] = record.wall_s;
  j["detail"] = record.detail;
  return j;
}

RunRecord RecordFromJson(const nlohmann::json& json) {
  try {
    RunRecord record;
    record.id = json.at("id").get<std::size_t>();
    record.seed = json.at("seed").get<std::uint64_t>();
    const std::string status = json.at("status").get<std::string>();
    const auto found = std::find(kStatusNames.begin(), kStatusNames.end(), status);
    if (found == kStatusNames.end()) throw std::runtime_error("unknown status '" + status + "'");
    record.status = static_cast<RunStatus>(found - kStatusNames.begin());
    if (!json.at("exit_code").is_null()) record.exit_code = json.at("exit_code").get<int>();
    if (!json.at("signal").is_null()) record.signal = json.at("signal").get<int>();
    record.wall_s = json.at("wall_s").get<double>();
    record.detail = json.at("detail").get<std::string>();
    return record;
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(std::string("malformed run record: ") + e.what());
  }
}

Rate WilsonRate(std::size_t successes, std::size_t trials) {
  Rate rate{successes, trials, std::nullopt, std::nullopt, std::nullopt};
  if (trials == 0) return rate;
  const double n = static_cast<double>(trials);
  const double p = static_cast<double>(successes) / n;
  const double z2 = kZ95 * kZ95;
  const double centre = (p + z2 / (2.0 * n)) / (1.0 + z2 / n);
  const double half = kZ95 / (1.0 + z2 / n) * std::sqrt(p * (1.0 - p) / n + z2 / (4.0 * n * n));
  rate.rate = p;
  rate.low = std::max(0.0, centre - half);
  rate.high = std::min(1.0, centre + half);
  return rate;
}

std::optional<double> Percentile(const std::vector<double>& sorted, double p) {
  if (sorted.empty()) return std::nullopt;
  const double h = (static_cast<double>(sorted.size()) - 1.0) * p;
  const auto below = static_cast<std::size_t>(std::floor(h));
  const std::size_t above = std::min(below + 1, sorted.size() - 1);
  return sorted[below] + (h - static_cast<double>(below)) * (sorted[above] - sorted[below]);
}

SweepSummary Summarize(const SweepPlan& plan, const std::vector<RunFiles>& files) {
  if (files.size() != plan.runs.size()) {
    throw std::invalid_argument("Summarize: one RunFiles per run of the plan");
  }
  SweepSummary summary;
  summary.name = plan.name;
  summary.axes = plan.axes;
  summary.confirm_within_s = plan.confirm_within_s;
  summary.coverage_at_s = plan.coverage_at_s;
  for (std::size_t k = 0; k < kCurvePoints; ++k) {
    summary.curve_t_s.push_back(plan.duration_s * static_cast<double>(k) /
                                static_cast<double>(kCurvePoints - 1));
  }
  summary.runs = plan.runs.size();
  std::vector<Counts> counts;
  for (std::size_t i = 0; i < plan.runs.size(); ++i) {
    const SweepRun& run = plan.runs[i];
    if (run.combination >= summary.groups.size()) {
      summary.groups.resize(run.combination + 1);
      counts.resize(run.combination + 1);
    }
    GroupSummary& group = summary.groups[run.combination];
    Counts& count = counts[run.combination];
    if (group.runs == 0) {
      group.values = run.values;
      group.label = CombinationLabel(plan.axes, run.values);
      group.coverage_at.resize(plan.coverage_at_s.size());
      count.curve_sum.assign(summary.curve_t_s.size(), 0.0);
    }
    ++group.runs;
    const std::optional<RunRecord>& record = files[i].record;
    if (!record) {
      ++group.missing;
      summary.missing.push_back(run.id);
      continue;
    }
    switch (record->status) {
      case RunStatus::kDone:
        ++group.done;
        break;
      case RunStatus::kCrashed:
        ++group.crashed;
        break;
      case RunStatus::kTimedOut:
        ++group.timed_out;
        break;
      case RunStatus::kError:
        ++group.errors;
        break;
    }
    if (record->status != RunStatus::kDone) continue;
    if (!files[i].report) {
      throw std::runtime_error("run " + RunName(run.id) + " is recorded done but has no report");
    }
    try {
      AddReport(plan, summary, *record, *files[i].report, group, count);
    } catch (const nlohmann::json::exception& e) {
      throw std::runtime_error("run " + RunName(run.id) + ": report.json: " + e.what());
    }
  }
  for (std::size_t g = 0; g < summary.groups.size(); ++g) {
    GroupSummary& group = summary.groups[g];
    const Counts& count = counts[g];
    SortAll(group);
    group.expectations_hold = WilsonRate(count.expectations_hold, group.done);
    group.all_confirmed = WilsonRate(count.all_confirmed, group.done);
    group.fires_confirmed = WilsonRate(count.fires_confirmed, count.fires);
    group.runs_with_collision = WilsonRate(count.runs_with_collision, group.done);
    for (const double sum : count.curve_sum) {
      group.coverage_curve.push_back(group.done > 0 ? sum / static_cast<double>(group.done) : 0.0);
    }
    summary.done += group.done;
    summary.crashed += group.crashed;
    summary.timed_out += group.timed_out;
    summary.errors += group.errors;
  }
  return summary;
}

}  // namespace fireswarm::run
