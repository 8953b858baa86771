// The sweep core: the sweep file (a bad axis key or value names the file, line
// and key), the deterministic run list and each run's scenario, the statistics
// (Wilson interval, percentiles, per-combination counts from reports), and the
// summary's plots holding the summary's numbers (parsed back from the HTML).
#include "fireswarm/run/sweep.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "fireswarm/run/scenario.hpp"
#include "fireswarm/run/sweep_summary.hpp"
#include "mini_xml.hpp"
#include "small_area.hpp"

namespace fireswarm::run {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;
using ::testing::StartsWith;

// The runner tests' small area with a fire.
const std::string kSweepBaseScenario = std::string("name: base\n") + test::kSmallAreaKeys +
                                       "fires:\n  - {lat: 45.00230, lon: 7.00480, start_s: 10}\n";

class SweepTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("fireswarm_sweep_test_" + std::to_string(getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
    std::ofstream(dir_ / "base.yaml") << kSweepBaseScenario;
  }
  void TearDown() override { fs::remove_all(dir_); }

  // Parses `text` as the sweep file "sweep.yaml" beside base.yaml.
  SweepSpec Parse(const std::string& text) const { return ParseSweep(text, "sweep.yaml", dir_); }

  std::string ErrorOf(const std::string& text) const {
    try {
      Parse(text);
    } catch (const ScenarioError& e) {
      return e.what();
    }
    return "no error";
  }

  fs::path dir_;
};

TEST_F(SweepTest, ABadAxisKeyNamesTheFileLineAndKey) {
  const std::string error = ErrorOf(
      "scenario: base.yaml\n"
      "seeds: {first: 1, count: 2}\n"
      "axes:\n"
      "  fleet.count: [1, 2]\n"
      "  fleet.cuont: [1, 2]\n");
  EXPECT_THAT(error, StartsWith("sweep.yaml:5:3: axes.fleet.cuont: not a scenario key: "));
  EXPECT_THAT(error, HasSubstr("did you mean 'count'"));
  EXPECT_THAT(ErrorOf("scenario: base.yaml\naxes:\n  fleet_count: [1]\n"),
              StartsWith("sweep.yaml:3:3: axes.fleet_count: not a scenario key: "));
  // Through a list: the scenario's `fires` is not a mapping.
  EXPECT_THAT(
      ErrorOf("scenario: base.yaml\naxes:\n  fires.lat: [45]\n"),
      StartsWith("sweep.yaml:3:3: axes.fires.lat: not a scenario key: fires: is not a mapping"));
}

TEST_F(SweepTest, AValueTheScenarioRefusesNamesItsLine) {
  const std::string error = ErrorOf(
      "scenario: base.yaml\n"
      "axes:\n"
      "  fleet.count: [2,\n"
      "                300]\n");
  EXPECT_THAT(error, StartsWith("sweep.yaml:4:17: axes.fleet.count[1]: the scenario refuses it: "
                                "fleet.count: must be in [1, 254], got 300"));
}

TEST_F(SweepTest, OtherBadInputNamesItsKey) {
  EXPECT_THAT(ErrorOf("scenario: missing.yaml\n"), HasSubstr("sweep.yaml:1:11: scenario: "));
  EXPECT_THAT(ErrorOf("scenario: base.yaml\naxes:\n  seed: [1, 2]\n"),
              StartsWith("sweep.yaml:3:3: axes.seed: the seeds are given by the sweep's `seeds`"));
  EXPECT_THAT(ErrorOf("scenario: base.yaml\naxes:\n  fleet.count: 3\n"),
              StartsWith("sweep.yaml:3:3: axes.fleet.count: must be a non-empty list"));
  EXPECT_THAT(ErrorOf("scenario: base.yaml\nseeds: {first: 1, count: 0}\n"),
              StartsWith("sweep.yaml:2:26: seeds.count: must be in [1, 100000]"));
  EXPECT_THAT(ErrorOf("scenario: base.yaml\nseeds: [4, 4]\n"),
              StartsWith("sweep.yaml:2:12: seeds[1]: repeated seed"));
  EXPECT_THAT(ErrorOf("scenario: base.yaml\nsedes: [4]\n"),
              StartsWith("sweep.yaml:2:1: sedes: unknown key; did you mean 'seeds'?"));
  EXPECT_THAT(ErrorOf("seeds: [4]\n"), StartsWith("sweep.yaml:1:1: scenario: missing (required)"));
}

TEST_F(SweepTest, RunsExpandInAFixedOrderAndEachScenarioCarriesItsValues) {
  const std::string text =
      "name: s\n"
      "scenario: base.yaml\n"
      "seeds: {first: 10, count: 2}\n"
      "axes:\n"
      "  fleet.count: [1, 3]\n"
      "  radio.loss: [0, 0.25]\n"
      "  wind.speed_mps: [4]\n";
  const SweepSpec spec = Parse(text);
  const SweepPlan plan = MakePlan(spec);
  ASSERT_EQ(plan.runs.size(), 8U);
  EXPECT_EQ(plan.axes, (std::vector<std::string>{"fleet.count", "radio.loss", "wind.speed_mps"}));
  // First axis slowest, seeds innermost.
  EXPECT_EQ(plan.runs[0].values, (std::vector<std::string>{"1", "0", "4"}));
  EXPECT_EQ(plan.runs[1].values, (std::vector<std::string>{"1", "0", "4"}));
  EXPECT_EQ(plan.runs[2].values, (std::vector<std::string>{"1", "0.25", "4"}));
  EXPECT_EQ(plan.runs[4].values, (std::vector<std::string>{"3", "0", "4"}));
  EXPECT_EQ(plan.runs[7].seed, 11U);
  EXPECT_EQ(plan.runs[7].combination, 3U);
  EXPECT_EQ(plan.runs[6].seed, 10U);
  // The run's scenario: the values and the seed set, nothing else changed.
  const std::string yaml = RunScenarioYaml(spec, plan.runs[7]);
  const Scenario scenario = ParseScenario(yaml, "run.yaml", "/nonexistent");
  EXPECT_EQ(scenario.seed, 11U);
  EXPECT_EQ(scenario.fleet.count, 3);
  EXPECT_DOUBLE_EQ(scenario.radio.loss, 0.25);
  EXPECT_DOUBLE_EQ(scenario.wind.speed_mps, 4.0);
  EXPECT_EQ(scenario.name, "base");
  ASSERT_EQ(scenario.fires.size(), 1U);
  EXPECT_DOUBLE_EQ(scenario.fires[0].start_s, 10.0);
  // The same sweep expands the same way, and the plan reads back whole.
  EXPECT_EQ(ToJson(MakePlan(Parse(text))), ToJson(plan));
  EXPECT_EQ(ToJson(PlanFromJson(nlohmann::json::parse(ToJson(plan).dump()))), ToJson(plan));
  EXPECT_EQ(CombinationLabel(plan.axes, plan.runs[7].values),
            "fleet.count=3 radio.loss=0.25 wind.speed_mps=4");
  EXPECT_EQ(RunName(7), "00007");
}

TEST_F(SweepTest, RelativeGeoJsonPathsBecomeAbsoluteInARunsScenario) {
  std::ofstream(dir_ / "area.geojson")
      << R"({"type":"Polygon","coordinates":[[[7.0,45.0],[7.010146,45.0],[7.010146,45.0045],)"
         R"([7.0,45.0045],[7.0,45.0]]]})";
  std::ofstream(dir_ / "geo.yaml") << "area: {geojson: area.geojson}\n"
                                      "fleet: {count: 1, launch: {lat: 44.9995, lon: 7.005}}\n";
  const SweepSpec spec = Parse("scenario: geo.yaml\nseeds: [5]\n");
  const SweepPlan plan = MakePlan(spec);
  ASSERT_EQ(plan.runs.size(), 1U);
  const Scenario scenario =
      ParseScenario(RunScenarioYaml(spec, plan.runs[0]), "elsewhere.yaml", "/nonexistent");
  ASSERT_TRUE(scenario.area_geojson.has_value());
  EXPECT_EQ(*scenario.area_geojson, (dir_ / "area.geojson").lexically_normal());
  EXPECT_EQ(scenario.seed, 5U);
}

// `fireswarm sweep scenarios/sweeps/x.yaml`: the sweep file named relative to
// the working directory; its runs' scenarios still name the GeoJSON absolutely.
TEST_F(SweepTest, ASweepFileNamedRelativelyGivesItsRunsAbsoluteGeoJsonPaths) {
  std::ofstream(dir_ / "area.geojson")
      << R"({"type":"Polygon","coordinates":[[[7.0,45.0],[7.010146,45.0],[7.010146,45.0045],)"
         R"([7.0,45.0045],[7.0,45.0]]]})";
  std::ofstream(dir_ / "geo.yaml") << "area: {geojson: area.geojson}\n"
                                      "fleet: {count: 1, launch: {lat: 44.9995, lon: 7.005}}\n";
  const std::filesystem::path relative_dir =
      std::filesystem::relative(dir_, std::filesystem::current_path());
  ASSERT_FALSE(relative_dir.is_absolute());
  const SweepSpec spec = ParseSweep("scenario: geo.yaml\nseeds: [5]\n", "sweep.yaml", relative_dir);
  const SweepPlan plan = MakePlan(spec);
  ASSERT_EQ(plan.runs.size(), 1U);
  const Scenario scenario =
      ParseScenario(RunScenarioYaml(spec, plan.runs[0]), "elsewhere.yaml", "/nonexistent");
  ASSERT_TRUE(scenario.area_geojson.has_value());
  EXPECT_TRUE(scenario.area_geojson->is_absolute()) << *scenario.area_geojson;
  EXPECT_EQ(*scenario.area_geojson, (dir_ / "area.geojson").lexically_normal());
}

TEST_F(SweepTest, SummaryOptionsDefaultToTheScenarios) {
  const SweepSpec spec = Parse("scenario: base.yaml\naxes:\n  duration_s: [40, 80]\n");
  EXPECT_DOUBLE_EQ(spec.confirm_within_s, 60.0);  // the base's duration, no expect
  EXPECT_DOUBLE_EQ(spec.duration_s, 80.0);
  EXPECT_EQ(spec.coverage_at_s, (std::vector<double>{20.0, 40.0, 60.0, 80.0}));
  EXPECT_EQ(spec.seeds, (std::vector<std::uint64_t>{3}));
  const SweepSpec given =
      Parse("scenario: base.yaml\nsummary: {confirm_within_s: 30, coverage_at_s: [10, 50]}\n");
  EXPECT_DOUBLE_EQ(given.confirm_within_s, 30.0);
  EXPECT_EQ(given.coverage_at_s, (std::vector<double>{10.0, 50.0}));
}

TEST(SweepStatistics, WilsonIntervalAndPercentiles) {
  const Rate rate = WilsonRate(8, 10);
  ASSERT_TRUE(rate.rate && rate.low && rate.high);
  EXPECT_DOUBLE_EQ(*rate.rate, 0.8);
  EXPECT_NEAR(*rate.low, 0.4902, 1e-4);  // Wilson 1927; e.g. statsmodels proportion_confint
  EXPECT_NEAR(*rate.high, 0.9433, 1e-4);
  const Rate all = WilsonRate(5, 5);
  EXPECT_DOUBLE_EQ(*all.high, 1.0);
  EXPECT_NEAR(*all.low, 0.5655, 1e-4);
  EXPECT_FALSE(WilsonRate(0, 0).rate.has_value());
  const std::vector<double> sorted{1.0, 2.0, 3.0, 4.0, 10.0};
  EXPECT_DOUBLE_EQ(*Percentile(sorted, 0.5), 3.0);
  EXPECT_DOUBLE_EQ(*Percentile(sorted, 0.9), 7.6);  // numpy.percentile(..., 90)
  EXPECT_DOUBLE_EQ(*Percentile(sorted, 0.0), 1.0);
  EXPECT_DOUBLE_EQ(*Percentile(sorted, 1.0), 10.0);
  EXPECT_FALSE(Percentile({}, 0.5).has_value());
}

// A report as `fireswarm run` writes it, with the keys the summary reads.
nlohmann::json FakeReport(const std::vector<std::optional<double>>& confirmed_s, double coverage,
                          int collisions) {
  nlohmann::json fires = nlohmann::json::array();
  for (const std::optional<double>& c : confirmed_s) {
    fires.push_back({{"confirmed_s", c ? nlohmann::json(*c) : nlohmann::json(nullptr)},
                     {"start_s", 10.0},
                     {"error_m", c ? nlohmann::json(*c / 10.0) : nlohmann::json(nullptr)}});
  }
  nlohmann::json collision_list = nlohmann::json::array();
  for (int k = 0; k < collisions; ++k) collision_list.push_back({{"t_s", 1.0}});
  return {{"fires", fires},
          {"coverage_over_time", {{0.0, 0.0}, {30.0, coverage / 2.0}, {60.0, coverage}}},
          {"collisions", collision_list},
          {"vehicles", {{"1", {{"airborne_s", 1800.0}}}, {"2", {{"airborne_s", 1800.0}}}}},
          {"min_separation_m", 25.0},
          {"false_tracks", nlohmann::json::array()},
          {"radio",
           {{"busy_fraction", 0.5},
            {"report_latency_s", {{"p50", 0.2}, {"p99", 0.9}}},
            {"retries", 3},
            {"reports_lost", 1}}}};
}

SweepPlan TwoByTwoPlan() {
  SweepPlan plan;
  plan.name = "t";
  plan.axes = {"fleet.count"};
  plan.confirm_within_s = 40.0;
  plan.coverage_at_s = {30.0, 60.0};
  plan.duration_s = 60.0;
  plan.runs = {{0, 0, 1, {"2"}}, {1, 0, 2, {"2"}}, {2, 1, 1, {"4"}}, {3, 1, 2, {"4"}}};
  return plan;
}

RunFiles DoneRun(std::size_t id, int exit_code, nlohmann::json report) {
  RunRecord record;
  record.id = id;
  record.status = RunStatus::kDone;
  record.exit_code = exit_code;
  return {record, std::move(report)};
}

TEST(SweepSummaryTest, CountsRatesAndDistributionsPerCombination) {
  const SweepPlan plan = TwoByTwoPlan();
  RunRecord crashed;
  crashed.id = 2;
  crashed.status = RunStatus::kCrashed;
  crashed.signal = 9;
  const std::vector<RunFiles> files{
      DoneRun(0, 0, FakeReport({30.0, 45.0}, 0.8, 0)),  // 20 and 35 s after ignition: within 40
      DoneRun(1, 1, FakeReport({20.0, std::nullopt}, 0.6, 1)),
      {crashed, std::nullopt},
      {std::nullopt, std::nullopt}};  // missing
  const SweepSummary summary = Summarize(plan, files);
  EXPECT_EQ(summary.runs, 4U);
  EXPECT_EQ(summary.done, 2U);
  EXPECT_EQ(summary.crashed, 1U);
  EXPECT_EQ(summary.missing, (std::vector<std::size_t>{3}));
  ASSERT_EQ(summary.groups.size(), 2U);
  const GroupSummary& two = summary.groups[0];
  EXPECT_EQ(two.label, "fleet.count=2");
  EXPECT_EQ(two.done, 2U);
  EXPECT_EQ(two.expectations_hold.successes, 1U);
  EXPECT_EQ(two.all_confirmed.successes, 1U);  // run 0 (20 and 35 s, within 40); run 1 missed one
  EXPECT_EQ(two.fires_confirmed.successes, 3U);
  EXPECT_EQ(two.fires_confirmed.trials, 4U);
  EXPECT_EQ(two.time_to_confirm_s, (std::vector<double>{10.0, 20.0, 35.0}));
  EXPECT_EQ(two.fused_error_m, (std::vector<double>{2.0, 3.0, 4.5}));
  ASSERT_EQ(two.coverage_at.size(), 2U);
  EXPECT_EQ(two.coverage_at[0], (std::vector<double>{0.3, 0.4}));
  EXPECT_EQ(two.coverage_at[1], (std::vector<double>{0.6, 0.8}));
  EXPECT_EQ(two.collisions, 1U);
  EXPECT_DOUBLE_EQ(two.flight_hours, 2.0);
  EXPECT_EQ(two.retries, 6U);
  EXPECT_DOUBLE_EQ(two.coverage_curve.back(), 0.7);
  const GroupSummary& four = summary.groups[1];
  EXPECT_EQ(four.crashed, 1U);
  EXPECT_EQ(four.missing, 1U);
  EXPECT_EQ(four.done, 0U);
  EXPECT_FALSE(four.all_confirmed.rate.has_value());
  // The JSON and CSV carry the same.
  const nlohmann::ordered_json json = ToJson(summary);
  EXPECT_EQ(json["groups"][0]["axes"]["fleet.count"], 2);
  EXPECT_EQ(json["groups"][0]["time_to_confirm_s"]["values"], nlohmann::json({10.0, 20.0, 35.0}));
  EXPECT_EQ(json["groups"][0]["time_to_confirm_s"]["p50"], 20.0);
  EXPECT_EQ(json["runs"]["missing"], 1);
  const std::string csv = SummaryCsv(summary);
  EXPECT_THAT(csv, StartsWith("fleet.count,runs,done,crashed,timed_out,errors,missing,"));
  EXPECT_THAT(csv, HasSubstr("\n2,2,2,0,0,0,0,0.5,0.5,"));
  EXPECT_THAT(csv, HasSubstr("\n4,2,0,1,0,0,1,,,"));
}

// The points of the polyline labelled `label` in the plot `id` of `html`.
std::vector<std::pair<double, double>> PlotPoints(const std::string& html, const std::string& id,
                                                  const std::string& label) {
  const std::size_t start =
      html.find("<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"plot\" id=\"" + id + "\"");
  EXPECT_NE(start, std::string::npos) << id;
  if (start == std::string::npos) return {};
  const std::size_t end = html.find("</svg>", start) + 6;
  const test::XmlDocument doc = test::ParseXml(html.substr(start, end - start));
  EXPECT_EQ(doc.error, "") << id;
  std::vector<std::pair<double, double>> points;
  for (const test::XmlElement* line : doc.Find("polyline")) {
    if (line->Attribute("data-label") != label) continue;
    std::istringstream in(line->Attribute("points"));
    std::string point;
    while (in >> point) {
      const std::size_t comma = point.find(',');
      points.emplace_back(std::stod(point.substr(0, comma)), std::stod(point.substr(comma + 1)));
    }
  }
  return points;
}

TEST(SweepSummaryTest, ThePlotsHoldTheSummarysNumbers) {
  const SweepPlan plan = TwoByTwoPlan();
  const std::vector<RunFiles> files{DoneRun(0, 0, FakeReport({30.0, 45.0}, 0.8, 0)),
                                    DoneRun(1, 0, FakeReport({20.0, std::nullopt}, 0.6, 0)),
                                    DoneRun(2, 0, FakeReport({12.5, 13.0}, 0.9, 0)),
                                    DoneRun(3, 0, FakeReport({60.0, 70.0}, 1.0, 0))};
  const SweepSummary summary = Summarize(plan, files);
  const std::string html = SummaryHtml(summary);
  for (const GroupSummary& group : summary.groups) {
    // CDF of time to confirm: steps at every value, up to confirmed / all fires.
    const auto cdf = PlotPoints(html, "time_to_confirm_cdf", group.label);
    ASSERT_EQ(cdf.size(), 2 * group.time_to_confirm_s.size()) << group.label;
    for (std::size_t i = 0; i < group.time_to_confirm_s.size(); ++i) {
      EXPECT_EQ(cdf[2 * i + 1].first, group.time_to_confirm_s[i]);
      EXPECT_DOUBLE_EQ(
          cdf[2 * i + 1].second,
          static_cast<double>(i + 1) / static_cast<double>(group.fires_confirmed.trials));
    }
    const auto error = PlotPoints(html, "fused_error_cdf", group.label);
    ASSERT_EQ(error.size(), 2 * group.fused_error_m.size());
    for (std::size_t i = 0; i < group.fused_error_m.size(); ++i) {
      EXPECT_EQ(error[2 * i + 1].first, group.fused_error_m[i]);
    }
    EXPECT_DOUBLE_EQ(error.back().second, 1.0);
    const auto coverage = PlotPoints(html, "coverage_over_time", group.label);
    ASSERT_EQ(coverage.size(), summary.curve_t_s.size());
    for (std::size_t k = 0; k < coverage.size(); ++k) {
      EXPECT_EQ(coverage[k].first, summary.curve_t_s[k]);
      EXPECT_EQ(coverage[k].second, group.coverage_curve[k]);
    }
  }
  EXPECT_DOUBLE_EQ(summary.groups[1].coverage_curve.back(), 0.95);
  EXPECT_THAT(html, HasSubstr("fleet.count=4"));
}

// The example sweeps under scenarios/sweeps/ load (and their axes check out).
TEST(RepositorySweeps, EveryExampleSweepLoads) {
  fs::path root;
  for (fs::path dir = fs::path(__FILE__).parent_path(); !dir.empty(); dir = dir.parent_path()) {
    if (fs::exists(dir / "scenarios" / "sweeps")) {
      root = dir;
      break;
    }
    if (dir == dir.root_path()) break;
  }
  ASSERT_FALSE(root.empty()) << "no scenarios/sweeps above " << __FILE__;
  int loaded = 0;
  for (const fs::directory_entry& entry : fs::directory_iterator(root / "scenarios" / "sweeps")) {
    if (entry.path().extension() != ".yaml") continue;
    SCOPED_TRACE(entry.path().string());
    EXPECT_NO_THROW(MakePlan(LoadSweep(entry.path())));
    ++loaded;
  }
  EXPECT_GE(loaded, 1);
}

}  // namespace
}  // namespace fireswarm::run
