#include "partition.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <boost/geometry.hpp>

#include "fireswarm/planner/plan.hpp"
#include "lanes.hpp"
#include "planner_test_helpers.hpp"
namespace fireswarm::planner {
namespace {

using testing::Fleet;

namespace bg = boost::geometry;

Polygon Ring(std::vector<Point> points) {
  Polygon p;
  p.outer().assign(points.begin(), points.end());
  bg::correct(p);
  return p;
}

void ExpectBalancedContiguousCover(const MultiPolygon& shape, const FleetSpec& fleet) {
  const SearchArea area{common::LocalFrame{common::LatLon{46, 7}}, shape, {}};
  const Plan plan = PlanSearch(area, fleet);
  double lo = 1e300, hi = 0.0, sum_m2 = 0.0;
  MultiPolygon all;
  for (const DronePlan& drone : plan.drones) {
    lo = std::min(lo, drone.time_s);
    hi = std::max(hi, drone.time_s);
    EXPECT_EQ(drone.region.size(), 1u) << "drone " << drone.receiver_id << " region in pieces";
    sum_m2 += AreaM2(drone.region);
    MultiPolygon next;
    bg::union_(all, drone.region, next);
    all = next;
  }
  EXPECT_LE((hi - lo) / hi, 0.05) << "fastest " << lo << " s, slowest " << hi << " s";
  MultiPolygon missing;
  bg::difference(shape, all, missing);
  EXPECT_LT(AreaM2(missing), 1e-6 * AreaM2(shape));
  EXPECT_NEAR(sum_m2, AreaM2(shape), 1e-6 * AreaM2(shape));  // no overlap
}

TEST(PartitionRoute, BalancedOnASquare) {
  ExpectBalancedContiguousCover({Ring({{0, 0}, {3000, 0}, {3000, 3000}, {0, 3000}, {0, 0}})},
                                Fleet(5, {-50, -50}));
}

TEST(PartitionRoute, BalancedOnAConcaveArea) {
  // An L: the route passes from one cell to the next across their common edge.
  ExpectBalancedContiguousCover(
      {Ring({{0, 0}, {3000, 0}, {3000, 1200}, {1200, 1200}, {1200, 3000}, {0, 3000}, {0, 0}})},
      Fleet(4, {1500, -100}));
}

TEST(PartitionRoute, EveryDroneGetsItsOwnLaunch) {
  Route route;
  route.speed_mps = 1.0;
  route.Extend({0, 0}, -1, 0);
  route.Extend({1000, 0}, -1, 0);
  const std::vector<Point> launches{{1000, 0}, {0, 0}};
  const auto shares =
      PartitionRoute(route, launches, [](Point a, Point b) { return bg::distance(a, b); });
  // The drone launching at x = 0 takes the first half.
  EXPECT_NEAR(shares[1].begin_s, 0.0, 1e-9);
  EXPECT_NEAR(shares[1].end_s, 500.0, 1e-2);
  EXPECT_NEAR(shares[0].end_s, 1000.0, 1e-9);
  EXPECT_NEAR(shares[0].time_s, shares[1].time_s, 1e-1);
}

TEST(Route, AtAndSliceFollowTheTurnsAndSegments) {
  Route route;
  route.speed_mps = 2.0;
  route.Extend({0, 0}, -1, 0);
  route.Extend({10, 0}, 0, 0);
  route.Extend({10, 10}, -1, 4.0);  // a 4 s turn at (10, 0)
  EXPECT_DOUBLE_EQ(route.TotalS(), 5.0 + 4.0 + 5.0);
  EXPECT_DOUBLE_EQ(route.At(7.0).x(), 10.0);
  EXPECT_DOUBLE_EQ(route.At(7.0).y(), 0.0);
  EXPECT_DOUBLE_EQ(route.At(11.5).y(), 5.0);
  const Path slice = route.Slice(2.5, 11.5);
  ASSERT_EQ(slice.size(), 3u);
  EXPECT_DOUBLE_EQ(slice.front().x(), 5.0);
  EXPECT_DOUBLE_EQ(slice.back().y(), 5.0);
}

}  // namespace
}  // namespace fireswarm::planner
