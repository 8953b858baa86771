// The runner's world set-up: the missions' altitudes as the vehicles fly them,
// and where the vehicles stand.
#include "world_setup.hpp"

#include <gtest/gtest.h>

#include <iterator>
#include <map>
#include <set>
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

TEST(InAltitudeLayers, EverySortieEndsWithItsWayHome) {
  std::vector<server::DroneMission> missions = SameRouteFor(2);
  missions[1].waypoints.push_back(missions[1].waypoints.front());
  missions[1].waypoints.push_back(missions[1].waypoints.back());
  missions[1].sortie_starts = {3};  // sorties of 3 and 2 waypoints
  const std::vector<server::DroneMission> out = InAltitudeLayers(missions);
  ASSERT_EQ(out[1].waypoints.size(), 7U);
  EXPECT_EQ(out[1].sortie_starts, (std::vector<std::size_t>{4}));
  const std::vector<std::vector<radio::Waypoint>> sorties = server::SortiesOf(out[1]);
  for (const std::vector<radio::Waypoint>& sortie : sorties) {
    EXPECT_EQ(sortie.back().flags, 0);
    EXPECT_DOUBLE_EQ(sortie.back().altitude_m, kFleetAltitudeM + kReturnLayerM);
    EXPECT_DOUBLE_EQ(sortie.back().lat_deg, sortie[sortie.size() - 2].lat_deg);
  }
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

TEST(InAltitudeLayers, LeavesAnEmptyMissionEmpty) {
  std::vector<server::DroneMission> missions(1);
  EXPECT_TRUE(InAltitudeLayers(missions).front().waypoints.empty());
}

}  // namespace
}  // namespace fireswarm::run::internal
