#include "fireswarm/radio/channel.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "radio/sim_net.hpp"

namespace fireswarm::radio {
namespace {

using std::chrono::milliseconds;

using sim_test::kTurnaround;
using sim_test::TestChannelConfig;
constexpr Nanos kHundredBytes{17'361'112};  // 100 bytes at 57,600 baud 8N1

std::vector<std::uint8_t> Pattern(std::size_t size, std::uint8_t first = 0) {
  std::vector<std::uint8_t> bytes(size);
  std::iota(bytes.begin(), bytes.end(), first);
  return bytes;
}

std::vector<std::uint8_t> Drained(SharedChannel& channel, RadioId radio) {
  std::vector<std::uint8_t> out;
  channel.Drain(radio, out);
  return out;
}

// Sends one burst as early as the turnaround allows and resolves it.
void SendAndResolve(SharedChannel& channel, RadioId radio, const std::vector<std::uint8_t>& bytes) {
  const Nanos now = channel.now();
  channel.AdvanceTo(channel.Transmit(radio, now, now + kTurnaround, bytes));
}

// Half-width of a 5-sigma band around the mean of a binomial(n, p) count.
double FiveSigma(double n, double p) {
  return 5.0 * std::sqrt(n * p * (1.0 - p));
}

TEST(SharedChannel, HundredByteFrameOccupiesExactAirtime) {
  SharedChannel channel(TestChannelConfig(), 1);
  const RadioId sender = channel.AddRadio();
  channel.AddRadio();
  EXPECT_EQ(channel.AirtimeOf(100), kHundredBytes);
  const Nanos end = channel.Transmit(sender, Nanos{0}, kTurnaround, Pattern(100));
  EXPECT_EQ(end, kTurnaround + kHundredBytes);
  EXPECT_EQ(channel.NextEventTime(), end);
}

TEST(SharedChannel, DeliversAtTheEndTimeNotBefore) {
  SharedChannel channel(TestChannelConfig(), 1);
  const RadioId sender = channel.AddRadio();
  const RadioId receiver = channel.AddRadio();
  const Nanos end = channel.Transmit(sender, Nanos{0}, kTurnaround, Pattern(100));
  channel.AdvanceTo(end - Nanos{1});
  EXPECT_TRUE(Drained(channel, receiver).empty());
  EXPECT_EQ(channel.NextEventTime(), end);
  channel.AdvanceTo(end);
  EXPECT_EQ(Drained(channel, receiver), Pattern(100));
  EXPECT_EQ(channel.NextEventTime(), std::nullopt);
  EXPECT_TRUE(Drained(channel, receiver).empty());  // Drain empties the inbox
}

TEST(SharedChannel, NextEventTimeIsTheEarliestEndAndInboxFollowsEndOrder) {
  SharedChannel channel(TestChannelConfig(), 1);
  const RadioId late = channel.AddRadio();
  const RadioId early = channel.AddRadio();
  const RadioId listener = channel.AddRadio();
  // Submitted in the opposite order of their times.
  const Nanos late_end = channel.Transmit(late, Nanos{0}, milliseconds(100), Pattern(10, 100));
  const Nanos early_end = channel.Transmit(early, Nanos{0}, kTurnaround, Pattern(10, 0));
  EXPECT_EQ(channel.NextEventTime(), early_end);
  channel.AdvanceTo(early_end);
  EXPECT_EQ(channel.NextEventTime(), late_end);
  channel.AdvanceTo(late_end + milliseconds(1));
  std::vector<std::uint8_t> expected = Pattern(10, 0);
  const std::vector<std::uint8_t> second = Pattern(10, 100);
  expected.insert(expected.end(), second.begin(), second.end());
  EXPECT_EQ(Drained(channel, listener), expected);
}

TEST(SharedChannel, StartBeforeTheTurnaroundThrows) {
  SharedChannel channel(TestChannelConfig(), 1);
  const RadioId radio = channel.AddRadio();
  const Nanos now = milliseconds(10);
  channel.AdvanceTo(now);
  EXPECT_THROW(channel.Transmit(radio, now, now + kTurnaround - Nanos{1}, Pattern(5)),
               std::logic_error);
  EXPECT_NO_THROW(channel.Transmit(radio, now, now + kTurnaround, Pattern(5)));
}

TEST(SharedChannel, TransmittingRadioAppendsBackToBackWithoutTurnaround) {
  SharedChannel channel(TestChannelConfig(), 1);
  const RadioId sender = channel.AddRadio();
  const RadioId receiver = channel.AddRadio();
  const Nanos first_end = channel.Transmit(sender, Nanos{0}, kTurnaround, Pattern(100));
  const Nanos decided = first_end - milliseconds(1);  // less than a turnaround before
  channel.AdvanceTo(decided);
  EXPECT_THROW(channel.Transmit(sender, decided, first_end - Nanos{1}, Pattern(5)),
               std::logic_error);  // would overlap its own transmission
  const Nanos second_end = channel.Transmit(sender, decided, first_end, Pattern(5, 100));
  channel.AdvanceTo(second_end);
  std::vector<std::uint8_t> expected = Pattern(100);
  const std::vector<std::uint8_t> second = Pattern(5, 100);
  expected.insert(expected.end(), second.begin(), second.end());
  EXPECT_EQ(Drained(channel, receiver), expected);
  EXPECT_EQ(channel.stats().collisions, 0U);
}

TEST(SharedChannel, TimeBeforeTheChannelTimeThrows) {
  SharedChannel channel(TestChannelConfig(), 1);
  const RadioId radio = channel.AddRadio();
  channel.AdvanceTo(milliseconds(20));
  EXPECT_THROW(channel.Transmit(radio, milliseconds(10), milliseconds(30), Pattern(5)),
               std::logic_error);
  EXPECT_THROW(channel.AdvanceTo(milliseconds(10)), std::logic_error);
  EXPECT_THROW(channel.Transmit(7, milliseconds(20), milliseconds(30), Pattern(5)),
               std::out_of_range);
}

TEST(SharedChannel, EmptyBurstPutsNothingOnTheAir) {
  SharedChannel channel(TestChannelConfig(), 1);
  const RadioId radio = channel.AddRadio();
  EXPECT_EQ(channel.Transmit(radio, Nanos{0}, kTurnaround, {}), kTurnaround);
  EXPECT_EQ(channel.NextEventTime(), std::nullopt);
}

TEST(SharedChannel, OverlappingTransmissionsAreLostToEveryReceiver) {
  SharedChannel channel(TestChannelConfig(), 1);
  const RadioId a = channel.AddRadio();
  const RadioId b = channel.AddRadio();
  const RadioId c = channel.AddRadio();
  const RadioId d = channel.AddRadio();
  channel.Transmit(a, Nanos{0}, kTurnaround, Pattern(100));
  const Nanos end = channel.Transmit(b, milliseconds(10), milliseconds(15), Pattern(100));
  channel.AdvanceTo(end);
  for (const RadioId radio : {a, b, c, d}) EXPECT_TRUE(Drained(channel, radio).empty());
  EXPECT_EQ(channel.stats().collisions, 2U);
  EXPECT_EQ(channel.stats().transmissions, 2U);
  EXPECT_EQ(channel.stats().receptions, 0U);
}

TEST(SharedChannel, TouchingTransmissionsDoNotCollide) {
  SharedChannel channel(TestChannelConfig(), 1);
  const RadioId a = channel.AddRadio();
  const RadioId b = channel.AddRadio();
  const RadioId c = channel.AddRadio();
  const Nanos a_end = channel.Transmit(a, Nanos{0}, kTurnaround, Pattern(100));
  const Nanos b_end = channel.Transmit(b, Nanos{0}, a_end, Pattern(20, 200));  // [a_end, b_end)
  channel.AdvanceTo(b_end);
  EXPECT_EQ(channel.stats().collisions, 0U);
  EXPECT_EQ(Drained(channel, a), Pattern(20, 200));
  EXPECT_EQ(Drained(channel, b), Pattern(100));
  EXPECT_EQ(Drained(channel, c).size(), 120U);
}

TEST(SharedChannel, ThreeWayOverlapsLoseAllThree) {
  SharedChannel channel(TestChannelConfig(), 1);
  const RadioId a = channel.AddRadio();
  const RadioId b = channel.AddRadio();
  const RadioId c = channel.AddRadio();
  const RadioId listener = channel.AddRadio();
  // All three overlap one another.
  channel.Transmit(a, Nanos{0}, milliseconds(5), Pattern(100));
  channel.Transmit(b, Nanos{0}, milliseconds(6), Pattern(100));
  channel.Transmit(c, Nanos{0}, milliseconds(7), Pattern(100));
  // A chain: b overlaps a and c, but a and c do not touch; all three are still lost.
  const Nanos a_start = milliseconds(100);
  const Nanos a_end = channel.Transmit(a, Nanos{0}, a_start, Pattern(100));
  channel.Transmit(b, Nanos{0}, a_end - milliseconds(1), Pattern(100));
  const Nanos c_end = channel.Transmit(c, Nanos{0}, a_end + milliseconds(1), Pattern(100));
  channel.AdvanceTo(c_end);
  EXPECT_EQ(channel.stats().collisions, 6U);
  EXPECT_TRUE(Drained(channel, listener).empty());
  // The air is clean again afterwards.
  SendAndResolve(channel, a, Pattern(10));
  EXPECT_EQ(Drained(channel, listener), Pattern(10));
}

TEST(SharedChannel, RadioTransmittingDuringATransmissionDoesNotHearIt) {
  SharedChannel channel(TestChannelConfig(), 1);
  const RadioId long_talker = channel.AddRadio();
  const RadioId short_talker = channel.AddRadio();
  const Nanos end = channel.Transmit(long_talker, Nanos{0}, kTurnaround, Pattern(200));
  // The short burst lies entirely inside the long one.
  channel.Transmit(short_talker, Nanos{0}, milliseconds(10), Pattern(2));
  channel.AdvanceTo(end);
  EXPECT_TRUE(Drained(channel, short_talker).empty());
  EXPECT_TRUE(Drained(channel, long_talker).empty());
}

TEST(SharedChannel, TransmitterDoesNotHearItself) {
  SharedChannel channel(TestChannelConfig(), 1);
  const RadioId sender = channel.AddRadio();
  const RadioId receiver = channel.AddRadio();
  SendAndResolve(channel, sender, Pattern(30));
  EXPECT_TRUE(Drained(channel, sender).empty());
  EXPECT_EQ(Drained(channel, receiver), Pattern(30));
  EXPECT_EQ(channel.stats().receptions, 1U);
}

TEST(SharedChannel, LossFractionMatchesConfiguredLoss) {
  ChannelConfig config = TestChannelConfig();
  config.loss = 0.1;
  SharedChannel channel(config, 42);
  const RadioId sender = channel.AddRadio();
  const RadioId receiver = channel.AddRadio();
  constexpr int kTransmissions = 10'000;
  constexpr std::size_t kBurstBytes = 4;
  for (int i = 0; i < kTransmissions; ++i) SendAndResolve(channel, sender, Pattern(kBurstBytes));
  const double received = static_cast<double>(Drained(channel, receiver).size() / kBurstBytes);
  const double lost = kTransmissions - received;
  EXPECT_NEAR(lost, kTransmissions * 0.1, FiveSigma(kTransmissions, 0.1));
  EXPECT_EQ(static_cast<double>(channel.stats().receptions_lost), lost);
}

// A radio_burst: within its window every reception is lost with its probability
// (1: all), on top of the channel's own loss; outside it nothing changes.
TEST(SharedChannel, LossBurstLosesReceptionsInItsWindowOnly) {
  constexpr std::size_t kBurstBytes = 4;
  constexpr int kTransmissions = 2'000;
  const auto run = [&](double burst_loss) {
    ChannelConfig config = TestChannelConfig();
    config.loss = 0.1;
    SharedChannel channel(config, 42);
    const RadioId sender = channel.AddRadio();
    const RadioId receiver = channel.AddRadio();
    // Each send-and-resolve takes the turnaround and the airtime: the window
    // covers the second thousand transmissions.
    const Nanos each = kTurnaround + channel.AirtimeOf(kBurstBytes);
    ChannelConfig with_burst = config;
    with_burst.loss_bursts.push_back({each * 1001, each * 2000, burst_loss});
    SharedChannel bursty(with_burst, 42);
    bursty.AddRadio();
    bursty.AddRadio();
    // Per channel (without, with the burst): losses before and in the window.
    std::vector<int> lost_in_window(2, 0);
    std::vector<int> lost_before(2, 0);
    const std::vector<SharedChannel*> channels{&channel, &bursty};
    for (std::size_t c = 0; c < 2; ++c) {
      for (int i = 0; i < kTransmissions; ++i) {
        SendAndResolve(*channels[c], sender, Pattern(kBurstBytes));
        const bool received = Drained(*channels[c], receiver).size() == kBurstBytes;
        if (received) continue;
        if (i < 1000) ++lost_before[c];
        if (i >= 1000 && i < 1999) ++lost_in_window[c];
      }
    }
    return std::pair(lost_in_window, lost_before);
  };
  const auto [dead_in, dead_before] = run(1.0);
  EXPECT_EQ(dead_in[1], 999);                 // a dead channel in the window
  EXPECT_EQ(dead_before[1], dead_before[0]);  // the same draws before it
  const auto [half_in, half_before] = run(0.5);
  EXPECT_EQ(half_before[1], half_before[0]);
  const double p = 1.0 - 0.9 * 0.5;
  EXPECT_NEAR(half_in[1], 999 * p, FiveSigma(999, p));
  EXPECT_NEAR(half_in[0], 999 * 0.1, FiveSigma(999, 0.1));
}

TEST(SharedChannel, BitErrorsMatchConfiguredRate) {
  ChannelConfig config = TestChannelConfig();
  config.bit_error_rate = 1e-3;
  SharedChannel channel(config, 7);
  const RadioId sender = channel.AddRadio();
  const RadioId receiver = channel.AddRadio();
  constexpr int kTransmissions = 1'000;
  const std::vector<std::uint8_t> sent = Pattern(100);
  for (int i = 0; i < kTransmissions; ++i) SendAndResolve(channel, sender, sent);
  const std::vector<std::uint8_t> received = Drained(channel, receiver);
  ASSERT_EQ(received.size(), sent.size() * kTransmissions);
  std::vector<int> flips_per_bit_position(8, 0);
  int flips = 0;
  for (std::size_t i = 0; i < received.size(); ++i) {
    const auto difference = static_cast<unsigned>(received[i] ^ sent[i % sent.size()]);
    flips += std::popcount(difference);
    for (unsigned bit = 0; bit < 8; ++bit)
      flips_per_bit_position[bit] += static_cast<int>((difference >> bit) & 1U);
  }
  const double bits = 8.0 * static_cast<double>(received.size());
  EXPECT_NEAR(flips, bits * 1e-3, FiveSigma(bits, 1e-3));
  EXPECT_EQ(channel.stats().bits_flipped, static_cast<std::uint64_t>(flips));
  // Flips land on every bit of a byte alike.
  for (const int count : flips_per_bit_position) {
    EXPECT_NEAR(count, bits / 8.0 * 1e-3, FiveSigma(bits / 8.0, 1e-3));
  }
}

TEST(SharedChannel, BitErrorRateOneInvertsEveryBit) {
  ChannelConfig config = TestChannelConfig();
  config.bit_error_rate = 1.0;
  SharedChannel channel(config, 7);
  const RadioId sender = channel.AddRadio();
  const RadioId receiver = channel.AddRadio();
  SendAndResolve(channel, sender, {0x00, 0xFF, 0x5A});
  EXPECT_EQ(Drained(channel, receiver), (std::vector<std::uint8_t>{0xFF, 0x00, 0xA5}));
  EXPECT_EQ(channel.stats().bits_flipped, 24U);
}

TEST(SharedChannel, RangeModelLosesMoreWithDistance) {
  ChannelConfig config = TestChannelConfig();
  config.range.clean_range_m = 100.0;
  config.range.max_range_m = 300.0;
  SharedChannel channel(config, 3);
  const RadioId sender = channel.AddRadio({0.0, 0.0, 0.0});
  const RadioId near = channel.AddRadio({60.0, 0.0, 80.0});    // 100 m: still clean
  const RadioId middle = channel.AddRadio({0.0, 200.0, 0.0});  // range factor 0.25
  const RadioId at_max = channel.AddRadio({0.0, 0.0, 300.0});
  const RadioId beyond = channel.AddRadio({0.0, 0.0, 0.0});
  channel.SetPosition(beyond, {400.0, 0.0, 0.0});
  constexpr int kTransmissions = 4'000;
  const std::vector<std::uint8_t> sent = Pattern(1);
  for (int i = 0; i < kTransmissions; ++i) SendAndResolve(channel, sender, sent);
  EXPECT_EQ(Drained(channel, near), std::vector<std::uint8_t>(kTransmissions, sent[0]));
  const double middle_lost = kTransmissions - static_cast<double>(Drained(channel, middle).size());
  EXPECT_NEAR(middle_lost, kTransmissions * 0.25, FiveSigma(kTransmissions, 0.25));
  EXPECT_TRUE(Drained(channel, at_max).empty());
  EXPECT_TRUE(Drained(channel, beyond).empty());
}

struct RunResult {
  std::vector<std::vector<std::uint8_t>> received;
  ChannelStats stats;
  std::vector<std::uint8_t> air_log;  // transmitter, collided and bytes of every record
};

// A busy fleet: loss, bit errors, range, collisions from free-running radios.
RunResult RunFleet(std::uint64_t seed) {
  ChannelConfig config = TestChannelConfig();
  config.loss = 0.2;
  config.bit_error_rate = 1e-3;
  config.range.clean_range_m = 50.0;
  config.range.max_range_m = 500.0;
  SharedChannel channel(config, seed);
  RunResult result;
  channel.SetAirObserver([&result](const AirRecord& record) {
    result.air_log.push_back(static_cast<std::uint8_t>(record.transmitter));
    result.air_log.push_back(record.collided ? 1 : 0);
    result.air_log.insert(result.air_log.end(), record.bytes.begin(), record.bytes.end());
  });
  constexpr RadioId kRadios = 6;
  for (RadioId i = 0; i < kRadios; ++i) channel.AddRadio({100.0 * i, 0.0, 0.0});
  for (int round = 0; round < 200; ++round) {
    const Nanos now = channel.now();
    for (RadioId radio = 0; radio < kRadios; ++radio) {
      if ((round + static_cast<int>(radio)) % 3 != 0) continue;
      // Close starts collide, spread ones do not.
      const Nanos spacing = milliseconds(round % 4 == 0 ? 1 : 5);
      const Nanos start = now + kTurnaround + spacing * radio;
      channel.Transmit(radio, now, start, Pattern(20 + radio, static_cast<std::uint8_t>(round)));
    }
    while (const auto next = channel.NextEventTime()) channel.AdvanceTo(*next);
  }
  for (RadioId radio = 0; radio < kRadios; ++radio)
    result.received.push_back(Drained(channel, radio));
  result.stats = channel.stats();
  return result;
}

TEST(SharedChannel, SameSeedAndInputsGiveIdenticalResults) {
  const RunResult first = RunFleet(2024);
  const RunResult second = RunFleet(2024);
  EXPECT_EQ(first.received, second.received);
  EXPECT_EQ(first.stats, second.stats);
  EXPECT_EQ(first.air_log, second.air_log);
  EXPECT_GT(first.stats.collisions, 0U);
  EXPECT_GT(first.stats.receptions_lost, 0U);
  EXPECT_GT(first.stats.bits_flipped, 0U);
  EXPECT_NE(first.received, RunFleet(2025).received);
}

TEST(SharedChannel, BusyTimeIsTheUnionOfTransmissions) {
  SharedChannel channel(TestChannelConfig(), 1);
  const RadioId a = channel.AddRadio();
  const RadioId b = channel.AddRadio();
  const RadioId c = channel.AddRadio();
  const RadioId d = channel.AddRadio();
  channel.AdvanceTo(milliseconds(1));
  EXPECT_EQ(channel.stats().busy, Nanos{0});
  const Nanos c_start = milliseconds(100);
  const Nanos c_end = channel.Transmit(c, channel.now(), c_start, Pattern(100));  // alone
  channel.Transmit(a, channel.now(), milliseconds(6), Pattern(100));
  const Nanos b_end = channel.Transmit(b, channel.now(), milliseconds(10), Pattern(100));
  channel.Transmit(d, channel.now(), milliseconds(12), Pattern(2));  // inside b's
  const Nanos c_middle = c_start + milliseconds(3);
  channel.AdvanceTo(c_middle);
  EXPECT_EQ(channel.stats().busy, (b_end - milliseconds(6)) + milliseconds(3));
  channel.AdvanceTo(c_end + milliseconds(50));
  EXPECT_EQ(channel.stats().busy, (b_end - milliseconds(6)) + (c_end - c_start));
}

TEST(SharedChannel, AirObserverSeesEveryResolvedTransmissionOnce) {
  SharedChannel channel(TestChannelConfig(), 1);
  struct Seen {
    RadioId transmitter;
    Nanos start;
    Nanos end;
    bool collided;
    std::vector<std::uint8_t> bytes;
  };
  std::vector<Seen> seen;
  channel.SetAirObserver([&seen](const AirRecord& record) {
    seen.push_back({record.transmitter,
                    record.start,
                    record.end,
                    record.collided,
                    {record.bytes.begin(), record.bytes.end()}});
  });
  const RadioId a = channel.AddRadio();
  const RadioId b = channel.AddRadio();
  const Nanos clean_end = channel.Transmit(a, Nanos{0}, kTurnaround, Pattern(3));
  const Nanos b_end = channel.Transmit(b, Nanos{0}, milliseconds(50), Pattern(100));
  const Nanos a_end = channel.Transmit(a, Nanos{0}, milliseconds(60), Pattern(4));
  channel.AdvanceTo(a_end);
  ASSERT_EQ(seen.size(), 2U);  // b has not ended yet
  channel.AdvanceTo(b_end + milliseconds(100));
  ASSERT_EQ(seen.size(), 3U);
  EXPECT_EQ(seen[0].transmitter, a);
  EXPECT_EQ(seen[0].start, kTurnaround);
  EXPECT_EQ(seen[0].end, clean_end);
  EXPECT_FALSE(seen[0].collided);
  EXPECT_EQ(seen[0].bytes, Pattern(3));
  EXPECT_EQ(seen[1].end, a_end);
  EXPECT_TRUE(seen[1].collided);
  EXPECT_EQ(seen[2].transmitter, b);
  EXPECT_EQ(seen[2].bytes, Pattern(100));
  EXPECT_TRUE(seen[2].collided);
}

TEST(SharedChannel, AirObserverMayTransmit) {
  SharedChannel channel(TestChannelConfig(), 1);
  const RadioId a = channel.AddRadio();
  const RadioId echo = channel.AddRadio();
  channel.SetAirObserver([&](const AirRecord& record) {
    if (record.transmitter == a) {
      channel.Transmit(echo, channel.now(), channel.now() + kTurnaround, Pattern(2, 9));
    }
  });
  SendAndResolve(channel, a, Pattern(5));
  ASSERT_TRUE(channel.NextEventTime().has_value());
  channel.AdvanceTo(*channel.NextEventTime());
  EXPECT_EQ(Drained(channel, a), Pattern(2, 9));
}

// Expects the configuration to be refused with a message naming `field`.
void ExpectConfigRejected(const ChannelConfig& config, const std::string& field) {
  try {
    config.Validate();
    ADD_FAILURE() << "accepted a bad " << field;
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find(field), std::string::npos) << error.what();
  }
  EXPECT_THROW(SharedChannel(config, 1), std::invalid_argument);
}

TEST(ChannelConfig, ValidateNamesTheBadField) {
  EXPECT_NO_THROW(ChannelConfig{}.Validate());
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  ChannelConfig config;
  config.baud = 0;
  ExpectConfigRejected(config, "baud");
  config = {};
  config.bits_per_byte = 7;
  ExpectConfigRejected(config, "bits_per_byte");
  config = {};
  config.turnaround = Nanos{-1};
  ExpectConfigRejected(config, "turnaround");
  for (const double bad : {-0.1, 1.5, kNaN}) {
    config = {};
    config.loss = bad;
    ExpectConfigRejected(config, "loss");
    config = {};
    config.bit_error_rate = bad;
    ExpectConfigRejected(config, "bit_error_rate");
  }
  config = {};
  config.range.clean_range_m = kNaN;
  ExpectConfigRejected(config, "clean_range_m");
  config = {};
  config.range.clean_range_m = 200.0;
  config.range.max_range_m = 100.0;
  ExpectConfigRejected(config, "max_range_m");
  config.range.max_range_m = kNaN;
  ExpectConfigRejected(config, "max_range_m");
  config = {};
  config.loss_bursts.push_back({Nanos{10}, Nanos{5}, 0.5});
  ExpectConfigRejected(config, "loss_bursts.until");
  config.loss_bursts.back() = {Nanos{0}, Nanos{5}, 1.5};
  ExpectConfigRejected(config, "loss_bursts.loss");
}

}  // namespace
}  // namespace fireswarm::radio
