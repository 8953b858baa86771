#include "coverage_raster.hpp"

#include <gtest/gtest.h>

#include <boost/geometry.hpp>

namespace fireswarm::planner {
namespace {

namespace bg = boost::geometry;

MultiPolygon Square() {
  Polygon p{{{0, 0}, {0, 100}, {100, 100}, {100, 0}, {0, 0}}};
  bg::correct(p);
  return {p};
}

TEST(CoverageFraction, OneLaneSeesItsBand) {
  // A lane along y = 50 with a 20 m footprint radius sees the band 30..70: 40 %.
  const double seen = CoverageFraction(Square(), {Path{{-10, 50}, {110, 50}}}, 20.0, 1.0);
  EXPECT_NEAR(seen, 0.40, 0.011);
}

TEST(CoverageFraction, DiagonalLaneAndDiscEnds) {
  // A short segment: a capsule of area 2 r L + pi r^2 = 2*10*20 + 314.2 = 714.2 m2.
  const double seen = CoverageFraction(Square(), {Path{{40, 40}, {52, 56}}}, 10.0, 0.5);
  EXPECT_NEAR(seen * 10'000.0, 714.2, 15.0);
}

TEST(CoverageFraction, HolesAreNotCounted) {
  Polygon holed{{{0, 0}, {0, 100}, {100, 100}, {100, 0}, {0, 0}},
                {{{25, 25}, {75, 25}, {75, 75}, {25, 75}, {25, 25}}}};
  bg::correct(holed);
  // Four passes around the hole see the whole ring; the unseen hole does not count.
  const std::vector<Path> paths{Path{{0, 10}, {100, 10}}, Path{{0, 90}, {100, 90}},
                                Path{{10, 0}, {10, 100}}, Path{{90, 0}, {90, 100}}};
  EXPECT_DOUBLE_EQ(CoverageFraction({holed}, paths, 15.0, 1.0), 1.0);
  EXPECT_LT(CoverageFraction(Square(), paths, 15.0, 1.0), 0.80);
}

TEST(CoverageCell, StaysBetweenOneMetreAndATenthOfTheSweep) {
  EXPECT_DOUBLE_EQ(CoverageCellM(1e6, 80.0), 1.0);
  EXPECT_NEAR(CoverageCellM(1e8, 80.0), 5.0, 1e-9);
  EXPECT_DOUBLE_EQ(CoverageCellM(1e10, 80.0), 8.0);
}

}  // namespace
}  // namespace fireswarm::planner
