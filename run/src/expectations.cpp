#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "scoring.hpp"

namespace fireswarm::run::internal {
namespace {

ExpectOutcome Outcome(std::string name, double value, double limit, bool passed,
                      std::string detail) {
  ExpectOutcome out;
  out.name = std::move(name);
  out.value = value;
  out.limit = limit;
  out.passed = passed;
  if (!passed) out.detail = std::move(detail);
  return out;
}

// A number for a message: at most two decimals, "never" when not finite.
std::string Num(double value) {
  if (!std::isfinite(value)) return "never";
  std::string text = std::to_string(std::round(value * 100.0) / 100.0);
  text.erase(text.find_last_not_of('0') + 1);
  if (!text.empty() && text.back() == '.') text.pop_back();
  return text;
}

// The keys on the fleet's safety and the radio: min_separation_m,
// max_reports_lost, min_collisions.
void EvaluateSafetyAndRadio(const Expectations& expect, const Report& report,
                            std::vector<ExpectOutcome>& out) {
  if (expect.min_separation_m) {
    const double limit = *expect.min_separation_m;
    // No separation measured (e.g. a single vehicle): nothing came close (reported as null).
    const double value = report.min_separation_m.value_or(std::numeric_limits<double>::infinity());
    out.push_back(Outcome(
        "min_separation_m", value, limit, value >= limit,
        "two vehicles came within " + Num(value) + " m, at least " + Num(limit) + " m required"));
  }
  if (expect.max_reports_lost) {
    const auto limit = static_cast<double>(*expect.max_reports_lost);
    const auto lost = static_cast<double>(report.radio.reports_lost);
    out.push_back(Outcome("max_reports_lost", lost, limit, lost <= limit,
                          Num(lost) + " fire report(s) of " +
                              std::to_string(report.radio.reports_sent) +
                              " never reached the server, at most " + Num(limit) + " allowed"));
  }
  if (expect.min_collisions) {
    const auto limit = static_cast<double>(*expect.min_collisions);
    const auto count = static_cast<double>(report.collisions.size());
    out.push_back(
        Outcome("min_collisions", count, limit, count >= limit,
                Num(count) + " collision(s) reported, at least " + Num(limit) + " expected"));
  }
}

}  // namespace

std::vector<ExpectOutcome> EvaluateExpectations(const Expectations& expect, const Report& report) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  std::vector<ExpectOutcome> out;
  if (expect.all_fires_confirmed_within_s) {
    const double limit = *expect.all_fires_confirmed_within_s;
    double worst = 0.0;
    std::string detail;
    for (std::size_t i = 0; i < report.fires.size(); ++i) {
      const FireOutcome& fire = report.fires[i];
      const double delay = fire.confirmed_s ? *fire.confirmed_s - fire.start_s : kInf;
      if (delay > limit && detail.empty()) {
        detail = "fire " + std::to_string(i + 1) +
                 (fire.confirmed_s ? " confirmed " + Num(delay) + " s after it started"
                                   : " never confirmed");
      }
      worst = std::max(worst, delay);
    }
    out.push_back(Outcome("all_fires_confirmed_within_s", worst, limit, worst <= limit,
                          detail + " (limit " + Num(limit) + " s)"));
  }
  if (expect.max_fused_error_m) {
    const double limit = *expect.max_fused_error_m;
    double worst = 0.0;
    std::size_t confirmed = 0;
    std::string detail;
    for (std::size_t i = 0; i < report.fires.size(); ++i) {
      const FireOutcome& fire = report.fires[i];
      if (!fire.error_m) continue;
      ++confirmed;
      if (*fire.error_m > limit && detail.empty()) {
        detail = "fire " + std::to_string(i + 1) + " fused " + Num(*fire.error_m) + " m off";
      }
      worst = std::max(worst, *fire.error_m);
    }
    // No error can be judged when fires exist and none was confirmed.
    if (confirmed == 0 && !report.fires.empty()) {
      out.push_back(Outcome("max_fused_error_m", kInf, limit, false, "no fire was confirmed"));
    } else {
      out.push_back(Outcome("max_fused_error_m", worst, limit, worst <= limit,
                            detail + " (limit " + Num(limit) + " m)"));
    }
  }
  if (expect.no_collisions) {
    const auto count = static_cast<double>(report.collisions.size());
    std::string detail;
    if (!report.collisions.empty()) {
      const Collision& first = report.collisions.front();
      detail = std::to_string(report.collisions.size()) + " collision(s), the first of vehicles " +
               std::to_string(first.vehicle_a) + " and " + std::to_string(first.vehicle_b) +
               " at " + Num(first.t_s) + " s";
    }
    out.push_back(Outcome("no_collisions", count, 0.0, report.collisions.empty(), detail));
  }
  if (expect.min_coverage) {
    const double limit = *expect.min_coverage;
    out.push_back(Outcome(
        "min_coverage", report.coverage, limit, report.coverage >= limit,
        "coverage " + Num(report.coverage * 100.0) + " % is below " + Num(limit * 100.0) + " %"));
  }
  if (expect.max_false_tracks) {
    const auto limit = static_cast<double>(*expect.max_false_tracks);
    const auto count = static_cast<double>(report.false_tracks.size());
    out.push_back(Outcome("max_false_tracks", count, limit, count <= limit,
                          Num(count) + " false track(s), at most " + Num(limit) + " allowed"));
  }
  EvaluateSafetyAndRadio(expect, report, out);
  return out;
}

}  // namespace fireswarm::run::internal
