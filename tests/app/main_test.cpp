// The `fireswarm` executable's contract: subcommands listed by --help, --help on
// each, and exit 2 naming the problem for anything it does not know.
#include <gtest/gtest.h>

#include <string>

#include "app/run_fireswarm.hpp"

namespace fireswarm::app {
namespace {

bool Contains(const RunResult& run, const std::string& text) {
  for (const std::string& line : run.lines) {
    if (line.find(text) != std::string::npos) return true;
  }
  return false;
}

TEST(FireswarmMain, HelpListsEverySubcommand) {
  const RunResult help = RunFireswarm("--help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_TRUE(Contains(help, "radio-bench"));
  EXPECT_TRUE(Contains(help, "radio-decode"));
}

TEST(FireswarmMain, EverySubcommandHasHelp) {
  for (const std::string command :
       {"params", "plan", "radio-bench", "radio-decode", "sim-bench", "sweep", "vehicle"}) {
    const RunResult help = RunFireswarm(command + " --help");
    EXPECT_EQ(help.exit_code, 0) << command;
    EXPECT_TRUE(Contains(help, "usage: fireswarm " + command)) << command;
  }
}

TEST(FireswarmMain, UnknownSubcommandOrNoneExitsTwo) {
  const RunResult unknown = RunFireswarm("fly-to-the-moon");
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_TRUE(Contains(unknown, "unknown subcommand 'fly-to-the-moon'"));
  EXPECT_EQ(RunFireswarm("").exit_code, 2);
}

}  // namespace
}  // namespace fireswarm::app
