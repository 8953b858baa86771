// ChannelRouter: several channels (separate SharedChannels, one ChannelLoop each)
// driven by one router, requests and reports routed by the vehicle's channel.
#include "fireswarm/radio/channel_router.hpp"

#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <set>
#include <span>
#include <vector>

#include "fireswarm/radio/channel_loop.hpp"
#include "fireswarm/radio/mission_chunks.hpp"
#include "fireswarm/radio/parser.hpp"
#include "radio/sim_net.hpp"

namespace fireswarm::radio {
namespace {

using sim_test::ServerConfig;
using sim_test::SimVehicle;
using sim_test::TestChannelConfig;
using std::chrono::seconds;

// The router on `channels` channels; each vehicle's radio sits on the channel the
// test says, which may not be the one it is registered on. A channel can be
// unplugged: its master's bursts no longer go on the air and it hears nothing.
class MultiChannelNet {
 public:
  explicit MultiChannelNet(std::size_t channels, double loss = 0.0)
      : router_(std::vector<SchedulerConfig>(channels, ServerConfig(LinkMode::kSlots))),
        unplugged_(channels, false),
        heard_(channels) {
    for (std::size_t k = 0; k < channels; ++k) {
      loops_.push_back(std::make_unique<ChannelLoop>(
          TestChannelConfig(loss), /*seed=*/7 + k,
          LoopMaster{[this, k] { return router_.NextWakeup(k); },
                     [this, k](Nanos now, std::span<const std::uint8_t> received) {
                       return StepServer(k, now, received);
                     }}));
      loops_.back()->channel().SetAirObserver([this, k](const AirRecord& record) {
        FrameParser parser(ChecksumMode::kCrc16);
        parser.Feed(record.bytes,
                    [&](const FrameView& frame) { heard_[k].insert(frame.receiver); });
      });
      raw_.push_back(loops_.back().get());
    }
  }

  /// Registers `id` on `registered` (nullopt: balanced) and puts its radio on
  /// `on_air` (nullopt: the registered channel).
  void AddVehicle(std::uint8_t id, std::optional<std::size_t> registered = std::nullopt,
                  std::optional<std::size_t> on_air = std::nullopt) {
    const std::size_t channel = router_.AddVehicle(id, 1.0, Nanos{0}, registered);
    VehicleEndpointConfig v;
    v.id = id;
    v.mode = LinkMode::kSlots;
    v.checksum = sim_test::kChecksum;
    v.timing = router_.channel(channel).config().timing;
    vehicles_[id] = std::make_unique<SimVehicle>(v);
    loops_.at(on_air.value_or(channel))
        ->AddVehicle([&vehicle = *vehicles_[id]](Nanos now, std::span<const std::uint8_t> bytes) {
          return vehicle.endpoint.OnReceive(now, bytes);
        });
  }

  void RunUntil(Nanos end) { RunLoopsUntil(raw_, end); }
  void Unplug(std::size_t channel) { unplugged_.at(channel) = true; }

  ChannelRouter& router() { return router_; }
  SimVehicle& vehicle(std::uint8_t id) { return *vehicles_.at(id); }
  /// Receiver IDs of every frame that went over the air on `channel`.
  const std::set<std::uint8_t>& heard(std::size_t channel) const { return heard_.at(channel); }

  template <typename Event>
  std::vector<Event> EventsOf() const {
    std::vector<Event> out;
    for (const auto& e : events_) {
      if (const auto* typed = std::get_if<Event>(&e)) out.push_back(*typed);
    }
    return out;
  }

 private:
  std::vector<Burst> StepServer(std::size_t channel, Nanos now,
                                std::span<const std::uint8_t> received) {
    std::vector<Burst> bursts = router_.Step(
        now, channel, unplugged_[channel] ? std::span<const std::uint8_t>{} : received);
    for (auto& e : router_.TakeEvents()) events_.push_back(std::move(e));
    if (unplugged_[channel]) bursts.clear();
    return bursts;
  }

  ChannelRouter router_;
  std::vector<bool> unplugged_;
  std::vector<std::set<std::uint8_t>> heard_;
  std::vector<std::unique_ptr<ChannelLoop>> loops_;
  std::vector<ChannelLoop*> raw_;
  std::map<std::uint8_t, std::unique_ptr<SimVehicle>> vehicles_;
  std::vector<SchedulerEvent> events_;
};

std::map<std::uint8_t, int> HeardTelemetry(const MultiChannelNet& net) {
  std::map<std::uint8_t, int> counts;
  for (const TelemetryReceived& t : net.EventsOf<TelemetryReceived>()) ++counts[t.vehicle];
  return counts;
}

TEST(ChannelRouter, SpreadsVehiclesInBalancedGroupsUnlessTheirChannelIsGiven) {
  ChannelRouter router(std::vector<SchedulerConfig>(3, ServerConfig(LinkMode::kSlots)));
  EXPECT_EQ(router.AddVehicle(9, 1.0, Nanos{0}, 2), 2U);
  for (std::uint8_t id = 1; id <= 5; ++id) router.AddVehicle(id);
  EXPECT_EQ(router.VehiclesOn(0).size(), 2U);
  EXPECT_EQ(router.VehiclesOn(1).size(), 2U);
  EXPECT_EQ(router.VehiclesOn(2).size(), 2U);
  EXPECT_EQ(router.ChannelOf(9), 2U);
  EXPECT_THROW(router.AddVehicle(7, 1.0, Nanos{0}, 3), std::invalid_argument);
  EXPECT_THROW(router.AddVehicle(9), std::invalid_argument);
  EXPECT_THROW(ChannelRouter(std::vector<SchedulerConfig>{}), std::invalid_argument);
}

TEST(ChannelRouter, RoutesUploadsCommandsAndReportsByTheVehiclesChannel) {
  MultiChannelNet net(2);
  for (std::uint8_t id = 1; id <= 4; ++id) net.AddVehicle(id);  // 1, 3 on 0; 2, 4 on 1
  std::set<RequestId> ids;
  std::vector<Waypoint> mission(6, Waypoint{46.0, 7.0, 60.0, 10.0, 0});
  for (std::uint8_t id = 1; id <= 4; ++id) {
    for (const MissionChunk& chunk : SplitMission(1, mission)) {
      ids.insert(net.router().SendMissionChunk(id, chunk));
    }
    Command command;
    command.type = CommandType::kHold;
    ids.insert(net.router().SendCommand(id, command, /*urgent=*/id == 4));
    net.vehicle(id).endpoint.QueueFireReport(FireReport{});
  }
  net.RunUntil(seconds(10));

  std::set<RequestId> completed;
  for (const RequestFinished& f : net.EventsOf<RequestFinished>()) {
    EXPECT_EQ(f.status, RequestStatus::kCompleted) << "vehicle " << int{f.vehicle};
    completed.insert(f.id);
  }
  EXPECT_EQ(completed, ids) << "IDs unique across channels, each request finished once";
  std::map<std::uint8_t, int> reports;
  for (const FireReportReceived& r : net.EventsOf<FireReportReceived>()) ++reports[r.vehicle];
  EXPECT_EQ(reports, (std::map<std::uint8_t, int>{{1, 1}, {2, 1}, {3, 1}, {4, 1}}));
  const auto chunks = static_cast<int>(SplitMission(1, mission).size());
  for (std::uint8_t id = 1; id <= 4; ++id) {
    EXPECT_EQ(net.vehicle(id).handler.executed, chunks + 1)
        << "its chunks and its command, vehicle " << int{id};
  }
  // Nothing addressed to a vehicle went over the other channel.
  for (const int id : {1, 3}) {
    EXPECT_FALSE(net.heard(1).contains(static_cast<std::uint8_t>(id)));
  }
  for (const int id : {2, 4}) {
    EXPECT_FALSE(net.heard(0).contains(static_cast<std::uint8_t>(id)));
  }
  EXPECT_EQ(net.router().stats().requests_completed, ids.size());
  EXPECT_EQ(net.router().channel(0).stats().requests_completed +
                net.router().channel(1).stats().requests_completed,
            ids.size());
}

TEST(ChannelRouter, AVehicleOnTheWrongChannelIsNeverHeardAndReportedSilent) {
  MultiChannelNet net(2);
  net.AddVehicle(1, 0);
  net.AddVehicle(2, 1);
  net.AddVehicle(3, /*registered=*/0, /*on_air=*/1);  // its modem tuned to the other channel
  net.RunUntil(seconds(10));

  const std::map<std::uint8_t, int> counts = HeardTelemetry(net);
  EXPECT_FALSE(counts.contains(3)) << "never heard on either channel";
  EXPECT_GE(counts.at(1), 9);
  EXPECT_GE(counts.at(2), 9);
  std::set<std::uint8_t> silent;
  for (const VehicleSilent& s : net.EventsOf<VehicleSilent>()) silent.insert(s.vehicle);
  EXPECT_EQ(silent, std::set<std::uint8_t>{3});
  EXPECT_EQ(net.router().channel(1).stats().unknown_senders, 0U) << "it never had a turn there";
  EXPECT_FALSE(net.router().health(0).silent) << "vehicle 1 answers on channel 0";
  EXPECT_FALSE(net.router().health(1).silent);
}

TEST(ChannelRouter, OneChannelLostWhileTheOthersFlyOn) {
  MultiChannelNet net(3, /*loss=*/0.05);
  for (std::uint8_t id = 1; id <= 9; ++id) net.AddVehicle(id);
  net.RunUntil(seconds(5));
  const std::map<std::uint8_t, int> before = HeardTelemetry(net);
  net.Unplug(1);
  net.RunUntil(seconds(25));
  const std::map<std::uint8_t, int> after = HeardTelemetry(net);

  EXPECT_TRUE(net.router().health(1).silent);
  EXPECT_GT(net.router().health(1).since, seconds(5));
  EXPECT_FALSE(net.router().health(0).silent);
  EXPECT_FALSE(net.router().health(2).silent);
  for (std::uint8_t id = 1; id <= 9; ++id) {
    const int gained = after.at(id) - before.at(id);
    if (net.router().ChannelOf(id) == 1) {
      EXPECT_EQ(gained, 0) << "vehicle " << int{id};
    } else {
      EXPECT_GE(gained, 17) << "vehicle " << int{id} << ": ~1 Hz over 20 s at 5 % loss";
    }
  }
}

}  // namespace
}  // namespace fireswarm::radio
