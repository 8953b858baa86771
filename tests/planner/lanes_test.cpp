#include "lanes.hpp"

#include <gtest/gtest.h>

#include <boost/geometry.hpp>
#include <cmath>

namespace fireswarm::planner {
namespace {

namespace bg = boost::geometry;

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
