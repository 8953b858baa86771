#include "decomposition.hpp"

#include <gtest/gtest.h>

#include <boost/geometry.hpp>

#include "lanes.hpp"

namespace fireswarm::planner {
namespace {

namespace bg = boost::geometry;

Polygon FromRings(std::vector<Point> outer, std::vector<std::vector<Point>> inners = {}) {
  Polygon p;
  p.outer().assign(outer.begin(), outer.end());
  for (auto& ring : inners) p.inners().emplace_back(ring.begin(), ring.end());
  bg::correct(p);
  return p;
}

// A U opening north: two 100 m arms on a 300 m wide, 100 m tall base.
MultiPolygon UShape() {
  return {FromRings({{0, 0},
                     {300, 0},
                     {300, 300},
                     {200, 300},
                     {200, 100},
                     {100, 100},
                     {100, 300},
                     {0, 300},
                     {0, 0}})};
}

MultiPolygon HoledSquare() {
  return {FromRings({{0, 0}, {1000, 0}, {1000, 1000}, {0, 1000}, {0, 0}},
                    {{{400, 400}, {600, 400}, {600, 600}, {400, 600}, {400, 400}}})};
}

void ExpectTiles(const std::vector<Polygon>& cells, const MultiPolygon& shape) {
  double sum_m2 = 0.0;
  MultiPolygon all;
  for (const Polygon& cell : cells) {
    EXPECT_TRUE(bg::is_valid(cell));
    EXPECT_TRUE(cell.inners().empty());
    sum_m2 += static_cast<double>(bg::area(cell));
    MultiPolygon next;
    bg::union_(all, cell, next);
    all = next;
  }
  // No overlap (areas add up) and the union is the shape (symmetric difference ~0).
  EXPECT_NEAR(sum_m2, AreaM2(shape), 1e-6 * AreaM2(shape));
  MultiPolygon difference;
  bg::sym_difference(all, shape, difference);
  EXPECT_LT(AreaM2(difference), 1e-6 * AreaM2(shape));
}

bool IsMonotone(const Polygon& cell) {
  Box envelope;
  bg::envelope(cell, envelope);
  for (int i = 1; i < 100; ++i) {
    const double y = envelope.min_corner().y() +
                     i / 100.0 * (envelope.max_corner().y() - envelope.min_corner().y());
    if (LineIntervals(cell, y).size() > 1) return false;
  }
  return true;
}

TEST(Decomposition, ConvexSquareIsOneCell) {
  const MultiPolygon square{FromRings({{0, 0}, {500, 0}, {500, 500}, {0, 500}, {0, 0}})};
  const auto cells = Decompose(square, 0.3);
  ASSERT_EQ(cells.size(), 1u);
  ExpectTiles(cells, square);
}

TEST(Decomposition, UShapeSplitsIntoMonotoneCells) {
  const auto cells = DecomposeLaneFrame(UShape());
  EXPECT_GE(cells.size(), 2u);
  ExpectTiles(cells, UShape());
  for (const Polygon& cell : cells) EXPECT_TRUE(IsMonotone(cell));
}

TEST(Decomposition, UShapeAlongAnotherDirection) {
  const double direction = 0.4;
  const auto cells = Decompose(UShape(), direction);
  EXPECT_GE(cells.size(), 2u);
  ExpectTiles(cells, UShape());
  const LaneFrame frame{direction};
  for (const Polygon& cell : cells) EXPECT_TRUE(IsMonotone(frame.ToLane(cell)));
}

TEST(Decomposition, HoledSquareHasCellsAroundTheHole) {
  const MultiPolygon shape = HoledSquare();
  const auto cells = DecomposeLaneFrame(shape);
  EXPECT_GE(cells.size(), 4u);  // below, left, right, above the hole
  ExpectTiles(cells, shape);
  const MultiPolygon hole{FromRings({{400, 400}, {600, 400}, {600, 600}, {400, 600}, {400, 400}})};
  for (const Polygon& cell : cells) {
    MultiPolygon inside;
    bg::intersection(cell, hole, inside);
    EXPECT_LT(AreaM2(inside), 1e-6);
    EXPECT_TRUE(IsMonotone(cell));
  }
}

// Regression: a hole's bottom edge on a slab's bottom level made Boost return the
// pieces on both sides of the hole as one polygon joined along that edge.
TEST(Decomposition, HoleAndZonesSharingLevelsStayMonotone) {
  Polygon square = FromRings({{0, 0}, {10000, 0}, {10000, 10000}, {0, 10000}, {0, 0}});
  square.inners().push_back(
      FromRings({{3500, 3000}, {6500, 3000}, {6500, 6000}, {3500, 6000}, {3500, 3000}}).outer());
  bg::correct(square);
  MultiPolygon zones;
  for (const auto& [x, y] : std::vector<std::pair<double, double>>{
           {2000, 1500}, {6200, 3600}, {4400, 5700}, {2600, 7800}, {6800, 2900}, {7400, 2200}}) {
    zones.push_back(FromRings({{x, y}, {x + 500, y}, {x + 500, y + 800}, {x, y + 800}, {x, y}}));
  }
  MultiPolygon region;
  bg::difference(MultiPolygon{square}, zones, region);
  const auto cells = DecomposeLaneFrame(region);
  ExpectTiles(cells, region);
  for (const Polygon& cell : cells) EXPECT_TRUE(IsMonotone(cell));
}

}  // namespace
}  // namespace fireswarm::planner
