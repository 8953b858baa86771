#include "fireswarm/radio/channel_loop.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <vector>

#include "radio/sim_net.hpp"

namespace fireswarm::radio {
namespace {

using std::chrono::milliseconds;

using sim_test::kTurnaround;
using sim_test::TestChannelConfig;

// What one radio heard, and when.
struct Heard {
  Nanos at;
  std::vector<std::uint8_t> bytes;
  friend bool operator==(const Heard&, const Heard&) = default;
};

// A master that wakes at `wakeup` once and sends `first` then `second` back to
// back; it records every step.
struct ScriptedMaster {
  Nanos wakeup = milliseconds(10);
  std::vector<std::uint8_t> first{1, 2, 3};
  std::vector<std::uint8_t> second{4, 5};
  std::vector<Heard> steps;

  Nanos NextWakeup() const { return wakeup; }
  std::vector<Burst> Step(Nanos now, std::span<const std::uint8_t> received) {
    steps.push_back(Heard{now, {received.begin(), received.end()}});
    if (now < wakeup) return {};
    wakeup = Nanos::max();
    const Nanos start = now + kTurnaround;
    const Nanos second_start = start + Airtime(first.size(), 57'600);
    return {Burst{start, first}, Burst{second_start, second}};
  }
};

// A vehicle that records what it heard and answers with `reply` when given.
struct RecordingVehicle {
  std::vector<std::uint8_t> reply;
  std::vector<Heard> heard;

  RadioStep AsStep() {
    return [this](Nanos now, std::span<const std::uint8_t> received) {
      heard.push_back(Heard{now, {received.begin(), received.end()}});
      if (reply.empty()) return std::vector<Burst>{};
      return std::vector<Burst>{Burst{now + kTurnaround, reply}};
    };
  }
};

TEST(ChannelLoop, MasterIsRadioZeroAndVehiclesFollowInOrder) {
  ScriptedMaster master;
  ChannelLoop loop(TestChannelConfig(), 1, MasterOf(master));
  RecordingVehicle a;
  RecordingVehicle b;
  EXPECT_EQ(loop.AddVehicle(a.AsStep()), 1U);
  EXPECT_EQ(loop.AddVehicle(b.AsStep()), 2U);
  EXPECT_EQ(loop.channel().radio_count(), 3U);
}

TEST(ChannelLoop, DeliversTheMastersBurstsInOrderToEveryVehicleAtTheirEnd) {
  ScriptedMaster master;
  ChannelLoop loop(TestChannelConfig(), 1, MasterOf(master));
  RecordingVehicle a;
  RecordingVehicle b;
  loop.AddVehicle(a.AsStep());
  loop.AddVehicle(b.AsStep());
  loop.RunUntil(milliseconds(100));

  const Nanos first_end = milliseconds(15) + Airtime(3, 57'600);
  const Nanos second_end = first_end + Airtime(2, 57'600);
  const std::vector<Heard> expected{{first_end, {1, 2, 3}}, {second_end, {4, 5}}};
  EXPECT_EQ(a.heard, expected);
  EXPECT_EQ(b.heard, expected);
  // The master steps at every event time, hearing nothing of its own.
  ASSERT_EQ(master.steps.size(), 3U);
  EXPECT_EQ(master.steps[0].at, milliseconds(10));
  for (const Heard& step : master.steps) EXPECT_TRUE(step.bytes.empty());
  EXPECT_EQ(loop.channel().now(), milliseconds(100));
}

TEST(ChannelLoop, AReplyReachesTheMasterAndTheOtherVehiclesButNotItsSender) {
  ScriptedMaster master;
  master.second.clear();  // an empty burst puts nothing on the air
  ChannelLoop loop(TestChannelConfig(), 1, MasterOf(master));
  RecordingVehicle quiet;
  RecordingVehicle talker;
  talker.reply = {9, 8, 7, 6};
  loop.AddVehicle(quiet.AsStep());
  loop.AddVehicle(talker.AsStep());
  loop.RunUntil(milliseconds(100));

  const Nanos request_end = milliseconds(15) + Airtime(3, 57'600);
  const Nanos reply_end = request_end + kTurnaround + Airtime(4, 57'600);
  ASSERT_EQ(master.steps.size(), 3U);
  EXPECT_EQ(master.steps.back(), (Heard{reply_end, {9, 8, 7, 6}}));
  EXPECT_EQ(quiet.heard, (std::vector<Heard>{{request_end, {1, 2, 3}}, {reply_end, {9, 8, 7, 6}}}));
  EXPECT_EQ(talker.heard, (std::vector<Heard>{{request_end, {1, 2, 3}}}));
}

TEST(ChannelLoop, TwoVehiclesAnsweringAtOnceCollideAndNobodyHearsThem) {
  ScriptedMaster master;
  master.second.clear();
  ChannelLoop loop(TestChannelConfig(), 1, MasterOf(master));
  RecordingVehicle a;
  RecordingVehicle b;
  a.reply = {1, 1, 1};
  b.reply = {2, 2};
  loop.AddVehicle(a.AsStep());
  loop.AddVehicle(b.AsStep());
  loop.RunUntil(milliseconds(100));

  EXPECT_EQ(loop.channel().stats().collisions, 2U);
  for (const Heard& step : master.steps) EXPECT_TRUE(step.bytes.empty());
  EXPECT_EQ(a.heard.size(), 1U);
  EXPECT_EQ(b.heard.size(), 1U);
}

TEST(ChannelLoop, NextEventTimeIsTheEarlierOfWakeupAndTransmissionEnd) {
  ScriptedMaster master;
  ChannelLoop loop(TestChannelConfig(), 1, MasterOf(master));
  EXPECT_EQ(loop.NextEventTime(), milliseconds(10));
  loop.StepAt(milliseconds(10));
  // The master sleeps now: the end of its first burst is next.
  EXPECT_EQ(loop.NextEventTime(), milliseconds(15) + Airtime(3, 57'600));
  loop.RunUntil(milliseconds(50));
  EXPECT_EQ(loop.NextEventTime(), Nanos::max());
}

TEST(ChannelLoop, AWakeupInThePastIsDueAtTheChannelsTime) {
  ScriptedMaster master;
  master.wakeup = Nanos::max();
  ChannelLoop loop(TestChannelConfig(), 1, MasterOf(master));
  loop.RunUntil(milliseconds(30));
  master.wakeup = milliseconds(10);  // a request queued between calls
  EXPECT_EQ(loop.NextEventTime(), milliseconds(30));
  loop.RunUntil(milliseconds(30));
  ASSERT_EQ(master.steps.size(), 1U);
  EXPECT_EQ(master.steps[0].at, milliseconds(30));
}

TEST(ChannelLoop, RunUntilStopsAtTheEndAndLeavesLaterEventsForLater) {
  ScriptedMaster master;
  ChannelLoop loop(TestChannelConfig(), 1, MasterOf(master));
  RecordingVehicle a;
  loop.AddVehicle(a.AsStep());
  loop.RunUntil(milliseconds(9));
  EXPECT_TRUE(master.steps.empty());
  EXPECT_EQ(loop.channel().now(), milliseconds(9));
  loop.RunUntil(milliseconds(10));  // an event exactly at the end runs
  EXPECT_EQ(master.steps.size(), 1U);
  EXPECT_TRUE(a.heard.empty());
}

TEST(ChannelLoop, AWakeupStuckAtOneInstantThrowsInsteadOfHanging) {
  ChannelLoop loop(TestChannelConfig(), 1,
                   LoopMaster{[] { return milliseconds(1); },
                              [](Nanos /*now*/, std::span<const std::uint8_t> /*received*/) {
                                return std::vector<Burst>{};
                              }});
  EXPECT_THROW(loop.RunUntil(milliseconds(2)), std::logic_error);
}

TEST(ChannelLoop, SameSeedSameCallsSameBytesAndTimes) {
  const auto run = [](std::uint64_t seed) {
    ScriptedMaster master;
    ChannelLoop loop(TestChannelConfig(/*loss=*/0.5), seed, MasterOf(master));
    std::vector<RecordingVehicle> vehicles(8);
    for (RecordingVehicle& v : vehicles) {
      v.reply = {7};
      loop.AddVehicle(v.AsStep());
    }
    loop.RunUntil(milliseconds(200));
    std::vector<Heard> log = master.steps;
    for (const RecordingVehicle& v : vehicles)
      log.insert(log.end(), v.heard.begin(), v.heard.end());
    return log;
  };
  EXPECT_EQ(run(3), run(3));
  EXPECT_NE(run(3), run(4));
}

}  // namespace
}  // namespace fireswarm::radio
