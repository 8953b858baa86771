#include "fireswarm/sim2d/simulation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "world_test_helpers.hpp"

namespace fireswarm::sim2d {
namespace {

using testing::VehicleAt;

VehicleCamera CameraOn(int vehicle_id, const std::string& model) {
  VehicleCamera camera;
  camera.vehicle_id = vehicle_id;
  camera.model = model;
  return camera;
}

// Two vehicles on the ground at the origin area, one fire right under vehicle 1.
SimulationConfig TwoVehiclesOneFire() {
  SimulationConfig config;
  config.world.seed = 99;
  config.fire.origin_m = Vec2(-500.0, -500.0);
  config.fire.width_m = 1000.0;
  config.fire.height_m = 1000.0;
  config.world.vehicles.push_back(VehicleAt(1, Vec2(0.0, 0.0)));
  config.world.vehicles.push_back(VehicleAt(2, Vec2(300.0, 0.0)));
  config.ignitions.push_back({Vec2(0.0, 0.0), 0.0});
  config.cameras.push_back(CameraOn(1, "amg8833"));
  config.cameras.push_back(CameraOn(2, "lepton35"));
  return config;
}

void RunFor(Simulation& sim, double seconds) {
  const auto steps = static_cast<int>(std::lround(seconds / sim.world().step_s()));
  for (int i = 0; i < steps; ++i) sim.Step();
}

TEST(Simulation, EachCameraDeliversFramesAtItsOwnRate) {
  Simulation sim(TwoVehiclesOneFire());
  int frames_1 = 0;
  int frames_2 = 0;
  for (int i = 0; i < 1000; ++i) {  // 10 s
    sim.Step();
    for (const CameraFrame& frame : sim.new_frames()) {
      (frame.vehicle_id == 1 ? frames_1 : frames_2)++;
      EXPECT_DOUBLE_EQ(frame.image->capture_time_s, sim.time_s());
    }
  }
  EXPECT_EQ(frames_1, 100);  // amg8833, 10 Hz
  EXPECT_EQ(frames_2, 87);   // lepton35, 8.7 Hz: frames at k / 8.7 s, k = 1..87
  EXPECT_EQ(sim.camera_frames(), 187);
}

TEST(Simulation, TheCameraAboveAFireSeesItAndTheOtherDoesNot) {
  Simulation sim(TwoVehiclesOneFire());
  RunFor(sim, 2.0);
  const ThermalImage* over_fire = sim.LatestFrame(1);
  const ThermalImage* elsewhere = sim.LatestFrame(2);
  ASSERT_NE(over_fire, nullptr);
  ASSERT_NE(elsewhere, nullptr);
  int hottest_over_fire = 0;
  for (const std::uint8_t grey : over_fire->pixels)
    hottest_over_fire = std::max<int>(hottest_over_fire, grey);
  int hottest_elsewhere = 0;
  for (const std::uint8_t grey : elsewhere->pixels)
    hottest_elsewhere = std::max<int>(hottest_elsewhere, grey);
  EXPECT_GT(hottest_over_fire, hottest_elsewhere + 100);
  EXPECT_GE(sim.fire().burning_count(), 1U);
  EXPECT_NE(sim.CameraOf(1), nullptr);
  EXPECT_EQ(sim.CameraOf(3), nullptr);
}

TEST(Simulation, BadCameraConfigIsRejectedNamingTheField) {
  SimulationConfig config = TwoVehiclesOneFire();
  config.cameras[1].model = "flir";
  try {
    Simulation sim(config);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("cameras[1].model"), std::string::npos) << e.what();
  }
  config = TwoVehiclesOneFire();
  config.cameras[1].vehicle_id = 7;
  EXPECT_THROW(Simulation{config}, std::invalid_argument);
  config = TwoVehiclesOneFire();
  config.cameras[1].vehicle_id = 1;  // two cameras on vehicle 1
  EXPECT_THROW(Simulation{config}, std::invalid_argument);
  config = TwoVehiclesOneFire();
  config.fire_step_s = 0.0;
  EXPECT_THROW(Simulation{config}, std::invalid_argument);
}

}  // namespace
}  // namespace fireswarm::sim2d
