// The server's test fleet: helpers shared by the Server tests (server_test.cpp,
// server_commands_test.cpp, lcm_bridge_test.cpp): fake vehicles on a simulated
// channel (fake_fleet.hpp) flying missions the server uploaded and started.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <vector>

#include "fireswarm/common/local_frame.hpp"
#include "fireswarm/common/time.hpp"
#include "fireswarm/server/server.hpp"
#include "server/fake_fleet.hpp"

namespace fireswarm::server::testing {

inline const common::LocalFrame kFrame{common::LatLon{46.0, -74.5}};
inline constexpr Nanos kSecond = std::chrono::seconds(1);

// A searching vehicle at `east_m, north_m` of the frame's origin.
inline radio::Telemetry Searching(double east_m, double north_m, std::uint32_t time_ms) {
  const common::LatLon where = kFrame.ToGeodetic({east_m, north_m});
  radio::Telemetry telemetry;
  telemetry.time_ms = time_ms;
  telemetry.lat_deg = where.lat_deg;
  telemetry.lon_deg = where.lon_deg;
  telemetry.altitude_m = 60.0;
  telemetry.mode = radio::FlightMode::kSearch;
  telemetry.flags = radio::telemetry_flags::kGpsFix | radio::telemetry_flags::kMissionValid;
  telemetry.battery_percent = 90;
  telemetry.mission_id = 1;
  return telemetry;
}

// On the ground at (east, north), with a GPS fix: heard there, the server knows
// the drone's stand and clears its take-off (a drone not yet heard waits).
inline radio::Telemetry OnItsStand(double east_m, double north_m, std::uint32_t time_ms) {
  radio::Telemetry telemetry = Searching(east_m, north_m, time_ms);
  telemetry.altitude_m = 0.0;
  telemetry.mode = radio::FlightMode::kIdle;
  return telemetry;
}

inline radio::FireReport ReportAt(double east_m, double north_m, double observer_east_m,
                                  std::uint32_t time_ms) {
  const common::LatLon fire = kFrame.ToGeodetic({east_m, north_m});
  const common::LatLon observer = kFrame.ToGeodetic({observer_east_m, north_m});
  radio::FireReport report;
  report.time_ms = time_ms;
  report.lat_deg = fire.lat_deg;
  report.lon_deg = fire.lon_deg;
  report.sigma_north_m = 3.0;
  report.sigma_east_m = 3.0;
  report.observer_lat_deg = observer.lat_deg;
  report.observer_lon_deg = observer.lon_deg;
  report.observer_altitude_m = 60.0;
  report.pixel_count = 4;
  report.peak_temperature_c = 400.0;
  report.confidence = 0.9;
  return report;
}

inline std::vector<DroneMission> Missions(const std::vector<std::uint8_t>& ids, int waypoints = 3,
                                          double spacing_m = 50.0) {
  std::vector<DroneMission> missions;
  for (const std::uint8_t id : ids) {
    DroneMission m;
    m.vehicle = id;
    m.mission_id = 1;
    for (int i = 0; i < waypoints; ++i) {
      radio::Waypoint w;
      const common::LatLon p = kFrame.ToGeodetic({100.0 * i, spacing_m * id});
      w.lat_deg = p.lat_deg;
      w.lon_deg = p.lon_deg;
      w.altitude_m = 60.0;
      w.speed_mps = 10.0;
      m.waypoints.push_back(w);
    }
    missions.push_back(m);
  }
  return missions;
}

inline const radio::Command* LastOf(const FakeVehicle& vehicle, radio::CommandType type) {
  const auto& commands = vehicle.commands();
  const auto found = std::find_if(commands.rbegin(), commands.rend(),
                                  [&](const radio::Command& c) { return c.type == type; });
  return found == commands.rend() ? nullptr : &*found;
}

// Three vehicles flying a started mission: 1 at the origin, 2 at 300 m east, 3 at
// 2 km east.
struct Fleet {
  explicit Fleet(const ServerConfig& config = {}) : air(0.0), server(config, kFrame) {
    for (std::uint8_t id = 1; id <= 3; ++id) {
      air.Add(id);
      server.AddVehicle(id);
    }
    server.LoadMission(Missions({1, 2, 3}));
    air.vehicle(1).endpoint().SetTelemetry(Searching(0, 0, 1'000));
    air.vehicle(2).endpoint().SetTelemetry(Searching(300, 0, 1'000));
    air.vehicle(3).endpoint().SetTelemetry(Searching(2'000, 0, 1'000));
    EXPECT_TRUE(server.Handle({OperatorCommand::Kind::kStart, 0, {}, 0.0, "test"}, Nanos{0}));
    air.Run(server, 60 * kSecond, [&] { return server.state() == MissionState::kRunning; });
  }
  void RunFor(Nanos duration) { air.RunUntil(server, air.channel().now() + duration); }
  Air air;
  Server server;
};

// Lanes 200 m apart, 1 km north, one per waypoint pair, lane starts flagged.
inline std::vector<DroneMission> LaneMissions(const std::vector<std::uint8_t>& ids,
                                              int lanes_each) {
  std::vector<DroneMission> missions;
  int lane = 0;
  for (const std::uint8_t id : ids) {
    DroneMission m;
    m.vehicle = id;
    m.mission_id = 1;
    for (int i = 0; i < lanes_each; ++i, ++lane) {
      for (const double north : {0.0, 1000.0}) {
        const common::LatLon p = kFrame.ToGeodetic({200.0 * lane, north});
        radio::Waypoint w;
        w.lat_deg = p.lat_deg;
        w.lon_deg = p.lon_deg;
        w.altitude_m = 60.0 + id;
        w.speed_mps = 10.0;
        w.flags = north == 0.0 ? 1 : 0;
        m.waypoints.push_back(w);
      }
    }
    missions.push_back(m);
  }
  return missions;
}

// Vehicles 1..3 searching at 0, 400 and 800 m east fly LaneMissions({1, 2, 3}, 2),
// started and running.
inline void StartLaneMission(Air& air, Server& server) {
  for (std::uint8_t id = 1; id <= 3; ++id) {
    air.Add(id);
    server.AddVehicle(id);
    air.vehicle(id).endpoint().SetTelemetry(Searching(400.0 * (id - 1), 0, 1'000));
  }
  server.LoadMission(LaneMissions({1, 2, 3}, 2));
  ASSERT_TRUE(server.Handle({OperatorCommand::Kind::kStart, 0, {}, 0.0, "test"}, Nanos{0}));
  air.Run(server, 60 * kSecond, [&] { return server.state() == MissionState::kRunning; });
}

}  // namespace fireswarm::server::testing
