// Runs the real `fireswarm` executable for the end-to-end tests in tests/app/.
// The test suite sets FIRESWARM_BIN to build/bin/fireswarm.
#pragma once

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

namespace fireswarm::app {

/// A tiny scenario: 800 m x 500 m, two drones, one fire near the launch (tracked
/// within 120 s); `duration_s` and the `expect:` block's lines vary per test.
inline std::string TinyScenario(double duration_s,
                                const std::string& expect = "  no_collisions: true\n") {
  return "name: tiny\n"
         "seed: 7\n"
         "duration_s: " +
         std::to_string(duration_s) +
         "\n"
         "area:\n"
         "  polygon: [[7.0, 45.0], [7.010146, 45.0], [7.010146, 45.0045], [7.0, 45.0045]]\n"
         "fleet:\n"
         "  count: 2\n"
         "  launch: {lat: 44.9995, lon: 7.005}\n"
         "fires:\n"
         "  - {lat: 45.00230, lon: 7.00480}\n"
         "expect:\n" +
         expect;
}

struct RunResult {
  int exit_code = -1;
  std::vector<std::string> lines;  // stdout and stderr, line by line
};

// Runs `fireswarm <arguments>` through the shell and collects its output.
inline RunResult RunFireswarm(const std::string& arguments) {
  const char* binary = std::getenv("FIRESWARM_BIN");
  if (binary == nullptr) ADD_FAILURE() << "FIRESWARM_BIN is not set (ctest sets it)";
  const std::string command =
      std::string("'") + (binary ? binary : "fireswarm") + "' " + arguments + " 2>&1";
  RunResult result;
  std::FILE* pipe = popen(command.c_str(), "r");
  if (pipe == nullptr) return result;
  std::string line;
  for (int c = std::fgetc(pipe); c != EOF; c = std::fgetc(pipe)) {
    if (c == '\n') {
      result.lines.push_back(line);
      line.clear();
    } else {
      line.push_back(static_cast<char>(c));
    }
  }
  if (!line.empty()) result.lines.push_back(line);
  const int status = pclose(pipe);
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

/// A fixture with a scratch directory of its own per test, removed afterwards.
class CommandTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           ("fireswarm_" + std::string(test->test_suite_name()) + "_" + std::to_string(getpid()) +
            "_" + test->name());
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::string PathOf(const std::string& name) const { return (dir_ / name).string(); }

  std::filesystem::path dir_;
};

}  // namespace fireswarm::app
