// summary.html: the sweep's table and its plots, one self-contained page (inline
// SVG, no script, nothing fetched). Each line of a plot is drawn in data units
// under a transform, so its points are the summary's numbers, not pixels.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "fireswarm/run/sweep_summary.hpp"
#include "sweep_text.hpp"
#include "xml_text.hpp"

namespace fireswarm::run {
namespace {

using internal::FixedNumber;
using internal::NumberText;
using internal::XmlEscape;

constexpr double kPlotWidth = 640.0;
constexpr double kPlotHeight = 320.0;
constexpr double kLeft = 64.0;
constexpr double kRight = 24.0;
constexpr double kTop = 28.0;
constexpr double kBottom = 48.0;
constexpr double kLegendRow = 18.0;
constexpr int kTicks = 5;
constexpr std::array<std::string_view, 10> kColours{"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728",
                                                    "#9467bd", "#8c564b", "#e377c2", "#7f7f7f",
                                                    "#bcbd22", "#17becf"};
constexpr std::array<std::string_view, 3> kDashes{"", "6 3", "2 2"};

struct Series {
  std::string label;
  std::vector<std::pair<double, double>> points;  // data units
};

// A round upper end for an axis that must reach `max`, whose fifths are round too
// (1, 1.5, 2, 2.5, 3, 4, 5, 6 or 8 times a power of ten).
double NiceMax(double max) {
  if (!(max > 0.0)) return 1.0;
  const double power = std::pow(10.0, std::floor(std::log10(max)));
  for (const double step : {1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0}) {
    if (step * power >= max) return step * power;
  }
  return 10.0 * power;
}

std::string Points(const std::vector<std::pair<double, double>>& points) {
  std::string text;
  for (const auto& [x, y] : points) {
    if (!text.empty()) text += ' ';
    text += NumberText(x) + "," + NumberText(y);
  }
  return text;
}

// One plot: axes with ticks, a line per series, a legend below.
std::string Plot(const std::string& id, const std::string& title, const std::string& x_title,
                 const std::string& y_title, double x_max, const std::vector<Series>& series) {
  const double inner_w = kPlotWidth - kLeft - kRight;
  const double inner_h = kPlotHeight - kTop - kBottom;
  const double height = kPlotHeight + kLegendRow * static_cast<double>(series.size());
  const double sx = inner_w / x_max;
  const double sy = inner_h;  // y is a fraction, 0..1
  std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"plot\" id=\"" + id +
                    "\" width=\"" + FixedNumber(kPlotWidth, 0) + "\" height=\"" +
                    FixedNumber(height, 0) + "\" viewBox=\"0 0 " + FixedNumber(kPlotWidth, 0) +
                    " " + FixedNumber(height, 0) + "\" data-x-max=\"" + NumberText(x_max) +
                    "\" font-family=\"sans-serif\" font-size=\"11\">\n";
  svg += "<title>" + XmlEscape(title, internal::XmlPlace::kText) + "</title>\n";
  svg += "<text x=\"" + FixedNumber(kLeft, 0) +
         "\" y=\"16\" font-size=\"13\" font-weight=\"bold\">" +
         XmlEscape(title, internal::XmlPlace::kText) + "</text>\n";
  const double x0 = kLeft;
  const double y0 = kTop + inner_h;
  for (int k = 0; k <= kTicks; ++k) {
    const double f = static_cast<double>(k) / kTicks;
    const std::string gx = FixedNumber(x0 + f * inner_w, 1);
    const std::string gy = FixedNumber(y0 - f * inner_h, 1);
    svg += "<line class=\"grid\" x1=\"" + gx + "\" y1=\"" + FixedNumber(kTop, 1) + "\" x2=\"" + gx +
           "\" y2=\"" + FixedNumber(y0, 1) + "\" stroke=\"#ddd\"/>\n";
    svg += "<line class=\"grid\" x1=\"" + FixedNumber(x0, 1) + "\" y1=\"" + gy + "\" x2=\"" +
           FixedNumber(x0 + inner_w, 1) + "\" y2=\"" + gy + "\" stroke=\"#ddd\"/>\n";
    svg += "<text x=\"" + gx + "\" y=\"" + FixedNumber(y0 + 14.0, 1) +
           "\" text-anchor=\"middle\">" + internal::ShortNumber(f * x_max, 4) + "</text>\n";
    svg += "<text x=\"" + FixedNumber(x0 - 6.0, 1) + "\" y=\"" +
           FixedNumber(y0 - f * inner_h + 4.0, 1) + "\" text-anchor=\"end\">" +
           internal::ShortNumber(f, 2) + "</text>\n";
  }
  svg += "<rect x=\"" + FixedNumber(x0, 1) + "\" y=\"" + FixedNumber(kTop, 1) + "\" width=\"" +
         FixedNumber(inner_w, 1) + "\" height=\"" + FixedNumber(inner_h, 1) +
         "\" fill=\"none\" stroke=\"#444\"/>\n";
  svg += "<text x=\"" + FixedNumber(x0 + inner_w / 2.0, 1) + "\" y=\"" + FixedNumber(y0 + 32.0, 1) +
         "\" text-anchor=\"middle\">" + XmlEscape(x_title, internal::XmlPlace::kText) + "</text>\n";
  svg += "<text transform=\"translate(14," + FixedNumber(kTop + inner_h / 2.0, 1) +
         ") rotate(-90)\" text-anchor=\"middle\">" + XmlEscape(y_title, internal::XmlPlace::kText) +
         "</text>\n";
  // Data units to pixels: x right from the left axis, y (0..1) up from the bottom.
  svg += "<g class=\"data\" transform=\"translate(" + FixedNumber(x0, 1) + "," +
         FixedNumber(y0, 1) + ") scale(" + NumberText(sx) + "," + NumberText(-sy) + ")\">\n";
  for (std::size_t s = 0; s < series.size(); ++s) {
    const std::string_view dash = kDashes[(s / kColours.size()) % kDashes.size()];
    svg += "<polyline class=\"series\" data-label=\"" + XmlEscape(series[s].label) +
           "\" fill=\"none\" stroke=\"" + std::string(kColours[s % kColours.size()]) +
           "\" stroke-width=\"2\" vector-effect=\"non-scaling-stroke\"" +
           (dash.empty() ? std::string() : " stroke-dasharray=\"" + std::string(dash) + "\"") +
           " points=\"" + Points(series[s].points) + "\"/>\n";
  }
  svg += "</g>\n";
  for (std::size_t s = 0; s < series.size(); ++s) {
    const double y = kPlotHeight + kLegendRow * static_cast<double>(s) - 4.0;
    svg += "<line x1=\"" + FixedNumber(x0, 1) + "\" y1=\"" + FixedNumber(y, 1) + "\" x2=\"" +
           FixedNumber(x0 + 24.0, 1) + "\" y2=\"" + FixedNumber(y, 1) + "\" stroke=\"" +
           std::string(kColours[s % kColours.size()]) + "\" stroke-width=\"2\"/>\n";
    svg += "<text class=\"legend\" x=\"" + FixedNumber(x0 + 30.0, 1) + "\" y=\"" +
           FixedNumber(y + 4.0, 1) + "\">" + XmlEscape(series[s].label, internal::XmlPlace::kText) +
           "</text>\n";
  }
  svg += "</svg>\n";
  return svg;
}

// A step CDF: for each value v_i (ascending) the points (v_i, i/n) and
// (v_i, (i+1)/n); `n` may exceed the values (fires never confirmed).
std::vector<std::pair<double, double>> Cdf(const std::vector<double>& sorted, std::size_t n) {
  std::vector<std::pair<double, double>> points;
  for (std::size_t i = 0; i < sorted.size(); ++i) {
    points.emplace_back(sorted[i], static_cast<double>(i) / static_cast<double>(n));
    points.emplace_back(sorted[i], static_cast<double>(i + 1) / static_cast<double>(n));
  }
  return points;
}

std::string Percent(const std::optional<double>& fraction) {
  return fraction ? FixedNumber(100.0 * *fraction, 1) + " %" : "&#8211;";
}

std::string Seconds(const std::optional<double>& value, int decimals = 0) {
  return value ? FixedNumber(*value, decimals) : "&#8211;";
}

std::string Table(const SweepSummary& summary) {
  std::string html =
      "<table>\n<tr><th>combination</th><th>runs</th>"
      "<th>crashed / timed out / errors / missing</th>"
      "<th>all fires confirmed within " +
      FixedNumber(summary.confirm_within_s, 0) +
      " s [95 % CI]</th><th>fires confirmed</th><th>time to confirm p50 / p90 s</th>"
      "<th>fused error p50 / p90 m</th>";
  for (const double t_s : summary.coverage_at_s) {
    html += "<th>coverage p50 at " + FixedNumber(t_s, 0) + " s</th>";
  }
  html += "<th>collisions / flight h</th><th>radio busy p50</th></tr>\n";
  for (const GroupSummary& g : summary.groups) {
    html += "<tr><td>" + XmlEscape(g.label, internal::XmlPlace::kText) + "</td><td>" +
            std::to_string(g.runs) + "</td><td>" + std::to_string(g.crashed) + " / " +
            std::to_string(g.timed_out) + " / " + std::to_string(g.errors) + " / " +
            std::to_string(g.missing) + "</td><td>" + Percent(g.all_confirmed.rate) + " [" +
            Percent(g.all_confirmed.low) + ", " + Percent(g.all_confirmed.high) + "]</td><td>" +
            std::to_string(g.fires_confirmed.successes) + " / " +
            std::to_string(g.fires_confirmed.trials) + "</td><td>" +
            Seconds(Percentile(g.time_to_confirm_s, 0.5)) + " / " +
            Seconds(Percentile(g.time_to_confirm_s, 0.9)) + "</td><td>" +
            Seconds(Percentile(g.fused_error_m, 0.5), 1) + " / " +
            Seconds(Percentile(g.fused_error_m, 0.9), 1) + "</td>";
    for (const std::vector<double>& at : g.coverage_at) {
      html += "<td>" + Percent(Percentile(at, 0.5)) + "</td>";
    }
    html +=
        "<td>" +
        (g.flight_hours > 0.0 ? FixedNumber(static_cast<double>(g.collisions) / g.flight_hours, 3)
                              : std::string("&#8211;")) +
        "</td><td>" + Percent(Percentile(g.radio_busy_fraction, 0.5)) + "</td></tr>\n";
  }
  return html + "</table>\n";
}

}  // namespace

std::string SummaryHtml(const SweepSummary& summary) {
  std::vector<Series> confirm;
  std::vector<Series> coverage;
  std::vector<Series> error;
  double confirm_max = 0.0;
  double error_max = 0.0;
  for (const GroupSummary& g : summary.groups) {
    confirm.push_back(
        {g.label, Cdf(g.time_to_confirm_s, std::max<std::size_t>(1, g.fires_confirmed.trials))});
    error.push_back(
        {g.label, Cdf(g.fused_error_m, std::max<std::size_t>(1, g.fused_error_m.size()))});
    Series curve{g.label, {}};
    for (std::size_t k = 0; k < summary.curve_t_s.size() && k < g.coverage_curve.size(); ++k) {
      curve.points.emplace_back(summary.curve_t_s[k], g.coverage_curve[k]);
    }
    coverage.push_back(std::move(curve));
    if (!g.time_to_confirm_s.empty())
      confirm_max = std::max(confirm_max, g.time_to_confirm_s.back());
    if (!g.fused_error_m.empty()) error_max = std::max(error_max, g.fused_error_m.back());
  }
  const double duration_s = summary.curve_t_s.empty() ? 1.0 : summary.curve_t_s.back();
  std::string html =
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\"/>\n<title>sweep " +
      XmlEscape(summary.name, internal::XmlPlace::kText) +
      "</title>\n<style>body{font-family:sans-serif;margin:2em}"
      "table{border-collapse:collapse;font-size:13px}td,th{border:1px solid #ccc;padding:3px 6px;"
      "text-align:right}td:first-child{text-align:left}svg{display:block;margin:1.5em 0}</style>\n"
      "</head>\n<body>\n<h1>sweep " +
      XmlEscape(summary.name, internal::XmlPlace::kText) + "</h1>\n<p>" +
      std::to_string(summary.runs) + " runs: " + std::to_string(summary.done) + " done, " +
      std::to_string(summary.crashed) + " crashed, " + std::to_string(summary.timed_out) +
      " timed out, " + std::to_string(summary.errors) + " errors, " +
      std::to_string(summary.missing.size()) +
      " missing. Rates are over the done runs; intervals are Wilson 95 %.</p>\n";
  html += Table(summary);
  html += Plot("time_to_confirm_cdf", "Time from ignition to confirmation (CDF over all fires)",
               "time to confirm, s", "fraction of fires", NiceMax(confirm_max), confirm);
  html += Plot("coverage_over_time", "Coverage against time (mean over runs)", "time, s",
               "fraction of the area seen", NiceMax(duration_s), coverage);
  html += Plot("fused_error_cdf", "Fused position error (CDF over confirmed fires)",
               "fused error, m", "fraction of confirmed fires", NiceMax(error_max), error);
  html += "</body>\n</html>\n";
  return html;
}

}  // namespace fireswarm::run
