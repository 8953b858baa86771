// A vehicle's non-volatile storage across a reboot: a new Vehicle made with the
// old one's store has its parameters, its missions (the upload in progress too)
// and its flight back; one made without starts from nothing.
#include "fireswarm/agents/non_volatile_store.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "fireswarm/agents/vehicle.hpp"
#include "fireswarm/radio/mission_chunks.hpp"

namespace fireswarm::agents {
namespace {

constexpr float kPitchDeg = -60.0F;

VehicleConfig ConfigWithStorage() {
  VehicleConfig config;
  config.id = 4;
  config.radio.checksum = radio::ChecksumMode::kCrc16;
  config.storage = std::make_shared<NonVolatileStore>();
  return config;
}

std::vector<radio::Waypoint> Waypoints(std::size_t count) {
  std::vector<radio::Waypoint> waypoints(count);
  for (std::size_t i = 0; i < count; ++i) {
    waypoints[i].lat_deg = 45.0 + 1e-4 * static_cast<double>(i);
    waypoints[i].lon_deg = 7.0;
    waypoints[i].altitude_m = 60.0;
  }
  return waypoints;
}

float PitchOf(const Vehicle& vehicle) {
  return vehicle.params().Get(ParamId::kCameraPitchDeg);
}

TEST(NonVolatileStore, ARebootedVehicleReloadsItsParametersAndMissions) {
  const VehicleConfig config = ConfigWithStorage();
  Vehicle before(config);
  radio::ParamWrite pitch;
  pitch.param_id = static_cast<std::uint16_t>(ParamId::kCameraPitchDeg);
  pitch.value = kPitchDeg;
  ASSERT_EQ(before.OnParamWrite(pitch).status, radio::ParamStatus::kOk);
  const std::vector<radio::Waypoint> complete = Waypoints(3);
  for (const radio::MissionChunk& chunk : radio::SplitMission(7, complete)) {
    before.OnMissionChunk(chunk);
  }
  // A second mission half uploaded when the vehicle goes down.
  const std::vector<radio::MissionChunk> next =
      radio::SplitMission(8, Waypoints(3 * radio::kMaxWaypointsPerChunk));
  ASSERT_GE(next.size(), 2U);
  ASSERT_EQ(before.OnMissionChunk(next[0]), radio::MissionAckStatus::kAccepted);

  const Vehicle after(config);
  EXPECT_EQ(PitchOf(after), kPitchDeg);
  ASSERT_NE(after.missions().complete(), nullptr);
  EXPECT_EQ(after.missions().complete()->id, 7);
  EXPECT_EQ(after.missions().complete()->waypoints.size(), complete.size());
  ASSERT_TRUE(after.missions().upload().has_value());
  EXPECT_EQ(after.missions().upload()->mission_id, 8);
  EXPECT_EQ(after.missions().upload()->chunks_received, 1U);
  EXPECT_FALSE(after.resuming());  // on the ground: nothing to resume
  EXPECT_EQ(after.mode(), radio::FlightMode::kIdle);

  VehicleConfig forgetful = config;
  forgetful.storage = nullptr;
  const Vehicle fresh(forgetful);
  EXPECT_NE(PitchOf(fresh), kPitchDeg);
  EXPECT_EQ(fresh.missions().complete(), nullptr);
}

TEST(NonVolatileStore, AnAirborneFlightIsResumedAtTheFirstStepWithAnEstimate) {
  VehicleConfig config = ConfigWithStorage();
  for (const radio::MissionChunk& chunk : radio::SplitMission(7, Waypoints(3))) {
    config.storage->WriteMissions([&] {
      MissionStore missions = config.storage->missions().value_or(MissionStore{});
      missions.OnChunk(chunk);
      return missions;
    }());
  }
  FlightRecord flight;
  flight.mode = radio::FlightMode::kSearch;
  flight.active_mission = 7;
  flight.waypoint_index = 2;
  flight.home = common::LatLon{45.0, 7.0};
  flight.baro_zero_m = 100.0;
  config.storage->WriteFlight(flight);

  Vehicle vehicle(config);
  EXPECT_TRUE(vehicle.resuming());
  // No estimate yet: level, armed, no climb.
  const ActuatorOutputs waiting = vehicle.Step(Nanos{0}, SensorInputs{});
  EXPECT_TRUE(waiting.armed);
  EXPECT_EQ(waiting.roll_rad, 0.0);
  EXPECT_EQ(waiting.pitch_rad, 0.0);
  EXPECT_EQ(waiting.climb_rate_mps, 0.0);
  EXPECT_TRUE(vehicle.resuming());

  SensorInputs inputs;
  inputs.gps = GpsInput{.lat_deg = 44.9995, .lon_deg = 7.0};
  inputs.baro = BaroInput{160.0};
  inputs.attitude = AttitudeInput{};
  vehicle.Step(std::chrono::milliseconds(10), inputs);
  EXPECT_FALSE(vehicle.resuming());
  EXPECT_EQ(vehicle.mode(), radio::FlightMode::kSearch);
  EXPECT_EQ(vehicle.active_mission(), 7);
  EXPECT_NEAR(vehicle.estimate().altitude_m, 60.0, 1e-9);  // above the take-off ground
  ASSERT_NE(vehicle.navigator(), nullptr);
  EXPECT_EQ(vehicle.navigator()->waypoint_index(), 2U);
  EXPECT_EQ(vehicle.flight_record().waypoint_index, 2U);
}

}  // namespace
}  // namespace fireswarm::agents
