// Investigate (seed 7.4): circling a fire with the camera kept on it.
#include <gtest/gtest.h>

#include <cstdio>

#include "fireswarm/agents/hot_regions.hpp"
#include "hil_test_helpers.hpp"

namespace fireswarm::hil {
namespace {

using radio::FlightMode;
using sim2d::Vec2;
using testing::Mission;
using testing::OneVehicleWorld;
using testing::RunUntilOr;
using testing::WaypointAt;

TEST(Investigate, LoiterKeepsTheFireInView) {
  const Vec2 fire(150.0, 300.0);
  sim2d::SimulationConfig config = OneVehicleWorld();
  config.ignitions.push_back({fire, 0.0});
  Mission mission(config);
  agents::Vehicle& vehicle = mission.AddVehicle(agents::VehicleConfig{});
  mission.RunUntil(1.0);
  // A lane 150 m west of the fire: the fire stays out of the camera's view.
  mission.link.UploadAndStart(1, 2,
                              {WaypointAt(mission, Vec2(0.0, 0.0), 60.0, /*lane_start=*/true),
                               WaypointAt(mission, Vec2(0.0, 1500.0), 60.0)});
  RunUntilOr(mission, 60.0, [&] { return vehicle.mode() == FlightMode::kSearch; });
  ASSERT_EQ(vehicle.mode(), FlightMode::kSearch);

  const common::LatLon fire_position = mission.ToLatLon(fire);
  radio::Command investigate;
  investigate.type = radio::CommandType::kInvestigate;
  investigate.lat_deg = fire_position.lat_deg;
  investigate.lon_deg = fire_position.lon_deg;
  investigate.duration_s = 150;  // radius and altitude 0: the default radius, here
  mission.link.server().SendCommand(1, investigate);
  const double commanded_s = mission.simulation.time_s();
  mission.RunUntil(commanded_s + 1.0);
  ASSERT_EQ(vehicle.mode(), FlightMode::kInvestigate);
  const double radius_m = vehicle.loiter().radius_m();

  // Let it reach the circle, then count the frames that show the fire.
  mission.RunUntil(commanded_s + 60.0);
  const agents::DetectorConfig detector =
      agents::DetectorConfigFor(common::CameraModelByName("seed"));
  int frames = 0;
  int frames_with_fire = 0;
  double worst_radius_error_m = 0.0;
  mission.RunUntil(commanded_s + 140.0, [&] {
    worst_radius_error_m = std::max(
        worst_radius_error_m, std::abs((mission.Truth(1).position_m - fire).norm() - radius_m));
    for (const sim2d::CameraFrame& taken : mission.simulation.new_frames()) {
      ++frames;
      const agents::CameraFrame frame = ToCameraFrame(*taken.image);
      for (const agents::HotRegion& region : agents::FindHotRegions(frame, detector)) {
        if (region.is_fire) {
          ++frames_with_fire;
          break;
        }
      }
    }
  });
  std::printf(
      "loiter at %.0f m around the fire: %d of %d frames show it, worst radius error %.2f m\n",
      radius_m, frames_with_fire, frames, worst_radius_error_m);
  ASSERT_GT(frames, 700);  // 80 s at 9 Hz
  EXPECT_GE(frames_with_fire, frames * 98 / 100);
  EXPECT_LT(worst_radius_error_m, 6.0);
  EXPECT_GE(vehicle.stats().fires_detected, 1U);
  EXPECT_EQ(vehicle.mode(), FlightMode::kInvestigate);
  // After its duration it goes back to the search.
  mission.RunUntil(commanded_s + 155.0);
  EXPECT_EQ(vehicle.mode(), FlightMode::kSearch);
}

}  // namespace
}  // namespace fireswarm::hil
