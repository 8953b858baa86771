// The runner's world set-up: where the vehicles stand.
#include "world_setup.hpp"

#include <gtest/gtest.h>

#include <map>
#include <vector>

#include "small_area.hpp"

namespace fireswarm::run::internal {
namespace {

constexpr double kFleetAltitudeM = 60.0;

std::vector<server::DroneMission> SameRouteFor(int drones) {
  std::vector<server::DroneMission> missions;
  for (int k = 0; k < drones; ++k) {
    server::DroneMission mission;
    mission.vehicle = static_cast<std::uint8_t>(k + 1);
    for (int i = 0; i < 3; ++i) {
      radio::Waypoint waypoint;
      waypoint.lat_deg = 46.0 + 0.001 * i;
      waypoint.lon_deg = -74.0;
      waypoint.altitude_m = kFleetAltitudeM;
      waypoint.flags = 1;
      mission.waypoints.push_back(waypoint);
    }
    missions.push_back(mission);
  }
  return missions;
}

TEST(StandPositions, EachDroneStandsAroundItsOwnSite) {
  Scenario scenario = test::SmallArea("");
  scenario.fleet.count = 3;
  const common::EastNorth west{-300.0, -60.0};
  const common::EastNorth east{300.0, -60.0};
  const std::map<std::uint8_t, common::EastNorth> sites{{1, west}, {2, east}, {3, east}};
  const std::map<int, sim2d::Vec2> stands = StandPositions(scenario, SameRouteFor(3), sites);
  ASSERT_EQ(stands.size(), 3U);
  // A site's only drone stands on it; two share a ring around theirs.
  EXPECT_NEAR((stands.at(1) - sim2d::Vec2(west.east_m, west.north_m)).norm(), 0.0, 1e-9);
  for (const int id : {2, 3}) {
    const double from_east = (stands.at(id) - sim2d::Vec2(east.east_m, east.north_m)).norm();
    EXPECT_GT(from_east, 1.0) << id;
    EXPECT_LT(from_east, scenario.fleet.stand_spacing_m) << id;
  }
  EXPECT_GE((stands.at(2) - stands.at(3)).norm(), scenario.fleet.stand_spacing_m - 1e-9);
}

}  // namespace
}  // namespace fireswarm::run::internal
