#include "fireswarm/planner/transit.hpp"

#include <gtest/gtest.h>

#include <boost/geometry.hpp>
#include <cmath>

#include "planner_test_helpers.hpp"
namespace fireswarm::planner {
namespace {

using testing::Rect;

namespace bg = boost::geometry;

MultiPolygon Block() {
  return MultiPolygon{Rect(400, -300, 600, 300)};
}
Box Bounds() {
  return Box{{-100, -1000}, {1100, 1000}};
}

TEST(TransitPlanner, StraightWhenClear) {
  const TransitPlanner planner(Block(), Bounds(), 1);
  const Path path = planner.Plan({0, 500}, {1000, 500});
  ASSERT_EQ(path.size(), 2u);
  EXPECT_TRUE(planner.IsClear({0, 500}, {1000, 500}));
}

TEST(TransitPlanner, GoesAroundANoFlyBlock) {
  const TransitPlanner planner(Block(), Bounds(), 1);
  EXPECT_FALSE(planner.IsClear({0, 0}, {1000, 0}));
  const Path path = planner.Plan({0, 0}, {1000, 0});
  ASSERT_GE(path.size(), 3u);
  EXPECT_EQ(bg::distance(path.front(), Point{0, 0}), 0.0);
  EXPECT_EQ(bg::distance(path.back(), Point{1000, 0}), 0.0);
  EXPECT_EQ(InteriorLengthM(path, Block()), 0.0);
  // Around the block's corners: at least sqrt(400^2 + 300^2) * 2 + 200, not much more.
  const auto length_m = static_cast<double>(bg::length(path));
  EXPECT_GE(length_m, 1199.0);
  EXPECT_LE(length_m, 1400.0);
}

TEST(TransitPlanner, SameSeedSamePath) {
  const TransitPlanner a(Block(), Bounds(), 7);
  const TransitPlanner b(Block(), Bounds(), 7);
  const Path pa = a.Plan({0, 0}, {1000, 0});
  const Path pb = b.Plan({0, 0}, {1000, 0});
  ASSERT_EQ(pa.size(), pb.size());
  for (std::size_t i = 0; i < pa.size(); ++i) {
    EXPECT_EQ(pa[i].x(), pb[i].x());
    EXPECT_EQ(pa[i].y(), pb[i].y());
  }
}

TEST(TransitPlanner, EndpointOnTheBoundaryIsAllowed) {
  const TransitPlanner planner(Block(), Bounds(), 1);
  const Path path = planner.Plan({400, 0}, {1000, 0});
  EXPECT_EQ(InteriorLengthM(path, Block()), 0.0);
}

TEST(TransitPlanner, RefusesAnEndpointInsideAZone) {
  const TransitPlanner planner(Block(), Bounds(), 1);
  EXPECT_THROW(planner.Plan({0, 0}, {500, 0}), std::runtime_error);
}

TEST(TransitPlanner, ACircleIsClearOnlyWhenItStaysOutOfEveryZone) {
  // Block: x 400..600, y -300..300.
  const TransitPlanner planner(Block(), Bounds(), 1);
  EXPECT_TRUE(planner.IsCircleClear({300, 0}, 50.0));    // 50 m short of the west edge
  EXPECT_FALSE(planner.IsCircleClear({300, 0}, 150.0));  // reaches 50 m in
  EXPECT_TRUE(planner.IsCircleClear({300, 0}, 100.0));   // touches the edge
  EXPECT_FALSE(planner.IsCircleClear({500, 0}, 20.0));   // centre in the zone
  // Around the whole block, never inside: farther than its farthest corner.
  EXPECT_TRUE(planner.IsCircleClear({500, 0}, 400.0));
  // Near a corner the nearest point is the corner, not an edge's line.
  EXPECT_TRUE(planner.IsCircleClear({380, 320}, 28.0));  // corner 28.3 m away
  EXPECT_FALSE(planner.IsCircleClear({380, 320}, 29.0));
  EXPECT_TRUE(TransitPlanner(MultiPolygon{}, Bounds(), 1).IsCircleClear({500, 0}, 20.0));
}

// Regression: RRTConnect returned the first path it found, around the far end of
// a long corridor (kilometres longer); the path must be the shortest one, around
// the near end: (-1500, 0) -> corner (-1800, -50) -> corner (-1800, -200) ->
// (-1500, -300), about 770 m (the corners are passed 1 cm off the zone).
TEST(TransitPlanner, GoesAroundTheNearEndOfALongCorridor) {
  const MultiPolygon corridor{Rect(-1800, -200, 1800, -50)};
  const TransitPlanner planner(corridor, Box{{-2500, -1000}, {2500, 1000}}, 1);
  const Path path = planner.Plan({-1500, 0}, {-1500, -300});
  EXPECT_EQ(InteriorLengthM(path, corridor), 0.0);
  const double shortest_m = std::hypot(300.0, 50.0) + 150.0 + std::hypot(300.0, 100.0);
  EXPECT_NEAR(static_cast<double>(bg::length(path)), shortest_m, 0.1);
}

// Regression: a lane end computed on a zone's slanted edge lies a rounding hair
// inside it; Plan threw "an endpoint is inside a no-fly zone" for it.
TEST(TransitPlanner, EndpointAHairInsideAZoneCountsAsOnItsBoundary) {
  MultiPolygon zones{Polygon{{{0, 0}, {1000, 300}, {1000, 400}, {0, 100}, {0, 0}}}};
  bg::correct(zones);
  const TransitPlanner planner(zones, Bounds(), 1);
  // On the lower edge y = 0.3 x, nudged 1e-9 m into the zone.
  const Point on_edge{500.0, 150.0 + 1e-9};
  ASSERT_TRUE(bg::within(on_edge, zones));
  EXPECT_FALSE(planner.IsInside(on_edge));
  Path path;
  ASSERT_NO_THROW(path = planner.Plan(on_edge, {500, 600}));
  EXPECT_EQ(InteriorLengthM(path, zones), 0.0);
  // Deeper than kOnBoundaryToleranceM is still refused.
  EXPECT_TRUE(planner.IsInside({500.0, 150.0 + 1e-3}));
  EXPECT_THROW(planner.Plan({500.0, 160.0}, {500, 600}), std::runtime_error);
}

TEST(InteriorLength, CountsOnlyTheInterior) {
  EXPECT_DOUBLE_EQ(InteriorLengthM(Path{{0, 0}, {1000, 0}}, Block()), 200.0);
  // Along the boundary: not inside.
  EXPECT_EQ(InteriorLengthM(Path{{400, -500}, {400, 500}}, Block()), 0.0);
  // Through a corner only.
  EXPECT_EQ(InteriorLengthM(Path{{300, -200}, {500, -400}}, Block()), 0.0);
}

}  // namespace
}  // namespace fireswarm::planner
