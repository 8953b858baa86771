#include "lanes.hpp"

#include <gtest/gtest.h>

#include <boost/geometry.hpp>
#include <cmath>

namespace fireswarm::planner {
namespace {

namespace bg = boost::geometry;

Polygon Square(double side_m) {
  Polygon p{{{0, 0}, {0, side_m}, {side_m, side_m}, {side_m, 0}, {0, 0}}};
  bg::correct(p);
  return p;
}

TEST(CellLanes, SpacedOneSweepApartInsideTheSquare) {
  const double sweep = 50.0;
  const auto lanes = CellLanes(Square(500), sweep, sweep / 2 / 0.9);
  ASSERT_EQ(lanes.size(), 10u);
  for (std::size_t k = 0; k < lanes.size(); ++k) {
    EXPECT_NEAR(lanes[k].y_m, 25.0 + 50.0 * static_cast<double>(k), 1e-9);
    // Endpoints on the boundary (x = 0 and x = 500), the segment inside.
    EXPECT_NEAR(lanes[k].x_min_m, 0.0, 1e-9);
    EXPECT_NEAR(lanes[k].x_max_m, 500.0, 1e-9);
    if (k > 0) {
      EXPECT_NEAR(lanes[k].y_m - lanes[k - 1].y_m, sweep, 1e-9);
    }
  }
}

TEST(CellLanes, SpacingShrinksToFitAndNeverExceedsTheSweep) {
  const auto lanes = CellLanes(Square(520), 50.0, 50.0 / 2 / 0.9);
  ASSERT_EQ(lanes.size(), 11u);
  EXPECT_LE(lanes[1].y_m - lanes[0].y_m, 50.0);
  EXPECT_NEAR(lanes.front().y_m - lanes.front().band_lo_m, (lanes[1].y_m - lanes[0].y_m) / 2, 1e-9);
  EXPECT_NEAR(lanes.back().band_hi_m, 520.0, 1e-9);
}

TEST(CellLanes, ClippedToATriangleWithEndsOnItsBoundary) {
  Polygon triangle{{{0, 0}, {400, 400}, {800, 0}, {0, 0}}};
  bg::correct(triangle);
  const double sweep = 40.0;
  const double radius = sweep / 2 / 0.9;
  const auto lanes = CellLanes(triangle, sweep, radius);
  ASSERT_EQ(lanes.size(), 10u);
  for (const Lane& lane : lanes) {
    // The chord at y is [y, 800 - y]; a 45 deg side needs the lane to reach a
    // little further than the chord only where the footprint would miss the strip.
    EXPECT_LE(lane.x_min_m, lane.y_m + 1e-9);
    EXPECT_GE(lane.x_max_m, 800 - lane.y_m - 1e-9);
    const double half = (lane.band_hi_m - lane.band_lo_m) / 2;
    const double needed = lane.y_m - half;  // the strip's far corner
    EXPECT_LE(std::hypot(lane.x_min_m - needed, half), radius + 1e-9);
  }
}

TEST(LineIntervals, TwoIntervalsThroughAHole) {
  Polygon holed{{{0, 0}, {0, 10}, {10, 10}, {10, 0}, {0, 0}},
                {{{4, 4}, {6, 4}, {6, 6}, {4, 6}, {4, 4}}}};
  bg::correct(holed);
  const auto intervals = LineIntervals(holed, 5.0);
  ASSERT_EQ(intervals.size(), 2u);
  EXPECT_DOUBLE_EQ(intervals[0].second, 4.0);
  EXPECT_DOUBLE_EQ(intervals[1].first, 6.0);
}

TEST(LaneFrame, RoundTrip) {
  const LaneFrame frame{0.7};
  const Point p = frame.ToLocal(frame.ToLane(Point{12.5, -3.0}));
  EXPECT_NEAR(p.x(), 12.5, 1e-12);
  EXPECT_NEAR(p.y(), -3.0, 1e-12);
  // Lanes run along the direction: its unit vector maps to +x.
  const Point along = frame.ToLane(Point{std::cos(0.7), std::sin(0.7)});
  EXPECT_NEAR(along.x(), 1.0, 1e-12);
  EXPECT_NEAR(along.y(), 0.0, 1e-12);
}

}  // namespace
}  // namespace fireswarm::planner
