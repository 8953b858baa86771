// The runner's world set-up: the missions' altitudes as the vehicles fly them.
#include "world_setup.hpp"

#include <gtest/gtest.h>

#include <iterator>
#include <set>
#include <vector>

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

TEST(InAltitudeLayers, SearchesInLayersAndFliesHomeAtAnAltitudeOfItsOwn) {
  // Twenty sorties end together and all converge on the launch site: on three
  // search layers, seven drones would fly home at one altitude and cross near
  // the stands (swarm20, seed 11: 0.74 m).
  const std::vector<server::DroneMission> missions = InAltitudeLayers(SameRouteFor(20));
  std::set<double> return_altitudes;
  for (std::size_t k = 0; k < missions.size(); ++k) {
    const std::vector<radio::Waypoint>& route = missions[k].waypoints;
    ASSERT_EQ(route.size(), 4U) << "drone " << k;
    const double layer_m =
        kFleetAltitudeM + kAltitudeLayerM * static_cast<double>(k % kAltitudeLayers);
    for (std::size_t i = 0; i + 1 < route.size(); ++i) {
      EXPECT_DOUBLE_EQ(route[i].altitude_m, layer_m) << "drone " << k << " waypoint " << i;
    }
    // The way home starts over the last search waypoint: no lane, no detour.
    const radio::Waypoint& way_home = route.back();
    EXPECT_DOUBLE_EQ(way_home.lat_deg, route[2].lat_deg);
    EXPECT_DOUBLE_EQ(way_home.lon_deg, route[2].lon_deg);
    EXPECT_EQ(way_home.flags, 0);
    EXPECT_GE(way_home.altitude_m, kFleetAltitudeM);
    return_altitudes.insert(way_home.altitude_m);
  }
  ASSERT_EQ(return_altitudes.size(), missions.size());
  for (auto it = std::next(return_altitudes.begin()); it != return_altitudes.end(); ++it) {
    EXPECT_GE(*it - *std::prev(it), kReturnLayerM - 1e-9);
  }
}

TEST(InAltitudeLayers, LeavesAnEmptyMissionEmpty) {
  std::vector<server::DroneMission> missions(1);
  EXPECT_TRUE(InAltitudeLayers(missions).front().waypoints.empty());
}

}  // namespace
}  // namespace fireswarm::run::internal
