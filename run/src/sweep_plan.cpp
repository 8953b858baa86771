// DIR/plan.json: the expanded runs of a sweep, the one thing a resumed sweep,
// a Slurm array task and `--collect` must agree on.
#include <stdexcept>
#include <string>

#include "fireswarm/run/sweep.hpp"

namespace fireswarm::run {

nlohmann::ordered_json ToJson(const SweepPlan& plan) {
  nlohmann::ordered_json j;
  j["format"] = "fireswarm-sweep-plan-1";
  j["name"] = plan.name;
  j["axes"] = plan.axes;
  j["confirm_within_s"] = plan.confirm_within_s;
  j["coverage_at_s"] = plan.coverage_at_s;
  j["duration_s"] = plan.duration_s;
  nlohmann::ordered_json runs = nlohmann::ordered_json::array();
  for (const SweepRun& run : plan.runs) {
    runs.push_back({{"id", run.id},
                    {"combination", run.combination},
                    {"seed", run.seed},
                    {"values", run.values}});
  }
  j["runs"] = runs;
  return j;
}

SweepPlan PlanFromJson(const nlohmann::json& json) {
  try {
    if (json.at("format") != "fireswarm-sweep-plan-1") {
      throw std::runtime_error("not a fireswarm sweep plan (format " + json.at("format").dump() +
                               ")");
    }
    SweepPlan plan;
    plan.name = json.at("name").get<std::string>();
    plan.axes = json.at("axes").get<std::vector<std::string>>();
    plan.confirm_within_s = json.at("confirm_within_s").get<double>();
    plan.coverage_at_s = json.at("coverage_at_s").get<std::vector<double>>();
    plan.duration_s = json.at("duration_s").get<double>();
    for (const nlohmann::json& run : json.at("runs")) {
      SweepRun r;
      r.id = run.at("id").get<std::size_t>();
      r.combination = run.at("combination").get<std::size_t>();
      r.seed = run.at("seed").get<std::uint64_t>();
      r.values = run.at("values").get<std::vector<std::string>>();
      if (r.id != plan.runs.size() || r.values.size() != plan.axes.size()) {
        throw std::runtime_error("run " + std::to_string(plan.runs.size()) + " is malformed");
      }
      plan.runs.push_back(std::move(r));
    }
    return plan;
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(std::string("malformed sweep plan: ") + e.what());
  }
}

}  // namespace fireswarm::run
