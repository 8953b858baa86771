// `fireswarm sweep` end to end through the built executable, its runs real child
// `fireswarm run` processes: the same summary, byte for byte, from one job, two
// jobs and the Slurm path's chunks (the emitted script run by hand); a run killed
// mid-sweep recorded as crashed and the sweep going on; a run over --timeout
// recorded; a sweep killed outright resuming without doing a recorded run again;
// bad flags and a bad axis key exiting 2 with file, line and key.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "app/fireswarm_process.hpp"
#include "app/run_fireswarm.hpp"

namespace fireswarm::app {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

constexpr auto kSweepDeadline = std::chrono::seconds(300);

class SweepCommandTest : public CommandTest {
 protected:
  void SetUp() override {
    CommandTest::SetUp();
    std::ofstream(PathOf("tiny.yaml")) << TinyScenario(kDurationS, "  min_coverage: 0.01\n");
  }

  // A sweep of the tiny scenario: fleet.count 1 and 2, `seeds` seeds each.
  std::string WriteSweep(int seeds, const std::string& name = "sweep.yaml") const {
    std::ofstream(PathOf(name)) << "name: tiny_sweep\n"
                                   "scenario: tiny.yaml\n"
                                   "seeds: {first: 1, count: "
                                << seeds
                                << "}\n"
                                   "axes:\n"
                                   "  fleet.count: [1, 2]\n"
                                   "summary: {coverage_at_s: [20, 40]}\n";
    return PathOf(name);
  }

  static std::string Summaries(const fs::path& out) {
    return FileText(out / "summary.json") + FileText(out / "summary.csv") +
           FileText(out / "summary.html");
  }

  static std::string FileText(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }

  static bool Mentions(const RunResult& result, const std::string& text) {
    for (const std::string& line : result.lines) {
      if (line.find(text) != std::string::npos) return true;
    }
    return false;
  }

  static std::string Output(const RunResult& result) {
    std::string all;
    for (const std::string& line : result.lines) all += line + "\n";
    return all;
  }

  static nlohmann::json Record(const fs::path& out, const std::string& run) {
    return nlohmann::json::parse(FileText(out / "runs" / run / "record.json"));
  }

  static constexpr double kDurationS = 60.0;
};

TEST_F(SweepCommandTest, TheSummaryIsTheSameFromOneJobTwoJobsAndTheSlurmChunks) {
  const std::string sweep = WriteSweep(2);
  const RunResult one = RunFireswarm("sweep " + sweep + " --out " + PathOf("one") + " --jobs 1");
  ASSERT_EQ(one.exit_code, 0) << Output(one);
  const RunResult two = RunFireswarm("sweep " + sweep + " --out " + PathOf("two") + " --jobs 2");
  ASSERT_EQ(two.exit_code, 0) << Output(two);
  EXPECT_FALSE(FileText(dir_ / "one" / "summary.json").empty());
  EXPECT_EQ(Summaries(dir_ / "one"), Summaries(dir_ / "two"));
  for (const char* run : {"00000", "00001", "00002", "00003"}) {
    for (const char* file : {"scenario.yaml", "report.json", "record.json", "output.txt"}) {
      EXPECT_TRUE(fs::is_regular_file(dir_ / "two" / "runs" / run / file)) << run << "/" << file;
    }
    EXPECT_EQ(Record(dir_ / "two", run)["status"], "done");
  }
  const nlohmann::json summary = nlohmann::json::parse(FileText(dir_ / "one" / "summary.json"));
  ASSERT_EQ(summary["groups"].size(), 2U);
  EXPECT_EQ(summary["groups"][1]["label"], "fleet.count=2");
  EXPECT_EQ(summary["groups"][1]["runs"]["done"], 2);
  EXPECT_EQ(summary["runs"]["done"], 4);
  // The page has its three plots, a line per combination in each.
  const std::string html = FileText(dir_ / "one" / "summary.html");
  for (const char* plot : {"time_to_confirm_cdf", "coverage_over_time", "fused_error_cdf"}) {
    const std::size_t at = html.find(std::string("id=\"") + plot + "\"");
    ASSERT_NE(at, std::string::npos) << plot;
    const std::string svg = html.substr(at, html.find("</svg>", at) - at);
    EXPECT_THAT(svg, HasSubstr("data-label=\"fleet.count=1\"")) << plot;
    EXPECT_THAT(svg, HasSubstr("data-label=\"fleet.count=2\"")) << plot;
  }

  // The Slurm path without Slurm: the emitted script run once per array task.
  const RunResult emit =
      RunFireswarm("sweep " + sweep + " --out " + PathOf("slurm") + " --emit slurm --chunks 2");
  ASSERT_EQ(emit.exit_code, 0) << Output(emit);
  const std::string script = FileText(dir_ / "slurm" / "sweep.sbatch");
  EXPECT_THAT(script, HasSubstr("#SBATCH --array=0-1\n"));
  EXPECT_THAT(script, HasSubstr("--chunk \"$SLURM_ARRAY_TASK_ID\" --chunks 2"));
  EXPECT_FALSE(fs::exists(dir_ / "slurm" / "summary.json"));
  for (const char* task : {"1", "0"}) {
    const std::string command = "SLURM_ARRAY_TASK_ID=" + std::string(task) + " bash '" +
                                (dir_ / "slurm" / "sweep.sbatch").string() + "' >/dev/null 2>&1";
    EXPECT_EQ(std::system(command.c_str()), 0) << task;
  }
  const RunResult collect = RunFireswarm("sweep --collect " + PathOf("slurm"));
  ASSERT_EQ(collect.exit_code, 0) << Output(collect);
  EXPECT_EQ(Summaries(dir_ / "slurm"), Summaries(dir_ / "one"));
}

TEST_F(SweepCommandTest, ARunKilledMidSweepIsRecordedAndTheSweepGoesOn) {
  const std::string sweep = WriteSweep(1);
  FireswarmProcess process({"sweep", sweep, "--out", PathOf("out"), "--jobs", "1"});
  const auto deadline = std::chrono::steady_clock::now() + kSweepDeadline;
  pid_t child = -1;
  while (const auto line = process.ReadLine(deadline)) {
    if (line->starts_with("run 00000 started (pid ")) {
      child = std::stoi(line->substr(std::string("run 00000 started (pid ").size()));
      break;
    }
  }
  ASSERT_GT(child, 0);
  ASSERT_EQ(::kill(child, SIGKILL), 0);
  const RunResult result = process.Finish(deadline);
  EXPECT_EQ(result.exit_code, 1) << Output(result);
  const nlohmann::json crashed = Record(dir_ / "out", "00000");
  EXPECT_EQ(crashed["status"], "crashed");
  EXPECT_EQ(crashed["signal"], SIGKILL);
  EXPECT_THAT(crashed["detail"].get<std::string>(), HasSubstr("SIGKILL"));
  EXPECT_EQ(Record(dir_ / "out", "00001")["status"], "done");
  const nlohmann::json summary = nlohmann::json::parse(FileText(dir_ / "out" / "summary.json"));
  EXPECT_EQ(summary["runs"]["crashed"], 1);
  EXPECT_EQ(summary["runs"]["done"], 1);
  EXPECT_EQ(summary["groups"][0]["runs"]["crashed"], 1);
  // Recorded is done: the same command again runs nothing.
  const RunResult again = RunFireswarm("sweep " + sweep + " --out " + PathOf("out"));
  EXPECT_TRUE(Mentions(again, "2 already recorded, 0 to run")) << Output(again);
}

TEST_F(SweepCommandTest, ARunOverTheTimeoutIsKilledAndRecorded) {
  const std::string sweep = WriteSweep(1);
  const RunResult result =
      RunFireswarm("sweep " + sweep + " --out " + PathOf("out") + " --jobs 2 --timeout 0.001");
  EXPECT_EQ(result.exit_code, 1) << Output(result);
  const nlohmann::json record = Record(dir_ / "out", "00001");
  EXPECT_EQ(record["status"], "timed_out");
  EXPECT_THAT(record["detail"].get<std::string>(), HasSubstr("--timeout 0.001"));
  const nlohmann::json summary = nlohmann::json::parse(FileText(dir_ / "out" / "summary.json"));
  EXPECT_EQ(summary["runs"]["timed_out"], 2);
  EXPECT_THAT(FileText(dir_ / "out" / "summary.csv"), HasSubstr("\n2,1,0,0,1,0,0,,,"));
}

TEST_F(SweepCommandTest, ASweepKilledOutrightResumesWithoutRedoingARecordedRun) {
  const std::string sweep = WriteSweep(2);
  {
    FireswarmProcess process({"sweep", sweep, "--out", PathOf("out"), "--jobs", "1"});
    const auto deadline = std::chrono::steady_clock::now() + kSweepDeadline;
    bool first_done = false;
    while (const auto line = process.ReadLine(deadline)) {
      if (line->starts_with("run 00000 done")) {
        first_done = true;
        break;
      }
    }
    ASSERT_TRUE(first_done);
    process.Kill();  // SIGKILL: no clean-up; its running child dies with it
  }
  const std::string first_record = FileText(dir_ / "out" / "runs" / "00000" / "record.json");
  ASSERT_FALSE(first_record.empty());
  EXPECT_FALSE(fs::exists(dir_ / "out" / "summary.json"));
  const RunResult resumed =
      RunFireswarm("sweep " + sweep + " --out " + PathOf("out") + " --jobs 2");
  ASSERT_EQ(resumed.exit_code, 0) << Output(resumed);
  EXPECT_FALSE(Mentions(resumed, "run 00000 started")) << Output(resumed);
  EXPECT_TRUE(Mentions(resumed, "run 00003 started")) << Output(resumed);
  // Not done twice: the record (its wall time too) is the first attempt's.
  EXPECT_EQ(FileText(dir_ / "out" / "runs" / "00000" / "record.json"), first_record);
  // Nothing lost: the summary is an uninterrupted sweep's.
  const RunResult fresh =
      RunFireswarm("sweep " + sweep + " --out " + PathOf("fresh") + " --jobs 2");
  ASSERT_EQ(fresh.exit_code, 0) << Output(fresh);
  EXPECT_EQ(Summaries(dir_ / "out"), Summaries(dir_ / "fresh"));
}

TEST_F(SweepCommandTest, BadInputExitsTwoNamingTheProblem) {
  const std::string sweep = WriteSweep(1);
  std::ofstream(PathOf("bad.yaml")) << "scenario: tiny.yaml\naxes:\n  fleet.count: [1]\n"
                                       "  fleet.cuont: [2]\n";
  const RunResult bad_axis = RunFireswarm("sweep " + PathOf("bad.yaml") + " --out " + PathOf("o"));
  EXPECT_EQ(bad_axis.exit_code, 2);
  EXPECT_TRUE(Mentions(bad_axis, PathOf("bad.yaml") + ":4:3: axes.fleet.cuont: not a scenario key"))
      << Output(bad_axis);
  EXPECT_FALSE(fs::exists(dir_ / "o"));
  for (const std::string& args :
       {sweep, sweep + " --out " + PathOf("o") + " --jobs 0",
        sweep + " --out " + PathOf("o") + " --emit pbs",
        sweep + " --out " + PathOf("o") + " --chunk 1",
        sweep + " --out " + PathOf("o") + " --chunk 2 --chunks 2",
        sweep + " --out " + PathOf("o") + " --timeout -1",
        std::string("--collect ") + PathOf("nothing"), "--collect " + PathOf("o") + " " + sweep}) {
    const RunResult result = RunFireswarm("sweep " + args);
    EXPECT_EQ(result.exit_code, 2) << args << "\n" << Output(result);
  }
  // A directory holding another sweep's runs is refused.
  ASSERT_EQ(RunFireswarm("sweep " + sweep + " --out " + PathOf("o") + " --emit slurm").exit_code,
            0);
  const RunResult other =
      RunFireswarm("sweep " + WriteSweep(2, "other.yaml") + " --out " + PathOf("o"));
  EXPECT_EQ(other.exit_code, 2);
  EXPECT_TRUE(Mentions(other, "holds the runs of another sweep")) << Output(other);
  // --collect names the runs still missing.
  const RunResult partial = RunFireswarm("sweep --collect " + PathOf("o"));
  EXPECT_EQ(partial.exit_code, 1);
  EXPECT_TRUE(Mentions(partial, "runs without a result: 00000 00001")) << Output(partial);
}

}  // namespace
}  // namespace fireswarm::app
