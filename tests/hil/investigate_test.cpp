// Investigate (seed 7.4): circling a fire with the camera kept on it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <vector>

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

// Starts the mission's vehicle (1) on one lane due north from the origin, `length_m` long, at 60 m.
void StartLaneNorth(Mission& mission, double length_m) {
  mission.RunUntil(1.0);
  mission.link.UploadAndStart(1, 2,
                              {WaypointAt(mission, Vec2(0.0, 0.0), 60.0, /*lane_start=*/true),
                               WaypointAt(mission, Vec2(0.0, length_m), 60.0)});
}

// Orders vehicle 1 to circle `point` (local m) for `duration_s`; radius 0: its
// own loiter radius; altitude 0: its own altitude.
void SendInvestigate(Mission& mission, const Vec2& point, std::uint16_t duration_s,
                     double altitude_m = 0.0) {
  const common::LatLon target = mission.ToLatLon(point);
  radio::Command investigate;
  investigate.type = radio::CommandType::kInvestigate;
  investigate.lat_deg = target.lat_deg;
  investigate.lon_deg = target.lon_deg;
  investigate.duration_s = duration_s;
  investigate.altitude_m = altitude_m;
  mission.link.server().SendCommand(1, investigate);
}

TEST(Investigate, LoiterKeepsTheFireInView) {
  const Vec2 fire(150.0, 300.0);
  sim2d::SimulationConfig config = OneVehicleWorld();
  config.ignitions.push_back({fire, 0.0});
  Mission mission(config);
  agents::Vehicle& vehicle = mission.AddVehicle(agents::VehicleConfig{});
  // A lane 150 m west of the fire: the fire stays out of the camera's view.
  StartLaneNorth(mission, 1500.0);
  RunUntilOr(mission, 60.0, [&] { return vehicle.mode() == FlightMode::kSearch; });
  ASSERT_EQ(vehicle.mode(), FlightMode::kSearch);

  SendInvestigate(mission, fire, 150);
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

// An investigation far from the vehicle: it flies straight to the circle at
// cruise speed (the loiter's own radial control alone spiralled in at a few m/s,
// and investigators sent across the area never arrived).
TEST(Investigate, AFarPointIsReachedAtCruiseSpeed) {
  sim2d::SimulationConfig config = OneVehicleWorld();
  config.world.wind.speed_mps = 4.0;  // the demo's wind, here against the transit
  config.world.wind.from_deg = 90.0;
  Mission mission(config);
  agents::Vehicle& vehicle = mission.AddVehicle(agents::VehicleConfig{});
  StartLaneNorth(mission, 1500.0);
  RunUntilOr(mission, 60.0, [&] { return vehicle.mode() == FlightMode::kSearch; });
  ASSERT_EQ(vehicle.mode(), FlightMode::kSearch);

  const Vec2 point(700.0, -400.0);
  SendInvestigate(mission, point, 400);
  const double commanded_s = mission.simulation.time_s();
  mission.RunUntil(commanded_s + 1.0);
  ASSERT_EQ(vehicle.mode(), FlightMode::kInvestigate);
  const double radius_m = vehicle.loiter().radius_m();
  const double distance_m = (mission.Truth(1).position_m - point).norm() - radius_m;

  // Cruise is 8 m/s: allow 15 % more, and the turn toward the point.
  const double allowed_s = distance_m / 8.0 * 1.15 + 10.0;
  RunUntilOr(mission, commanded_s + allowed_s,
             [&] { return (mission.Truth(1).position_m - point).norm() < radius_m + 10.0; });
  const double arrived_s = mission.simulation.time_s() - commanded_s;
  std::printf("investigation %.0f m away: on the circle after %.0f s (allowed %.0f s)\n",
              distance_m, arrived_s, allowed_s);
  ASSERT_LT((mission.Truth(1).position_m - point).norm(), radius_m + 10.0);
  // Then it circles there at the loiter radius.
  double worst_radius_error_m = 0.0;
  mission.RunUntil(mission.simulation.time_s() + 60.0, [&] {
    worst_radius_error_m = std::max(
        worst_radius_error_m, std::abs((mission.Truth(1).position_m - point).norm() - radius_m));
  });
  EXPECT_LT(worst_radius_error_m, 10.0);
  EXPECT_EQ(vehicle.mode(), FlightMode::kInvestigate);
}

// After an investigation the search goes back to the point it left its lane and
// sweeps the rest of the lane: straight to the lane's end would leave a strip
// of it unseen.
TEST(Investigate, TheSearchResumesWhereItLeftTheLane) {
  sim2d::SimulationConfig config = OneVehicleWorld();
  Mission mission(config);
  agents::Vehicle& vehicle = mission.AddVehicle(agents::VehicleConfig{});
  StartLaneNorth(mission, 1200.0);
  RunUntilOr(mission, 200.0, [&] { return mission.Truth(1).position_m.y() > 300.0; });
  ASSERT_EQ(vehicle.mode(), FlightMode::kSearch);
  const Vec2 left_at = mission.Truth(1).position_m;

  // 300 m east of the lane, 60 s around it (its transit included).
  SendInvestigate(mission, Vec2(300.0, left_at.y()), 60);
  RunUntilOr(mission, mission.simulation.time_s() + 10.0,
             [&] { return vehicle.mode() == FlightMode::kInvestigate; });
  ASSERT_EQ(vehicle.mode(), FlightMode::kInvestigate);
  RunUntilOr(mission, mission.simulation.time_s() + 90.0,
             [&] { return vehicle.mode() == FlightMode::kSearch; });
  ASSERT_EQ(vehicle.mode(), FlightMode::kSearch);

  // Every 50 m of the lane past the point it left is flown over, within 10 m,
  // and none of the lane before it again.
  double lowest_north_m = std::numeric_limits<double>::infinity();
  std::vector<double> nearest_m;
  for (double y = left_at.y() + 50.0; y < 1150.0; y += 50.0) {
    nearest_m.push_back(std::numeric_limits<double>::infinity());
  }
  RunUntilOr(mission, mission.simulation.time_s() + 300.0, [&] {
    for (std::size_t i = 0; i < nearest_m.size(); ++i) {
      const Vec2 lane_point(0.0, left_at.y() + 50.0 * static_cast<double>(i + 1));
      nearest_m[i] = std::min(nearest_m[i], (mission.Truth(1).position_m - lane_point).norm());
    }
    lowest_north_m = std::min(lowest_north_m, mission.Truth(1).position_m.y());
    return vehicle.mode() != FlightMode::kSearch;
  });
  const double worst_m = *std::max_element(nearest_m.begin(), nearest_m.end());
  std::printf("resumed lane: every point of it flown within %.1f m\n", worst_m);
  EXPECT_LT(worst_m, 10.0);
  EXPECT_GT(lowest_north_m, left_at.y() - 30.0);
}

// The way back to the lane is flown at the lane's altitude, not at the
// investigation's (nor wherever the vehicle was when the investigation ended):
// the server predicts a drone flying back to its route at the altitude of the
// waypoint it resumes, and its neighbours' layers are kept from that one.
TEST(Investigate, TheWayBackToTheLaneIsFlownAtTheLanesAltitude) {
  sim2d::SimulationConfig config = OneVehicleWorld();
  Mission mission(config);
  agents::Vehicle& vehicle = mission.AddVehicle(agents::VehicleConfig{});
  StartLaneNorth(mission, 1200.0);
  RunUntilOr(mission, 200.0, [&] { return mission.Truth(1).position_m.y() > 300.0; });
  ASSERT_EQ(vehicle.mode(), FlightMode::kSearch);

  // 300 m east of the lane at 90 m (the lane: 60 m), 60 s around it.
  SendInvestigate(mission, Vec2(300.0, mission.Truth(1).position_m.y()), 60, 90.0);
  RunUntilOr(mission, mission.simulation.time_s() + 90.0, [&] {
    return vehicle.mode() == FlightMode::kInvestigate && mission.Truth(1).altitude_m > 85.0;
  });
  ASSERT_GT(mission.Truth(1).altitude_m, 85.0);
  RunUntilOr(mission, mission.simulation.time_s() + 90.0,
             [&] { return vehicle.mode() == FlightMode::kSearch; });
  ASSERT_EQ(vehicle.mode(), FlightMode::kSearch);
  ASSERT_GT(mission.Truth(1).position_m.x(), 100.0);  // still out at its circle

  // Halfway back to the lane it flies the lane's altitude already.
  RunUntilOr(mission, mission.simulation.time_s() + 120.0,
             [&] { return mission.Truth(1).position_m.x() < 60.0; });
  ASSERT_LT(mission.Truth(1).position_m.x(), 60.0);
  EXPECT_NEAR(mission.Truth(1).altitude_m, 60.0, 3.0);
}

}  // namespace
}  // namespace fireswarm::hil
