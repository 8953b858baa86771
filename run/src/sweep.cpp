// Reading a sweep file: the base scenario, the seeds and the axes, each axis
// value checked by parsing the scenario it makes (so an axis key must be a real
// scenario key and a value one the scenario takes), every error naming the sweep
// file's line and key.
#include "fireswarm/run/sweep.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "fireswarm/run/scenario.hpp"
#include "sweep_yaml.hpp"
#include "yaml_field.hpp"

namespace fireswarm::run {
namespace {

namespace fs = std::filesystem;
using internal::Field;
using internal::Mapping;
using internal::Range;

std::vector<std::uint64_t> ReadSeeds(const Field& field) {
  std::vector<std::uint64_t> seeds;
  if (field.IsSequence()) {
    for (const Field& element : field.Elements()) {
      const std::uint64_t seed = element.Unsigned64();
      if (std::find(seeds.begin(), seeds.end(), seed) != seeds.end()) element.Fail("repeated seed");
      seeds.push_back(seed);
    }
    if (seeds.empty()) field.Fail("must name at least one seed");
    return seeds;
  }
  const Mapping range(field, {"first", "count"});
  const std::uint64_t first = range.Required("first").Unsigned64();
  const auto count = static_cast<std::uint64_t>(
      range.Required("count").Integer(1, static_cast<std::int64_t>(kMaxSweepRuns)));
  if (first > std::numeric_limits<std::uint64_t>::max() - (count - 1)) {
    field.Fail("the range first + count - 1 passes the largest seed");
  }
  for (std::uint64_t k = 0; k < count; ++k) seeds.push_back(first + k);
  return seeds;
}

// The scenario's complaint without its "<file>:<line>:<column>: " (the line is
// the generated scenario's, not one the user wrote).
std::string WithoutPlace(const std::string& message, const std::string& source) {
  if (!message.starts_with(source + ":")) return message;
  std::size_t at = source.size() + 1;
  for (int part = 0; part < 2; ++part) {
    std::size_t digits = at;
    while (digits < message.size() && std::isdigit(static_cast<unsigned char>(message[digits]))) {
      ++digits;
    }
    if (digits == at || digits >= message.size() || message[digits] != ':') break;
    at = digits + 1;
  }
  while (at < message.size() && message[at] == ' ') ++at;
  return message.substr(at);
}

struct ScenarioCheck {
  std::optional<Scenario> scenario;
  std::string problem;  ///< when scenario is empty
  bool unknown_key = false;
};

ScenarioCheck TryScenario(const SweepSpec& spec, const std::vector<std::string>& keys,
                          const std::vector<std::string>& values) {
  ScenarioCheck check;
  const std::string source = spec.scenario_path.string();
  std::string text;
  try {
    text = internal::OverriddenScenarioYaml(spec.scenario_text, std::nullopt, keys, values,
                                            std::nullopt);
  } catch (const internal::OverrideError& e) {
    check.problem = e.what();
    check.unknown_key = true;
    return check;
  }
  try {
    check.scenario = ParseScenario(text, source, spec.scenario_path.parent_path());
  } catch (const ScenarioError& e) {
    check.problem = WithoutPlace(e.what(), source);
    check.unknown_key = check.problem.find(": unknown key") != std::string::npos;
  }
  return check;
}

std::vector<SweepAxis> ReadAxes(const Field& field, const SweepSpec& spec) {
  if (!field.IsMap()) field.Fail("must be a mapping of scenario keys to lists of values");
  std::vector<SweepAxis> axes;
  for (const auto& entry : field.node()) {
    const YAML::Node key_node = entry.first;
    const YAML::Node value_node = entry.second;
    const std::string key = key_node.IsScalar() ? key_node.Scalar() : std::string("?");
    const Field key_field = field.Child(key_node, field.path() + "." + key);
    if (!key_node.IsScalar() || key.empty()) key_field.Fail("an axis key must be a scenario key");
    if (key == "seed") key_field.Fail("the seeds are given by the sweep's `seeds`, not an axis");
    for (const SweepAxis& seen : axes) {
      if (seen.key == key) key_field.Fail("repeated axis");
    }
    const Field values = field.Child(value_node, key_field.path());
    if (!value_node.IsSequence() || value_node.size() == 0) {
      key_field.Fail("must be a non-empty list of values, e.g. [5, 10, 20]");
    }
    SweepAxis axis{key, {}};
    for (const Field& value : values.Elements()) {
      const std::string text = internal::FlowYaml(value.node());
      if (std::find(axis.values.begin(), axis.values.end(), text) != axis.values.end()) {
        value.Fail("repeated value");
      }
      // Each value alone on the base scenario: the scenario loader is the one
      // judge of what a key is and what it takes.
      const ScenarioCheck check = TryScenario(spec, {key}, {text});
      if (!check.scenario) {
        if (check.unknown_key) key_field.Fail("not a scenario key: " + check.problem);
        value.Fail("the scenario refuses it: " + check.problem);
      }
      axis.values.push_back(text);
    }
    axes.push_back(std::move(axis));
  }
  return axes;
}

std::size_t CombinationCount(const std::vector<SweepAxis>& axes) {
  std::size_t count = 1;
  for (const SweepAxis& axis : axes) count *= axis.values.size();
  return count;
}

// The axis values of combination `index` (the first axis varies slowest).
std::vector<std::string> Combination(const std::vector<SweepAxis>& axes, std::size_t index) {
  std::vector<std::string> values(axes.size());
  for (std::size_t a = axes.size(); a-- > 0;) {
    values[a] = axes[a].values[index % axes[a].values.size()];
    index /= axes[a].values.size();
  }
  return values;
}

std::vector<std::string> AxisKeys(const std::vector<SweepAxis>& axes) {
  std::vector<std::string> keys;
  for (const SweepAxis& axis : axes) keys.push_back(axis.key);
  return keys;
}

// Every combination parses (values may be fine alone and clash together), and
// the longest duration among them.
double CheckCombinations(const Field& axes_field, const SweepSpec& spec) {
  const std::vector<std::string> keys = AxisKeys(spec.axes);
  double longest_s = 0.0;
  for (std::size_t c = 0; c < CombinationCount(spec.axes); ++c) {
    const std::vector<std::string> values = Combination(spec.axes, c);
    const ScenarioCheck check = TryScenario(spec, keys, values);
    if (!check.scenario) {
      axes_field.Fail("the combination " + CombinationLabel(keys, values) +
                      " makes a bad scenario: " + check.problem);
    }
    longest_s = std::max(longest_s, check.scenario->duration_s);
  }
  return longest_s;
}

void ReadSummaryOptions(const Mapping& root, const Scenario& base, SweepSpec& spec) {
  spec.confirm_within_s = base.expect.all_fires_confirmed_within_s.value_or(base.duration_s);
  for (int quarter = 1; quarter <= 4; ++quarter) {
    spec.coverage_at_s.push_back(spec.duration_s * quarter / 4.0);
  }
  const std::optional<Field> field = root.Find("summary");
  if (!field) return;
  const Mapping summary(*field, {"confirm_within_s", "coverage_at_s"});
  spec.confirm_within_s = summary.Number("confirm_within_s", spec.confirm_within_s,
                                         Range{0.0, std::numeric_limits<double>::infinity(), true});
  if (const std::optional<Field> times = summary.Find("coverage_at_s")) {
    spec.coverage_at_s.clear();
    for (const Field& time : times->Elements()) {
      const double t_s = time.Number(Range{0.0, std::numeric_limits<double>::infinity()});
      if (!spec.coverage_at_s.empty() && t_s <= spec.coverage_at_s.back()) {
        time.Fail("the times must be ascending");
      }
      spec.coverage_at_s.push_back(t_s);
    }
    if (spec.coverage_at_s.empty()) times->Fail("must name at least one time");
  }
}

}  // namespace

SweepSpec ParseSweep(std::string_view text, const std::string& source_name,
                     const std::filesystem::path& base_dir) {
  const YAML::Node document = internal::LoadYaml(text, source_name);
  if (!document.IsMap()) {
    throw ScenarioError(source_name +
                        ": the sweep must be a YAML mapping of keys (scenario, seeds, axes, ...)");
  }
  const Field top(source_name, document, "");
  const Mapping root(top, {"name", "scenario", "seeds", "axes", "summary"});
  SweepSpec spec;
  spec.source = source_name;
  const std::optional<Field> name = root.Find("name");
  spec.name = name ? name->Text() : fs::path(source_name).stem().string();

  const Field scenario_field = root.Required("scenario");
  const fs::path given(scenario_field.Text());
  spec.scenario_path = (given.is_absolute() ? given : base_dir / given).lexically_normal();
  std::optional<Scenario> base;
  try {
    spec.scenario_text = internal::ReadConfigFile(spec.scenario_path, "scenario file");
    base = ParseScenario(spec.scenario_text, spec.scenario_path.string(),
                         spec.scenario_path.parent_path());
  } catch (const ScenarioError& e) {
    scenario_field.Fail(e.what());
  }

  const std::optional<Field> seeds = root.Find("seeds");
  spec.seeds = seeds ? ReadSeeds(*seeds) : std::vector<std::uint64_t>{base->seed};
  spec.duration_s = base->duration_s;
  if (const std::optional<Field> axes = root.Find("axes")) {
    spec.axes = ReadAxes(*axes, spec);
    std::size_t runs = spec.seeds.size();
    for (const SweepAxis& axis : spec.axes) {
      if (runs > kMaxSweepRuns / axis.values.size()) {
        axes->Fail("more than " + std::to_string(kMaxSweepRuns) + " runs (seeds x combinations)");
      }
      runs *= axis.values.size();
    }
    if (spec.axes.size() > 1) spec.duration_s = CheckCombinations(*axes, spec);
    for (const SweepAxis& axis : spec.axes) {
      if (axis.key != "duration_s") continue;
      for (const std::string& value : axis.values) {
        spec.duration_s = std::max(spec.duration_s, std::stod(value));
      }
    }
  }
  ReadSummaryOptions(root, *base, spec);
  return spec;
}

SweepSpec LoadSweep(const std::filesystem::path& path) {
  return ParseSweep(internal::ReadConfigFile(path, "sweep file"), path.string(),
                    path.parent_path());
}

SweepPlan MakePlan(const SweepSpec& spec) {
  SweepPlan plan;
  plan.name = spec.name;
  plan.axes = AxisKeys(spec.axes);
  plan.confirm_within_s = spec.confirm_within_s;
  plan.coverage_at_s = spec.coverage_at_s;
  plan.duration_s = spec.duration_s;
  for (std::size_t c = 0; c < CombinationCount(spec.axes); ++c) {
    const std::vector<std::string> values = Combination(spec.axes, c);
    for (const std::uint64_t seed : spec.seeds) {
      plan.runs.push_back({plan.runs.size(), c, seed, values});
    }
  }
  return plan;
}

std::string RunScenarioYaml(const SweepSpec& spec, const SweepRun& run) {
  return internal::OverriddenScenarioYaml(spec.scenario_text, run.seed, AxisKeys(spec.axes),
                                          run.values, spec.scenario_path.parent_path());
}

std::string RunName(std::size_t id) {
  std::string digits = std::to_string(id);
  constexpr std::size_t kWidth = 5;
  if (digits.size() < kWidth) digits.insert(0, kWidth - digits.size(), '0');
  return digits;
}

std::string CombinationLabel(const std::vector<std::string>& axes,
                             const std::vector<std::string>& values) {
  if (axes.empty()) return "all";
  std::string label;
  for (std::size_t a = 0; a < axes.size(); ++a) {
    if (a > 0) label += ' ';
    label += axes[a] + "=" + values[a];
  }
  return label;
}

}  // namespace fireswarm::run
