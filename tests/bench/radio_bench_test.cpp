// The link targets, asserted on simulated figures (simulated time, so no
// wall-clock flakiness): 50 vehicles at 57,600 baud with a 5 ms turnaround.
#include "fireswarm/bench/radio_bench.hpp"

#include <gtest/gtest.h>

namespace fireswarm::bench {
namespace {

using radio::LinkMode;

constexpr int kFleet = 50;
constexpr double kSeconds = 60.0;
constexpr double kTargetTelemetryHz = 1.0;
constexpr double kTargetReportP99S = 2.0;

RadioBenchConfig Fleet(LinkMode mode, double loss = 0.0) {
  RadioBenchConfig config;
  config.vehicles = kFleet;
  config.seconds = kSeconds;
  config.mode = mode;
  config.baud = 57'600;
  config.turnaround = std::chrono::milliseconds(5);
  config.loss = loss;
  return config;
}

TEST(RadioBench, SlotsModeMeetsTheTargetsForFiftyVehicles) {
  const RadioBenchResult r = RunRadioBench(Fleet(LinkMode::kSlots));
  EXPECT_GE(r.telemetry_hz_min, kTargetTelemetryHz);
  EXPECT_LE(r.report_latency_p99_s, kTargetReportP99S);
  EXPECT_GT(r.reports_sent, 0U);
  EXPECT_EQ(r.reports_lost, 0U);
  EXPECT_EQ(r.collisions, 0U);
  EXPECT_EQ(r.missed_replies, 0U);
  EXPECT_LT(r.busy_fraction, 1.0);
}

TEST(RadioBench, SlotsModeLosesNoReportAtTenPercentLoss) {
  const RadioBenchResult r = RunRadioBench(Fleet(LinkMode::kSlots, 0.1));
  EXPECT_GT(r.missed_replies, 0U);
  EXPECT_EQ(r.reports_lost, 0U);
  EXPECT_EQ(r.collisions, 0U);
  EXPECT_LE(r.report_latency_p99_s, kTargetReportP99S);
}

TEST(RadioBench, PollModeIsCollisionFreeButSlowerPerVehicle) {
  const RadioBenchResult poll = RunRadioBench(Fleet(LinkMode::kPoll));
  const RadioBenchResult slots = RunRadioBench(Fleet(LinkMode::kSlots));
  EXPECT_EQ(poll.collisions, 0U);
  EXPECT_EQ(poll.reports_lost, 0U);
  // One turnaround pair and a Poll per reply: 50 vehicles do not fit in a second.
  EXPECT_LT(poll.telemetry_hz_min, slots.telemetry_hz_min);
}

TEST(RadioBench, MissionUploadCompletesWithAcks) {
  RadioBenchConfig config = Fleet(LinkMode::kSlots, 0.1);
  config.vehicles = 10;
  config.seconds = 20.0;
  config.mission_waypoints = 45;  // 3 chunks each
  const RadioBenchResult r = RunRadioBench(config);
  ASSERT_TRUE(r.mission_upload_s.has_value());
  EXPECT_EQ(r.requests_completed, 30U);
  EXPECT_EQ(r.requests_failed, 0U);
  EXPECT_EQ(r.reports_lost, 0U);
}

void ExpectSame(const RadioBenchResult& a, const RadioBenchResult& b) {
  EXPECT_EQ(a.sim_seconds, b.sim_seconds);
  EXPECT_EQ(a.busy_fraction, b.busy_fraction);
  EXPECT_EQ(a.payload_bytes_per_s, b.payload_bytes_per_s);
  EXPECT_EQ(a.telemetry_hz_min, b.telemetry_hz_min);
  EXPECT_EQ(a.telemetry_age_p99_s, b.telemetry_age_p99_s);
  EXPECT_EQ(a.report_latency_p50_s, b.report_latency_p50_s);
  EXPECT_EQ(a.report_latency_p99_s, b.report_latency_p99_s);
  EXPECT_EQ(a.reports_sent, b.reports_sent);
  EXPECT_EQ(a.transmissions, b.transmissions);
  EXPECT_EQ(a.missed_replies, b.missed_replies);
  EXPECT_EQ(a.duplicate_reports, b.duplicate_reports);
}

TEST(RadioBench, SameSeedSameFigures) {
  RadioBenchConfig config = Fleet(LinkMode::kSlots, 0.1);
  config.seconds = 20.0;
  config.seed = 42;
  ExpectSame(RunRadioBench(config), RunRadioBench(config));
  config.mode = LinkMode::kPoll;
  ExpectSame(RunRadioBench(config), RunRadioBench(config));

  RadioBenchConfig other = config;
  other.seed = 43;
  EXPECT_NE(RunRadioBench(config).report_latency_p50_s, RunRadioBench(other).report_latency_p50_s);
}

// Issue 21: 150 vehicles, more than one channel holds at 1 Hz, on three
// channels of 50 meet the same targets as 50 on one (10 % loss included).
TEST(RadioBench, ThreeChannelsCarryThreeTimesTheFleet) {
  RadioBenchConfig config = Fleet(LinkMode::kSlots, 0.1);
  config.vehicles = 3 * kFleet;
  config.channels = 3;
  config.seconds = 30.0;
  const RadioBenchResult r = RunRadioBench(config);
  ASSERT_EQ(r.per_channel.size(), 3U);
  for (const ChannelFigures& channel : r.per_channel) {
    EXPECT_EQ(channel.vehicles, kFleet);
    EXPECT_GT(channel.busy_fraction, 0.0);
    EXPECT_LE(channel.busy_fraction, r.busy_fraction);
  }
  EXPECT_GT(r.reports_sent, 0U);
  EXPECT_EQ(r.reports_lost, 0U);
  EXPECT_EQ(r.collisions, 0U) << "separate frequencies never collide";
  EXPECT_LE(r.report_latency_p99_s, kTargetReportP99S);
  EXPECT_GE(r.telemetry_hz_min, 0.85) << "1 Hz turns, 10 % of the replies lost";
  config.channels = 17;
  EXPECT_THROW(RunRadioBench(config), std::invalid_argument);
}

TEST(RadioBench, RejectsBadConfiguration) {
  RadioBenchConfig config;
  config.vehicles = 0;
  EXPECT_THROW(RunRadioBench(config), std::invalid_argument);
  config = RadioBenchConfig{};
  config.loss = 1.0;
  EXPECT_THROW(RunRadioBench(config), std::invalid_argument);
}

}  // namespace
}  // namespace fireswarm::bench
