// The server on two radio channels (issue 21): the mission's uploads and starts,
// operator commands and fire reports go over each vehicle's own channel, and
// radio_stats_t reports per channel.
#include <gtest/gtest.h>

#include <memory>
#include <span>
#include <vector>

#include "fireswarm/radio/channel_loop.hpp"
#include "fireswarm/server/lcm_bridge.hpp"
#include "fireswarm/server/server.hpp"
#include "server/fake_fleet.hpp"
#include "server/server_fixture.hpp"

namespace fireswarm::server {
namespace {

using testing::FakeVehicle;
using testing::kFrame;
using testing::kSecond;
using testing::Missions;
using common::Nanos;

// Vehicles 1 and 3 fixed on channel 1, 2 and 4 balanced onto channel 0.
class TwoChannelFleet {
 public:
  TwoChannelFleet() : server_(Config(), kFrame) {
    for (std::size_t k = 0; k < 2; ++k) {
      loops_.push_back(std::make_unique<radio::ChannelLoop>(
          radio::ChannelConfig{}, 11 + k,
          radio::LoopMaster{[this, k] { return server_.NextWakeup(k); },
                            [this, k](Nanos now, std::span<const std::uint8_t> received) {
                              return server_.Step(now, k, received);
                            }}));
      raw_.push_back(loops_.back().get());
    }
    for (std::uint8_t id = 1; id <= 4; ++id) {
      server_.AddVehicle(id);
      vehicles_.push_back(std::make_unique<FakeVehicle>(id, radio::LinkMode::kSlots, 0));
      // On its stand west of its first waypoint (Missions): heard there, it is
      // cleared to take off.
      vehicles_.back()->endpoint().SetTelemetry(testing::OnItsStand(-100.0, 50.0 * id, 1'000));
      loops_.at(server_.scheduler().ChannelOf(id))
          ->AddVehicle([&v = *vehicles_.back()](Nanos now, std::span<const std::uint8_t> bytes) {
            return v.endpoint().OnReceive(now, bytes);
          });
    }
  }

  static ServerConfig Config() {
    ServerConfig config;
    config.channels.assign(2, config.radio.timing);
    config.vehicle_channels = {{1, 1}, {3, 1}};
    return config;
  }

  void RunFor(Nanos span) {
    end_ += span;
    radio::RunLoopsUntil(raw_, end_);
  }
  Server& server() { return server_; }
  FakeVehicle& vehicle(std::uint8_t id) { return *vehicles_.at(id - 1U); }

 private:
  Server server_;
  std::vector<std::unique_ptr<radio::ChannelLoop>> loops_;
  std::vector<radio::ChannelLoop*> raw_;
  std::vector<std::unique_ptr<FakeVehicle>> vehicles_;
  Nanos end_{0};
};

TEST(ServerChannels, UploadsCommandsAndReportsGoOverEachVehiclesChannel) {
  TwoChannelFleet fleet;
  Server& server = fleet.server();
  EXPECT_EQ(server.scheduler().ChannelOf(1), 1U);
  EXPECT_EQ(server.scheduler().ChannelOf(3), 1U);
  EXPECT_EQ(server.scheduler().ChannelOf(2), 0U);
  EXPECT_EQ(server.scheduler().ChannelOf(4), 0U);
  server.LoadMission(Missions({1, 2, 3, 4}, 20));
  ASSERT_TRUE(server.Handle(OperatorCommand{}, Nanos{0}));
  fleet.RunFor(15 * kSecond);
  for (std::uint8_t id = 1; id <= 4; ++id) {
    EXPECT_TRUE(fleet.vehicle(id).complete()) << "vehicle " << int{id};
    EXPECT_EQ(fleet.vehicle(id).starts_accepted(), 1) << "vehicle " << int{id};
  }

  OperatorCommand hold;
  hold.kind = OperatorCommand::Kind::kHold;
  hold.vehicle = 3;
  ASSERT_TRUE(server.Handle(hold, 15 * kSecond));
  fleet.vehicle(4).endpoint().QueueFireReport(testing::ReportAt(150, 0, 0, 14'000));
  fleet.RunFor(5 * kSecond);
  EXPECT_NE(testing::LastOf(fleet.vehicle(3), radio::CommandType::kHold), nullptr);
  EXPECT_EQ(server.fusion().tracks().size(), 1U) << "vehicle 4's report, over channel 0";
  EXPECT_EQ(server.scheduler().channel(0).stats().fire_reports, 1U);
  EXPECT_EQ(server.scheduler().channel(1).stats().fire_reports, 0U);
  EXPECT_EQ(server.scheduler().stats().requests_failed, 0U);

  RadioCounters counters;
  const radio_stats_t stats = ToRadioStats(server, 20.0, 20'000'000, 2.0, counters);
  EXPECT_EQ(stats.channel_count, 2);
  EXPECT_EQ(stats.vehicle_channel, (std::vector<std::int16_t>{1, 0, 1, 0}));
  EXPECT_EQ(stats.channel_vehicles, (std::vector<std::int16_t>{2, 2}));
  EXPECT_EQ(stats.channel_frames_sent[0] + stats.channel_frames_sent[1], stats.frames_sent);
  EXPECT_EQ(stats.channel_silent, (std::vector<std::int8_t>{0, 0}));
}

}  // namespace
}  // namespace fireswarm::server
