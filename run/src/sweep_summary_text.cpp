// summary.json and summary.csv of a sweep.
#include <charconv>
#include <cmath>
#include <string>

#include "fireswarm/run/sweep_summary.hpp"
#include "sweep_text.hpp"

namespace fireswarm::run {
namespace {

using Json = nlohmann::ordered_json;

constexpr std::array<double, 3> kQuantiles{0.1, 0.5, 0.9};
constexpr std::array<std::string_view, 3> kQuantileNames{"p10", "p50", "p90"};

Json NullOr(const std::optional<double>& value) {
  return value ? Json(*value) : Json(nullptr);
}

std::optional<double> Mean(const std::vector<double>& values) {
  if (values.empty()) return std::nullopt;
  double sum = 0.0;
  for (const double v : values) sum += v;
  return sum / static_cast<double>(values.size());
}

std::optional<double> Max(const std::vector<double>& sorted) {
  if (sorted.empty()) return std::nullopt;
  return sorted.back();
}

Json RateJson(const Rate& rate) {
  return {{"successes", rate.successes},
          {"trials", rate.trials},
          {"rate", NullOr(rate.rate)},
          {"ci95", Json::array({NullOr(rate.low), NullOr(rate.high)})}};
}

Json Distribution(const std::vector<double>& sorted, bool with_values) {
  Json j;
  j["count"] = sorted.size();
  j["mean"] = NullOr(Mean(sorted));
  for (std::size_t q = 0; q < kQuantiles.size(); ++q) {
    j[std::string(kQuantileNames[q])] = NullOr(Percentile(sorted, kQuantiles[q]));
  }
  j["max"] = NullOr(Max(sorted));
  if (with_values) j["values"] = sorted;
  return j;
}

// An axis value as JSON: a number when the YAML text is one, else the text.
Json AxisValue(const std::string& text) {
  std::int64_t integer = 0;
  const char* end = text.data() + text.size();
  if (auto [ptr, error] = std::from_chars(text.data(), end, integer);
      error == std::errc() && ptr == end) {
    return integer;
  }
  double number = 0.0;
  if (auto [ptr, error] = std::from_chars(text.data(), end, number);
      error == std::errc() && ptr == end && std::isfinite(number)) {
    return number;
  }
  return text;
}

std::string Cell(const std::optional<double>& value) {
  return value ? internal::NumberText(*value) : std::string();
}

// A CSV field, quoted when it holds a separator, a quote or a line break.
std::string CsvField(const std::string& text) {
  if (text.find_first_of(",\"\n\r") == std::string::npos) return text;
  std::string quoted = "\"";
  for (const char c : text) {
    if (c == '"') quoted += '"';
    quoted += c;
  }
  return quoted + "\"";
}

}  // namespace

nlohmann::ordered_json ToJson(const SweepSummary& summary) {
  Json j;
  j["name"] = summary.name;
  j["axes"] = summary.axes;
  j["confirm_within_s"] = summary.confirm_within_s;
  j["coverage_at_s"] = summary.coverage_at_s;
  j["runs"] = {{"total", summary.runs},      {"done", summary.done},
               {"crashed", summary.crashed}, {"timed_out", summary.timed_out},
               {"errors", summary.errors},   {"missing", summary.missing.size()}};
  j["missing_runs"] = summary.missing;
  j["coverage_curve_t_s"] = summary.curve_t_s;
  Json groups = Json::array();
  for (const GroupSummary& group : summary.groups) {
    Json g;
    g["label"] = group.label;
    Json values;
    for (std::size_t a = 0; a < summary.axes.size(); ++a) {
      values[summary.axes[a]] = AxisValue(group.values[a]);
    }
    g["axes"] = summary.axes.empty() ? Json::object() : values;
    g["runs"] = {{"total", group.runs},      {"done", group.done},
                 {"crashed", group.crashed}, {"timed_out", group.timed_out},
                 {"errors", group.errors},   {"missing", group.missing}};
    g["expectations_hold"] = RateJson(group.expectations_hold);
    g["all_fires_confirmed_within"] = RateJson(group.all_confirmed);
    g["fires_confirmed"] = RateJson(group.fires_confirmed);
    g["time_to_confirm_s"] = Distribution(group.time_to_confirm_s, true);
    g["fused_error_m"] = Distribution(group.fused_error_m, true);
    Json coverage = Json::array();
    for (std::size_t k = 0; k < summary.coverage_at_s.size(); ++k) {
      Json at = Distribution(group.coverage_at[k], false);
      at["t_s"] = summary.coverage_at_s[k];
      coverage.push_back(at);
    }
    g["coverage_at"] = coverage;
    g["coverage_curve"] = group.coverage_curve;
    g["collisions"] = {
        {"total", group.collisions},
        {"runs_with_collision", RateJson(group.runs_with_collision)},
        {"flight_hours", group.flight_hours},
        {"per_flight_hour", group.flight_hours > 0.0
                                ? Json(static_cast<double>(group.collisions) / group.flight_hours)
                                : Json(nullptr)}};
    g["min_separation_m"] = Distribution(group.min_separation_m, false);
    g["false_tracks"] = group.false_tracks;
    g["radio"] = {{"busy_fraction", Distribution(group.radio_busy_fraction, false)},
                  {"report_latency_p50_s", Distribution(group.report_latency_p50_s, false)},
                  {"retries", group.retries},
                  {"reports_lost", group.reports_lost}};
    groups.push_back(g);
  }
  j["groups"] = groups;
  return j;
}

std::string SummaryCsv(const SweepSummary& summary) {
  std::string header;
  for (const std::string& axis : summary.axes) header += CsvField(axis) + ",";
  header +=
      "runs,done,crashed,timed_out,errors,missing,expectations_hold_rate,"
      "all_fires_confirmed_rate,all_fires_confirmed_ci95_low,all_fires_confirmed_ci95_high,"
      "fires,fires_confirmed,time_to_confirm_p10_s,time_to_confirm_p50_s,time_to_confirm_p90_s,"
      "time_to_confirm_max_s,fused_error_p50_m,fused_error_p90_m,fused_error_max_m";
  for (const double t_s : summary.coverage_at_s) {
    header += ",coverage_p50_at_" + internal::NumberText(t_s) + "_s";
  }
  header +=
      ",collisions,flight_hours,collisions_per_flight_hour,min_separation_p10_m,false_tracks,"
      "radio_busy_p50,report_latency_p50_s,retries,reports_lost\n";
  std::string csv = header;
  for (const GroupSummary& g : summary.groups) {
    std::string row;
    for (const std::string& value : g.values) row += CsvField(value) + ",";
    for (const std::size_t n : {g.runs, g.done, g.crashed, g.timed_out, g.errors, g.missing}) {
      row += std::to_string(n) + ",";
    }
    row += Cell(g.expectations_hold.rate) + "," + Cell(g.all_confirmed.rate) + "," +
           Cell(g.all_confirmed.low) + "," + Cell(g.all_confirmed.high) + "," +
           std::to_string(g.fires_confirmed.trials) + "," +
           std::to_string(g.fires_confirmed.successes);
    for (const double q : kQuantiles) row += "," + Cell(Percentile(g.time_to_confirm_s, q));
    row += "," + Cell(Max(g.time_to_confirm_s));
    row += "," + Cell(Percentile(g.fused_error_m, 0.5)) + "," +
           Cell(Percentile(g.fused_error_m, 0.9)) + "," + Cell(Max(g.fused_error_m));
    for (const std::vector<double>& at : g.coverage_at) row += "," + Cell(Percentile(at, 0.5));
    row += "," + std::to_string(g.collisions) + "," + internal::NumberText(g.flight_hours) + "," +
           (g.flight_hours > 0.0
                ? internal::NumberText(static_cast<double>(g.collisions) / g.flight_hours)
                : std::string()) +
           "," + Cell(Percentile(g.min_separation_m, 0.1)) + "," + std::to_string(g.false_tracks) +
           "," + Cell(Percentile(g.radio_busy_fraction, 0.5)) + "," +
           Cell(Percentile(g.report_latency_p50_s, 0.5)) + "," + std::to_string(g.retries) + "," +
           std::to_string(g.reports_lost) + "\n";
    csv += row;
  }
  return csv;
}

}  // namespace fireswarm::run
