#include "fireswarm/server/handover.hpp"

#include <gtest/gtest.h>

#include <boost/geometry/algorithms/correct.hpp>
#include <cmath>
#include <set>
#include <utility>
#include <vector>

#include "fireswarm/planner/transit.hpp"
#include "server/server_fixture.hpp"

namespace fireswarm::server {
namespace {

using testing::kFrame;

radio::Waypoint At(double east_m, double north_m, bool lane_start, double altitude_m = 60.0) {
  const common::LatLon p = kFrame.ToGeodetic({east_m, north_m});
  radio::Waypoint w;
  w.lat_deg = p.lat_deg;
  w.lon_deg = p.lon_deg;
  w.altitude_m = altitude_m;
  w.speed_mps = 10.0;
  w.flags = lane_start ? 1 : 0;
  return w;
}

// A lawnmower of `lanes` north-south lanes 1 km long, 80 m apart from `east_m`.
std::vector<radio::Waypoint> Lawnmower(double east_m, int lanes, double altitude_m) {
  std::vector<radio::Waypoint> route;
  for (int i = 0; i < lanes; ++i) {
    const double e = east_m + 80.0 * i;
    const bool up = i % 2 == 0;
    route.push_back(At(e, up ? 0.0 : 1000.0, true, altitude_m));
    route.push_back(At(e, up ? 1000.0 : 0.0, false, altitude_m));
  }
  return route;
}

Taker TakerAt(std::uint8_t id, double east_m, std::vector<radio::Waypoint> remaining,
              double altitude_m) {
  Taker t;
  t.vehicle = id;
  t.position_en_m = Eigen::Vector2d(east_m, 0.0);
  t.remaining = std::move(remaining);
  t.altitude_m = altitude_m;
  t.speed_mps = 9.0;
  return t;
}

// Lane key: its two ends rounded to the metre, in either direction.
std::set<std::pair<long, long>> LanesIn(const std::vector<radio::Waypoint>& route) {
  std::set<std::pair<long, long>> lanes;
  for (std::size_t i = 0; i + 1 < route.size(); ++i) {
    if ((route[i].flags & 1) == 0) continue;
    const common::EastNorth a = kFrame.ToLocal({route[i].lat_deg, route[i].lon_deg});
    const common::EastNorth b = kFrame.ToLocal({route[i + 1].lat_deg, route[i + 1].lon_deg});
    const long east = std::lround(a.east_m);
    EXPECT_EQ(east, std::lround(b.east_m)) << "a lane is north-south";
    lanes.insert({east, std::lround(std::max(a.north_m, b.north_m))});
  }
  return lanes;
}

TEST(HandOverLanes, EveryLostLaneGoesToExactlyOneTakerAfterItsOwnRoute) {
  // The lost drone had 6 lanes left in the middle; takers on either side.
  const std::vector<radio::Waypoint> orphaned = Lawnmower(1000.0, 6, 63.0);
  const std::vector<radio::Waypoint> west_own = Lawnmower(0.0, 2, 60.0);
  const std::vector<radio::Waypoint> east_own = Lawnmower(2000.0, 2, 66.0);
  const auto routes =
      HandOverLanes(orphaned, {TakerAt(1, 0.0, west_own, 60.0), TakerAt(2, 2000.0, east_own, 66.0)},
                    kFrame)
          .routes;
  ASSERT_EQ(routes.size(), 2U);
  const std::vector<radio::Waypoint>& west = routes.at(1);
  const std::vector<radio::Waypoint>& east = routes.at(2);
  // Own waypoints first, unchanged.
  ASSERT_GT(west.size(), west_own.size());
  EXPECT_TRUE(std::equal(west_own.begin(), west_own.end(), west.begin()));
  EXPECT_TRUE(std::equal(east_own.begin(), east_own.end(), east.begin()));
  // The lost lanes, each once, between them; at the taker's own altitude and speed.
  const std::vector<radio::Waypoint> west_added(west.begin() + 4, west.end());
  const std::vector<radio::Waypoint> east_added(east.begin() + 4, east.end());
  std::set<std::pair<long, long>> given = LanesIn(west_added);
  const std::set<std::pair<long, long>> east_lanes = LanesIn(east_added);
  for (const auto& lane : east_lanes) EXPECT_TRUE(given.insert(lane).second) << "given twice";
  EXPECT_EQ(given, LanesIn(orphaned));
  for (const radio::Waypoint& w : west_added) EXPECT_DOUBLE_EQ(w.altitude_m, 60.0);
  for (const radio::Waypoint& w : east_added) EXPECT_DOUBLE_EQ(w.altitude_m, 66.0);
  for (const radio::Waypoint& w : east_added) EXPECT_DOUBLE_EQ(w.speed_mps, 9.0);
  // Shared in two runs, the western lanes to the western taker.
  EXPECT_GE(LanesIn(west_added).size(), 2U);
  EXPECT_GE(east_lanes.size(), 2U);
  EXPECT_LT(LanesIn(west_added).rbegin()->first, east_lanes.begin()->first);
}

TEST(HandOverLanes, ATakerWithMuchLeftGetsFewerLanes) {
  const std::vector<radio::Waypoint> orphaned = Lawnmower(1000.0, 6, 60.0);
  const auto routes =
      HandOverLanes(orphaned,
                    {TakerAt(1, 900.0, Lawnmower(0.0, 6, 60.0), 60.0), TakerAt(2, 900.0, {}, 63.0)},
                    kFrame)
          .routes;
  ASSERT_TRUE(routes.contains(2));
  const std::size_t busy = routes.contains(1) ? LanesIn(routes.at(1)).size() - 6 : 0;
  const std::size_t idle = LanesIn(routes.at(2)).size();
  EXPECT_EQ(busy + idle, 6U);
  EXPECT_GT(idle, busy);
}

TEST(HandOverLanes, NothingToHandOverWithoutALane) {
  // Only its way home was left.
  const std::vector<radio::Waypoint> orphaned = {At(0, 0, false), At(0, 500, false)};
  EXPECT_TRUE(HandOverLanes(orphaned, {TakerAt(1, 0.0, {}, 60.0)}, kFrame).routes.empty());
  EXPECT_TRUE(HandOverLanes(Lawnmower(0.0, 2, 60.0), {}, kFrame).routes.empty());
}

// The taker's path as flown: from where it is through every waypoint, in the
// planner's (east, north) metres.
planner::Path FlownPath(const Taker& taker, const std::vector<radio::Waypoint>& route) {
  planner::Path path{{taker.position_en_m.x(), taker.position_en_m.y()}};
  for (const radio::Waypoint& w : route) {
    const common::EastNorth p = kFrame.ToLocal({w.lat_deg, w.lon_deg});
    path.emplace_back(p.east_m, p.north_m);
  }
  return path;
}

planner::Polygon Rect(double east0, double north0, double east1, double north1) {
  planner::Polygon p{{{east0, north0}, {east0, north1}, {east1, north1}, {east1, north0}}};
  boost::geometry::correct(p);
  return p;
}

TEST(HandOverLanes, JoinsGoAroundTheNoFlyZones) {
  // Two lost lanes north-south at 1000 and 1300 m east. One zone lies across the
  // straight way from the taker (200 m north, west of it) to the first lane, one
  // across the join at the lanes' north ends.
  const std::vector<radio::Waypoint> orphaned = {At(1000, 0, true), At(1000, 1000, false),
                                                 At(1300, 1000, true), At(1300, 0, false)};
  const planner::MultiPolygon zones{Rect(400, -300, 600, 800), Rect(1100, 900, 1200, 1100)};
  const planner::TransitPlanner around(zones, planner::Box{{-1000, -1000}, {2500, 2500}}, 1);
  const Taker taker = TakerAt(1, 0.0, {}, 60.0);
  Taker north_of_origin = taker;
  north_of_origin.position_en_m = Eigen::Vector2d(0.0, 200.0);

  // Straight, both joins would cross a zone.
  const LaneHandOver straight = HandOverLanes(orphaned, {north_of_origin}, kFrame);
  ASSERT_TRUE(straight.routes.contains(1));
  EXPECT_GT(planner::InteriorLengthM(FlownPath(north_of_origin, straight.routes.at(1)), zones),
            100.0);

  const LaneHandOver routed = HandOverLanes(orphaned, {north_of_origin}, kFrame, &around);
  ASSERT_TRUE(routed.routes.contains(1));
  const std::vector<radio::Waypoint>& route = routed.routes.at(1);
  EXPECT_EQ(planner::InteriorLengthM(FlownPath(north_of_origin, route), zones), 0.0);
  EXPECT_EQ(routed.straight_joins, 0);
  // The same lanes, with the transit's corners between them as plain waypoints.
  EXPECT_EQ(LanesIn(route), LanesIn(orphaned));
  EXPECT_GT(route.size(), orphaned.size());
  for (const radio::Waypoint& w : route) EXPECT_DOUBLE_EQ(w.altitude_m, 60.0);
}

TEST(HandOverLanes, ATakerEndsWhereItsOwnRouteEndedGoingAroundTheZones) {
  // Its own route ends on the way home, over the launch site at its return
  // altitude (75 m); the lost lanes lie east, a zone between them and home.
  const std::vector<radio::Waypoint> own = {At(0, 500, true), At(0, 900, false),
                                            At(0, 0, false, 75.0)};
  const std::vector<radio::Waypoint> orphaned = {At(1000, 0, true), At(1000, 1000, false)};
  const planner::MultiPolygon zones{Rect(400, 300, 600, 700)};
  const planner::TransitPlanner around(zones, planner::Box{{-1000, -1000}, {2500, 2500}}, 1);
  const Taker taker = TakerAt(1, 0.0, own, 60.0);
  const LaneHandOver handed = HandOverLanes(orphaned, {taker}, kFrame, &around);
  ASSERT_TRUE(handed.routes.contains(1));
  const std::vector<radio::Waypoint>& route = handed.routes.at(1);
  EXPECT_EQ(LanesIn(route), (std::set<std::pair<long, long>>{{0, 900}, {1000, 1000}}));
  // Back to the end of its own route, at its altitude, and no lane starts there.
  const common::EastNorth end = kFrame.ToLocal({route.back().lat_deg, route.back().lon_deg});
  EXPECT_NEAR(end.east_m, 0.0, 0.01);
  EXPECT_NEAR(end.north_m, 0.0, 0.01);
  EXPECT_DOUBLE_EQ(route.back().altitude_m, 75.0);
  EXPECT_EQ(route.back().flags, 0);
  EXPECT_EQ(planner::InteriorLengthM(FlownPath(taker, route), zones), 0.0);
}

TEST(HandOverLanes, AJoinThatCannotBeRoutedStaysStraightAndIsCounted) {
  // The taker has drifted 50 m into a zone: no transit can start there.
  const std::vector<radio::Waypoint> orphaned = {At(1000, 0, true), At(1000, 1000, false)};
  const planner::MultiPolygon zones{Rect(-100, -100, 100, 100)};
  const planner::TransitPlanner around(zones, planner::Box{{-1000, -1000}, {2500, 2500}}, 1);
  const LaneHandOver handed =
      HandOverLanes(orphaned, {TakerAt(1, 50.0, {}, 60.0)}, kFrame, &around);
  EXPECT_EQ(handed.straight_joins, 1);
  ASSERT_TRUE(handed.routes.contains(1));
  EXPECT_EQ(handed.routes.at(1).size(), 2U);
}

}  // namespace
}  // namespace fireswarm::server
