// Whole runs on several radio channels (issue 21): the runner gives each channel
// its own simulated frequency; a dead one grounds only its own vehicles.
#include <gtest/gtest.h>

#include "fireswarm/run/runner.hpp"
#include "fireswarm/run/scenario.hpp"
#include "fireswarm/server/server.hpp"
#include "small_area.hpp"

namespace fireswarm::run {
namespace {

using test::SmallArea;

TEST(RunScenarioChannels, TwoChannelsCarryTheFleet) {
  std::size_t channels = 0;
  RunOptions options;
  options.on_step = [&](double /*t_s*/, const server::Server& server) {
    channels = server.scheduler().channel_count();
  };
  const Report report = RunScenario(SmallArea("radio: {channels: 2}\n"), options).report;
  EXPECT_EQ(channels, 2U);
  ASSERT_EQ(report.vehicles.size(), 2U);
  for (const int id : {1, 2}) {
    EXPECT_GT(report.vehicles.at(id).distance_m, 100.0) << "vehicle " << id;
    EXPECT_EQ(report.radio.telemetry_age_p50_p99_s.count(id), 1U) << "vehicle " << id;
  }
}

TEST(RunScenarioChannels, ADeadChannelGroundsItsVehiclesAndTheOtherFliesOn) {
  bool silent = false;
  bool other_silent = true;
  RunOptions options;
  options.on_step = [&](double /*t_s*/, const server::Server& server) {
    silent = server.scheduler().health(1).silent;
    other_silent = server.scheduler().health(0).silent;
  };
  // Channel 1 loses everything: its modem is as good as unplugged.
  const Report report = RunScenario(SmallArea("radio:\n  channels: 2\n  channel_overrides:\n"
                                              "    - {channel: 1, loss: 1.0, vehicles: [2]}\n"),
                                    options)
                            .report;
  EXPECT_TRUE(silent);
  EXPECT_FALSE(other_silent);
  EXPECT_EQ(report.vehicles.at(2).final_state, "idle");
  EXPECT_LT(report.vehicles.at(2).distance_m, 1.0);
  EXPECT_EQ(report.radio.telemetry_age_p50_p99_s.count(2), 0U);
  EXPECT_GT(report.vehicles.at(1).distance_m, 100.0);
  EXPECT_EQ(report.radio.telemetry_age_p50_p99_s.count(1), 1U);
}

}  // namespace
}  // namespace fireswarm::run
