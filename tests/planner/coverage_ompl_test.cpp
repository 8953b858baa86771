// CoverOmpl: the viewpoint-tour coverage covers a region with holes and no-fly
// zones, never enters a zone, and repeats itself exactly.
#include <gtest/gtest.h>

#include <boost/geometry.hpp>  // buffer and its strategies

#include "coverage.hpp"
#include "fireswarm/planner/transit.hpp"
#include "planner_test_helpers.hpp"
namespace fireswarm::planner {
namespace {

using testing::Rect;

namespace bg = boost::geometry;

constexpr double kSweepWidthM = 50.0;
constexpr double kFootprintWidthM = kSweepWidthM / 0.9;  // 10 % side overlap

// The fraction of `region` within half a footprint of `path` (a footprint swept
// along the path, round at the turns).
double CoveredFraction(const Path& path, const MultiPolygon& region) {
  MultiPolygon swept;
  bg::buffer(path, swept, bg::strategy::buffer::distance_symmetric<double>(kFootprintWidthM / 2),
             bg::strategy::buffer::side_straight(), bg::strategy::buffer::join_round(16),
             bg::strategy::buffer::end_flat(), bg::strategy::buffer::point_circle(16));
  MultiPolygon covered;
  bg::intersection(region, swept, covered);

  return bg::area(covered) / bg::area(region);
}

struct Scene {
  MultiPolygon region;
  MultiPolygon no_fly;
};

// A 1 km x 800 m L-shaped block with a lake (a hole) and a no-fly zone that
// splits the upper part: legs between viewpoints must go around it.
Scene TestScene() {
  Scene scene;
  MultiPolygon block{Rect(0, 0, 1'000, 400)};
  MultiPolygon upper{Rect(0, 400, 500, 800)};
  MultiPolygon both;
  bg::union_(block, upper, both);
  scene.no_fly = {Rect(200, 450, 260, 900)};
  const MultiPolygon lake{Rect(600, 100, 800, 250)};
  MultiPolygon without_lake;
  bg::difference(both, lake, without_lake);
  bg::difference(without_lake, scene.no_fly, scene.region);
  return scene;
}

TEST(CoverOmpl, CoversTheRegionWithoutEnteringNoFlyZones) {
  const Scene scene = TestScene();
  const TransitPlanner transit(scene.no_fly, Box({-200, -200}, {1'200, 1'100}), 7);
  const Path path = CoverOmpl(scene.region, kSweepWidthM, Point(-50, -50), transit, 7);
  ASSERT_GT(path.size(), 100U);
  EXPECT_EQ(InteriorLengthM(path, scene.no_fly), 0.0);
  EXPECT_GE(CoveredFraction(path, scene.region), 0.995);
  // Roughly area / sweep width: not a wild detour.
  const double ideal_m = bg::area(scene.region) / kSweepWidthM;
  EXPECT_LT(bg::length(path), 1.5 * ideal_m);
}

TEST(CoverOmpl, IsDeterministic) {
  const Scene scene = TestScene();
  const TransitPlanner transit(scene.no_fly, Box({-200, -200}, {1'200, 1'100}), 3);
  const Path first = CoverOmpl(scene.region, kSweepWidthM, Point(0, 0), transit, 3);
  const Path second = CoverOmpl(scene.region, kSweepWidthM, Point(0, 0), transit, 3);
  ASSERT_EQ(first.size(), second.size());
  for (std::size_t i = 0; i < first.size(); ++i) {
    EXPECT_EQ(first[i].x(), second[i].x());
    EXPECT_EQ(first[i].y(), second[i].y());
  }
}

TEST(CoverOmpl, RejectsANonPositiveSweepWidthAndHandlesAnEmptyRegion) {
  const TransitPlanner transit({}, Box({0, 0}, {10, 10}), 1);
  EXPECT_THROW(CoverOmpl({Rect(0, 0, 10, 10)}, 0.0, Point(0, 0), transit, 1),
               std::invalid_argument);
  EXPECT_TRUE(CoverOmpl({}, kSweepWidthM, Point(0, 0), transit, 1).empty());
}

}  // namespace
}  // namespace fireswarm::planner
