// DroneMission's sorties, the plan turned into missions and the launch sites
// taken off each sortie's ends (drone_mission.cpp).
#include <gtest/gtest.h>

#include <stdexcept>
#include <utility>
#include <vector>

#include "fireswarm/common/local_frame.hpp"
#include "fireswarm/server/mission_manager.hpp"

namespace fireswarm::server {
namespace {

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

TEST(ToDroneMissions, SplitsTheRouteIntoSortiesAfterEachReturn) {
  planner::Plan plan;
  planner::DronePlan drone;
  drone.receiver_id = 3;
  drone.launch = planner::Point(0.0, 0.0);
  // launch, lane, return (ends sortie 1), lane, launch (the last landing)
  drone.waypoints.push_back({{0, 0}, {46.0, -74.0}, false, false});
  drone.waypoints.push_back({{100, 0}, {46.0, -73.99}, false, true});
  drone.waypoints.push_back({{100, 80}, {46.001, -73.99}, false, false});
  drone.waypoints.push_back({{0, 0}, {46.0, -74.0}, true, false});
  drone.waypoints.push_back({{100, 160}, {46.002, -73.99}, false, true});
  drone.waypoints.push_back({{100, 240}, {46.003, -73.99}, false, false});
  drone.waypoints.push_back({{0, 0}, {46.0, -74.0}, false, false});
  plan.drones.push_back(drone);
  const DroneMission mission = ToDroneMissions(plan, 9, 60.0, 8.0).at(0);
  EXPECT_EQ(mission.sortie_starts, (std::vector<std::size_t>{4}));
  EXPECT_EQ(SortieCount(mission), 2U);
  EXPECT_EQ(SortieRange(mission, 0), (std::pair<std::size_t, std::size_t>{0, 4}));
  EXPECT_EQ(SortieRange(mission, 1), (std::pair<std::size_t, std::size_t>{4, 7}));
  EXPECT_THROW(SortieRange(mission, 2), std::out_of_range);
  EXPECT_EQ(SortieMissionId(mission, 1), 10);
  EXPECT_EQ(SortieOf(mission, 3), 0U);
  EXPECT_EQ(SortieOf(mission, 4), 1U);

  // Flown from the stands: each sortie loses the launch site at both ends.
  const common::LocalFrame frame{common::LatLon{46.0, -74.0}};
  const DroneMission flown = WithoutLaunchSite({mission}, frame, LaunchSitesOf(plan)).at(0);
  ASSERT_EQ(flown.waypoints.size(), 4U);
  EXPECT_EQ(flown.sortie_starts, (std::vector<std::size_t>{2}));
  EXPECT_EQ(flown.waypoints[0], mission.waypoints[1]);
  EXPECT_EQ(flown.waypoints[2], mission.waypoints[4]);
  EXPECT_EQ(SortiesOf(flown).at(1),
            (std::vector<radio::Waypoint>{mission.waypoints[4], mission.waypoints[5]}));
}

TEST(WithoutLaunchSite, EachDroneLosesOnlyItsOwnSite) {
  const common::LocalFrame frame{common::LatLon{46.0, -74.5}};
  const auto at = [&](double east_m, double north_m) {
    const common::LatLon p = frame.ToGeodetic({east_m, north_m});
    radio::Waypoint w;
    w.lat_deg = p.lat_deg;
    w.lon_deg = p.lon_deg;
    return w;
  };
  DroneMission west;
  west.vehicle = 1;
  west.waypoints = {at(0, 0), at(100, 0), at(0, 0)};
  DroneMission east;
  east.vehicle = 2;
  east.waypoints = {at(0, 0), at(500, 0), at(1'000, 0)};  // starts over the west site
  const std::vector<DroneMission> out =
      WithoutLaunchSite({west, east}, frame, {{1, {0.0, 0.0}}, {2, {1'000.0, 0.0}}});
  EXPECT_EQ(out[0].waypoints, (std::vector<radio::Waypoint>{at(100, 0)}));
  EXPECT_EQ(out[1].waypoints, (std::vector<radio::Waypoint>{at(0, 0), at(500, 0)}));
}

TEST(WithoutLaunchSite, DropsTheLaunchAtEitherEndAndKeepsReturnsBetweenSorties) {
  const common::LocalFrame frame{common::LatLon{46.0, -74.5}};
  const common::EastNorth launch{10.0, 20.0};
  const auto at = [&](double east_m, double north_m) {
    const common::LatLon p = frame.ToGeodetic({east_m, north_m});
    radio::Waypoint w;
    w.lat_deg = p.lat_deg;
    w.lon_deg = p.lon_deg;
    return w;
  };
  DroneMission mission;
  mission.vehicle = 1;
  // launch, lane, return between sorties, lane, launch, launch again
  mission.waypoints = {at(10, 20),   at(300, 20), at(10.2, 20),
                       at(300, 100), at(10, 20),  at(10, 20.5)};
  DroneMission idle;
  idle.vehicle = 2;
  idle.waypoints = {at(10, 20), at(10, 20)};
  const std::vector<DroneMission> out = WithoutLaunchSite({mission, idle}, frame, launch);
  ASSERT_EQ(out[0].waypoints.size(), 3u);
  EXPECT_EQ(out[0].waypoints[0], mission.waypoints[1]);
  EXPECT_EQ(out[0].waypoints[1], mission.waypoints[2]) << "the return between sorties stays";
  EXPECT_EQ(out[0].waypoints[2], mission.waypoints[3]);
  EXPECT_TRUE(out[1].waypoints.empty()) << "a route of only the launch site is nothing to fly";
}

}  // namespace
}  // namespace fireswarm::server
