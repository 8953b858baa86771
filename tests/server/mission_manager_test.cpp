#include "fireswarm/server/mission_manager.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <set>
#include <vector>

#include "fireswarm/radio/channel.hpp"
#include "fireswarm/radio/link.hpp"
#include "fireswarm/radio/vehicle_endpoint.hpp"

namespace fireswarm::server {
namespace {

using radio::Nanos;

// The radio side of a vehicle: stores chunks as the APOne mission store does
// (complete when every chunk is in) and refuses the start `refusals` times, as a
// vehicle without a GPS fix does.
class FakeVehicle final : public radio::VehicleRequestHandler {
 public:
  FakeVehicle(std::uint8_t id, radio::LinkMode mode, int refusals)
      : endpoint_(Config(id, mode), *this), refusals_left_(refusals) {}

  radio::CommandResult OnCommand(const radio::Command& command) override {
    if (command.type != radio::CommandType::kStartMission) return radio::CommandResult::kUnsupported;
    if (!complete_ || command.mission_id != mission_id_) return radio::CommandResult::kRejected;
    if (refusals_left_ > 0) {
      --refusals_left_;
      return radio::CommandResult::kRejected;
    }
    ++starts_accepted_;
    return radio::CommandResult::kAccepted;
  }
  radio::MissionAckStatus OnMissionChunk(const radio::MissionChunk& chunk) override {
    if (chunk.chunk_index >= chunk.chunk_count) return radio::MissionAckStatus::kRejected;
    mission_id_ = chunk.mission_id;
    waypoints_.resize(chunk.total_waypoints);
    for (std::size_t i = 0; i < chunk.waypoint_count; ++i) {
      waypoints_.at(chunk.first_waypoint + i) = chunk.waypoints[i];
    }
    chunks_.insert(chunk.chunk_index);
    complete_ = chunks_.size() == chunk.chunk_count;
    return complete_ ? radio::MissionAckStatus::kComplete : radio::MissionAckStatus::kAccepted;
  }
  radio::ParamValue OnParamRead(const radio::ParamRead&) override { return {}; }
  radio::ParamValue OnParamWrite(const radio::ParamWrite&) override { return {}; }

  radio::VehicleEndpoint& endpoint() { return endpoint_; }
  const std::vector<radio::Waypoint>& waypoints() const { return waypoints_; }
  bool complete() const { return complete_; }
  int starts_accepted() const { return starts_accepted_; }

 private:
  static radio::VehicleEndpointConfig Config(std::uint8_t id, radio::LinkMode mode) {
    radio::VehicleEndpointConfig config;
    config.id = id;
    config.mode = mode;
    return config;
  }
  radio::VehicleEndpoint endpoint_;
  int refusals_left_;
  std::uint16_t mission_id_ = 0;
  std::set<std::uint8_t> chunks_;
  std::vector<radio::Waypoint> waypoints_;
  bool complete_ = false;
  int starts_accepted_ = 0;
};

// The server's scheduler and the fake vehicles on one shared channel, run event by
// event (no wall clock).
struct Air {
  Air(double loss, radio::LinkMode mode) : channel(Channel(loss), 7), server_link(channel, channel.AddRadio()) {
    config.mode = mode;
    scheduler = std::make_unique<radio::MasterScheduler>(config);
  }
  static radio::ChannelConfig Channel(double loss) {
    radio::ChannelConfig channel_config;
    channel_config.loss = loss;
    return channel_config;
  }
  FakeVehicle& Add(std::uint8_t id, int refusals) {
    vehicles.push_back(std::make_unique<FakeVehicle>(id, config.mode, refusals));
    links.push_back(std::make_unique<radio::SimLink>(channel, channel.AddRadio()));
    scheduler->AddVehicle(id, 1.0);
    return *vehicles.back();
  }
  // Runs until `done()` or `limit`; every scheduler event goes to `manager`.
  template <typename Done>
  Nanos Run(MissionManager& manager, Nanos limit, Done&& done) {
    while (!done()) {
      const Nanos t = std::max(channel.now(),
                               std::min({scheduler->NextWakeup(), manager.NextWakeup(),
                                         channel.NextEventTime().value_or(Nanos::max())}));
      if (t > limit) break;
      channel.AdvanceTo(t);
      manager.Step(t);
      std::vector<std::uint8_t> bytes;
      server_link.Receive(t, bytes);
      for (const radio::Burst& burst : scheduler->Step(t, bytes)) {
        server_link.Transmit(t, burst.start, burst.bytes);
      }
      for (const radio::SchedulerEvent& event : scheduler->TakeEvents()) manager.OnEvent(event);
      for (std::size_t i = 0; i < vehicles.size(); ++i) {
        bytes.clear();
        links[i]->Receive(t, bytes);
        if (bytes.empty()) continue;
        for (const radio::Burst& burst : vehicles[i]->endpoint().OnReceive(t, bytes)) {
          links[i]->Transmit(t, burst.start, burst.bytes);
        }
      }
    }
    return channel.now();
  }

  radio::SchedulerConfig config;
  radio::SharedChannel channel;
  radio::SimLink server_link;
  std::unique_ptr<radio::MasterScheduler> scheduler;
  std::vector<std::unique_ptr<FakeVehicle>> vehicles;
  std::vector<std::unique_ptr<radio::SimLink>> links;
};

DroneMission Mission(std::uint8_t vehicle, std::size_t waypoints) {
  DroneMission mission;
  mission.vehicle = vehicle;
  mission.mission_id = 42;
  for (std::size_t i = 0; i < waypoints; ++i) {
    radio::Waypoint waypoint;
    waypoint.lat_deg = 46.0 + 1e-4 * static_cast<double>(i);
    waypoint.lon_deg = -74.5 + 1e-4 * static_cast<double>(vehicle);
    waypoint.altitude_m = 60.0;
    waypoint.speed_mps = 10.0;
    waypoint.flags = static_cast<std::uint8_t>(i % 2);
    mission.waypoints.push_back(waypoint);
  }
  return mission;
}

constexpr Nanos kLimit = std::chrono::seconds(600);

TEST(MissionManager, UploadsEveryDroneAndStartsIt) {
  Air air(0.0, radio::LinkMode::kSlots);
  std::vector<DroneMission> missions;
  for (std::uint8_t id = 1; id <= 4; ++id) {
    air.Add(id, 0);
    missions.push_back(Mission(id, 45));  // 3 chunks each
  }
  MissionManager manager(*air.scheduler, missions);
  manager.Begin();
  air.Run(manager, kLimit, [&] { return manager.AllStarted(); });
  for (std::uint8_t id = 1; id <= 4; ++id) {
    const DroneProgress& progress = manager.progress(id);
    EXPECT_EQ(progress.phase, DronePhase::kFlying) << int{id} << ": " << progress.failure;
    EXPECT_EQ(progress.chunk_count, 3u);
    EXPECT_EQ(progress.chunks_acked, 3u);
    const FakeVehicle& vehicle = *air.vehicles[id - 1u];
    EXPECT_EQ(vehicle.waypoints(), missions[id - 1u].waypoints) << "vehicle " << int{id};
    EXPECT_EQ(vehicle.starts_accepted(), 1);
  }
}

TEST(MissionManager, AsksARefusedStartAgainUntilTheVehicleAccepts) {
  Air air(0.0, radio::LinkMode::kPoll);
  air.Add(3, /*refusals=*/2);
  MissionManager manager(*air.scheduler, {Mission(3, 10)});
  manager.Begin();
  const Nanos end = air.Run(manager, kLimit, [&] { return manager.AllStarted(); });
  EXPECT_EQ(manager.progress(3).phase, DronePhase::kFlying);
  EXPECT_EQ(manager.progress(3).start_refusals, 2);
  // Two refusals, each followed by the configured wait before asking again.
  EXPECT_GE(end, 2 * radio::FromSeconds(MissionManagerConfig{}.start_retry_s));
}

TEST(MissionManager, CompletesTheUploadOnALossyChannel) {
  Air air(0.2, radio::LinkMode::kSlots);
  std::vector<DroneMission> missions;
  for (std::uint8_t id = 10; id < 16; ++id) {
    air.Add(id, 0);
    missions.push_back(Mission(id, 70));
  }
  MissionManager manager(*air.scheduler, missions);
  manager.Begin();
  air.Run(manager, kLimit, [&] { return manager.AllStarted(); });
  EXPECT_GT(air.scheduler->stats().retries, 0u) << "20 % loss must have cost resends";
  for (std::size_t i = 0; i < missions.size(); ++i) {
    const std::uint8_t id = missions[i].vehicle;
    EXPECT_EQ(manager.progress(id).phase, DronePhase::kFlying) << manager.progress(id).failure;
    EXPECT_EQ(air.vehicles[i]->waypoints(), missions[i].waypoints);
  }
}

TEST(MissionManager, GivesUpOnASilentVehicleAndSaysWhy) {
  Air air(0.0, radio::LinkMode::kPoll);
  air.Add(1, 0);
  air.scheduler->AddVehicle(2, 1.0);  // registered, but no radio answers as 2
  MissionManager manager(*air.scheduler, {Mission(1, 5), Mission(2, 5)});
  manager.Begin();
  air.Run(manager, kLimit, [&] { return manager.AllStarted(); });
  EXPECT_EQ(manager.progress(1).phase, DronePhase::kFlying);
  EXPECT_EQ(manager.progress(2).phase, DronePhase::kFailed);
  EXPECT_NE(manager.progress(2).failure.find("unanswered"), std::string::npos)
      << manager.progress(2).failure;
}

TEST(MissionManager, RefusesTwoMissionsForOneVehicle) {
  Air air(0.0, radio::LinkMode::kPoll);
  air.Add(1, 0);
  EXPECT_THROW(MissionManager(*air.scheduler, {Mission(1, 5), Mission(1, 6)}),
               std::invalid_argument);
}

TEST(ToDroneMissions, CarriesEveryWaypointWithLaneFlagsAltitudeAndSpeed) {
  planner::Plan plan;
  planner::DronePlan drone;
  drone.receiver_id = 7;
  drone.waypoints.push_back({{0, 0}, {46.0, -74.0}, false, false});
  drone.waypoints.push_back({{100, 0}, {46.0, -73.99}, false, true});
  drone.waypoints.push_back({{100, 80}, {46.001, -73.99}, false, false});
  plan.drones.push_back(drone);
  const std::vector<DroneMission> missions = ToDroneMissions(plan, 9, 60.0, 8.0);
  ASSERT_EQ(missions.size(), 1u);
  EXPECT_EQ(missions[0].vehicle, 7);
  EXPECT_EQ(missions[0].mission_id, 9);
  ASSERT_EQ(missions[0].waypoints.size(), 3u);
  EXPECT_EQ(missions[0].waypoints[1].flags, 1);
  EXPECT_EQ(missions[0].waypoints[0].flags, 0);
  EXPECT_DOUBLE_EQ(missions[0].waypoints[2].lat_deg, 46.001);
  EXPECT_DOUBLE_EQ(missions[0].waypoints[2].altitude_m, 60.0);
  EXPECT_DOUBLE_EQ(missions[0].waypoints[2].speed_mps, 8.0);

  plan.drones[0].receiver_id = 255;
  EXPECT_THROW(ToDroneMissions(plan, 9, 60.0, 8.0), std::invalid_argument);
}

}  // namespace
}  // namespace fireswarm::server
