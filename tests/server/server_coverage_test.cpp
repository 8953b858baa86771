// The server's coverage (ServerConfig::area): the cameras' footprints marked on
// planner::CoverageGrid from telemetry, as the run's report marks them from the
// truth, and what mission_status_t reports; without an area, the share of
// waypoints passed. Vehicles are radio endpoints on a simulated channel.
#include <gtest/gtest.h>

#include <boost/geometry/algorithms/correct.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "fireswarm/server/lcm_bridge.hpp"
#include "fireswarm/server/server.hpp"
#include "server/fake_fleet.hpp"
#include "server/server_fixture.hpp"

namespace fireswarm::server {
namespace {

using common::Nanos;
using testing::Air;

using testing::kFrame;
using testing::kSecond;

planner::Polygon AreaRect(double x0, double y0, double x1, double y1) {
  planner::Polygon p{{{x0, y0}, {x0, y1}, {x1, y1}, {x1, y0}, {x0, y0}}};
  boost::geometry::correct(p);
  return p;
}

// A 200 m square searched with the seed camera straight down: 1,600 cells of 5 m.
ServerConfig SquareConfig() {
  ServerConfig config;
  config.area = {AreaRect(0, 0, 200, 200)};
  config.camera = common::CameraModelByName("seed");
  config.camera_pitch_deg = -90.0;
  return config;
}

// Telemetry at (east_m, north_m) heading north, `altitude_m` up, with a GPS fix.
radio::Telemetry At(double east_m, double north_m, double altitude_m) {
  const common::LatLon where = kFrame.ToGeodetic({east_m, north_m});
  radio::Telemetry t;
  t.time_ms = 1'000;
  t.lat_deg = where.lat_deg;
  t.lon_deg = where.lon_deg;
  t.altitude_m = altitude_m;
  t.mode = radio::FlightMode::kSearch;
  t.flags = radio::telemetry_flags::kGpsFix;
  t.mission_id = 1;
  return t;
}

// One vehicle sending `telemetry`, heard for 3 s.
struct Heard {
  Heard(const ServerConfig& config, const radio::Telemetry& telemetry)
      : air(0.0), server(config, kFrame) {
    air.Add(1);
    server.AddVehicle(1);
    air.vehicle(1).endpoint().SetTelemetry(telemetry);
    air.RunUntil(server, 3 * kSecond);
  }
  Air air;
  Server server;
};

// Nadir at 20 m over (100, 100): 30.7 m across by 23.1 m along, the centres of
// 6 x 4 cells (planner's CoverageGridTest counts the same footprint).
TEST(ServerCoverage, TelemetryMarksTheCamerasFootprint) {
  const Heard heard(SquareConfig(), At(100.0, 100.0, 20.0));
  ASSERT_NE(heard.server.coverage(), nullptr);
  EXPECT_EQ(heard.server.coverage()->searchable_cells(), 1'600U);
  EXPECT_EQ(heard.server.coverage()->seen_cells(), 24U);
  const mission_status_t status = ToMissionStatus(heard.server, 3.0, 1);
  EXPECT_DOUBLE_EQ(status.coverage_fraction, 24.0 / 1'600.0);
}

// Without a fix the position means nothing (the vehicle sends 0, 0; here a
// plausible one, so only the flag can keep it off the grid).
TEST(ServerCoverage, TelemetryWithoutAGpsFixMarksNothing) {
  radio::Telemetry telemetry = At(100.0, 100.0, 20.0);
  telemetry.flags = 0;
  const Heard heard(SquareConfig(), telemetry);
  EXPECT_EQ(heard.server.coverage()->seen_cells(), 0U);
}

TEST(ServerCoverage, AVehicleOnTheGroundOrTakingOffMarksNothing) {
  const Heard heard(SquareConfig(), At(100.0, 100.0, planner::kMinCoverageAltitudeM - 0.5));
  EXPECT_EQ(heard.server.coverage()->seen_cells(), 0U);
}

std::vector<DroneMission> ThreeWaypoints() {
  DroneMission m;
  m.vehicle = 1;
  m.mission_id = 1;
  for (int i = 0; i < 3; ++i) {
    radio::Waypoint w;
    const common::LatLon p = kFrame.ToGeodetic({50.0 * i, 100.0});
    w.lat_deg = p.lat_deg;
    w.lon_deg = p.lon_deg;
    w.altitude_m = 20.0;
    w.speed_mps = 10.0;
    m.waypoints.push_back(w);
  }
  return {m};
}

// A drone flying to its third of three waypoints over (100, 100): with an area
// the status gives the cells seen, without one the waypoints passed (2 of 3).
double StatusCoverage(const ServerConfig& config) {
  Air air(0.0);
  Server server(config, kFrame);
  air.Add(1);
  server.AddVehicle(1);
  server.LoadMission(ThreeWaypoints());
  radio::Telemetry telemetry = At(100.0, 100.0, 20.0);
  telemetry.waypoint_index = 2;
  air.vehicle(1).endpoint().SetTelemetry(telemetry);
  EXPECT_TRUE(server.Handle({OperatorCommand::Kind::kStart, 0, {}, 0.0, "test"}, Nanos{0}));
  air.Run(server, 60 * kSecond, [&] { return server.state() == MissionState::kRunning; });
  air.RunUntil(server, air.channel().now() + 3 * kSecond);
  EXPECT_EQ(server.state(), MissionState::kRunning);
  return ToMissionStatus(server, 10.0, 1).coverage_fraction;
}

TEST(ServerCoverage, WithoutAnAreaTheStatusFallsBackToWaypointsPassed) {
  EXPECT_DOUBLE_EQ(StatusCoverage(ServerConfig{}), 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(StatusCoverage(SquareConfig()), 24.0 / 1'600.0);
  const Server server(ServerConfig{}, kFrame);
  EXPECT_EQ(server.coverage(), nullptr);
}

TEST(ServerCoverage, AnAreaNeedsAUsableCamera) {
  ServerConfig config = SquareConfig();
  config.camera.reset();
  try {
    Server server(config, kFrame);
    FAIL() << "an area without a camera was taken";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("camera"), std::string::npos) << e.what();
  }
  config = SquareConfig();
  config.camera_pitch_deg = 0.0;  // the optical axis on the horizon
  EXPECT_THROW(Server(config, kFrame), std::invalid_argument);
  config.camera_pitch_deg = -100.0;
  EXPECT_THROW(Server(config, kFrame), std::invalid_argument);
}

}  // namespace
}  // namespace fireswarm::server
