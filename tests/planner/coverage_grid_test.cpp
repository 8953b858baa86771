// CoverageGrid: the raster the run's report and the server's mission_status_t
// both count coverage on. Footprints checked cell by cell on 5 m cells.
#include "fireswarm/planner/coverage_grid.hpp"

#include <gtest/gtest.h>

#include <boost/geometry.hpp>
#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "fireswarm/common/angles.hpp"
#include "planner/planner_test_helpers.hpp"

namespace fireswarm::planner {
namespace {

using testing::Rect;

const common::CameraModel& Seed() {
  return common::CameraModelByName("seed");
}  // 75 x 60 deg

constexpr double kNorth = 0.0;
constexpr double kEast = std::numbers::pi / 2.0;
constexpr double kSouth = std::numbers::pi;

TEST(CoverageGrid, ASquareHasItsCellsAndNoneSeenYet) {
  const CoverageGrid grid({Rect(0, 0, 100, 100)}, {});
  EXPECT_DOUBLE_EQ(grid.cell_m(), kCoverageGridCellM);
  EXPECT_EQ(grid.searchable_cells(), 400U);
  EXPECT_EQ(grid.seen_cells(), 0U);
  EXPECT_DOUBLE_EQ(grid.Fraction(), 0.0);
}

// Nadir at 20 m: 2 h tan(37.5 deg) = 30.7 m across, 2 h tan(30 deg) = 23.1 m
// along. Around (50, 50) that takes cell centres 37.5..62.5 across (6) and
// 42.5..57.5 along (4): 24 cells, whichever way the vehicle heads.
TEST(CoverageGrid, NadirFootprintMarksTheCellsUnderIt) {
  for (const double heading_rad : {kNorth, kEast}) {
    CoverageGrid grid({Rect(0, 0, 100, 100)}, {});
    grid.Mark({50.0, 50.0}, heading_rad, 20.0, Seed(), -90.0);
    EXPECT_EQ(grid.seen_cells(), 24U) << heading_rad;
    EXPECT_DOUBLE_EQ(grid.Fraction(), 24.0 / 400.0);
  }
}

// The bitset the command center sends: bit k = row * cols + col is Seen(row, col).
TEST(CoverageGrid, SeenBitsetHoldsEveryCellRowByRowFromTheSouthWest) {
  // 21 x 12 cells (not a whole number of bytes), a no-fly zone in the footprint.
  CoverageGrid grid({Rect(0, 0, 105, 60)}, {Rect(45, 25, 55, 35)});
  grid.Mark({50.0, 30.0}, kNorth, 20.0, Seed(), -90.0);
  grid.Mark({100.0, 55.0}, kNorth, 20.0, Seed(), -90.0);  // the last cells
  ASSERT_TRUE(grid.Seen(grid.rows() - 1, grid.cols() - 1));
  const std::vector<std::uint8_t> bits = grid.SeenBitset();
  const auto cells = static_cast<std::size_t>(grid.rows() * grid.cols());
  ASSERT_EQ(bits.size(), (cells + 7) / 8);
  std::size_t set = 0;
  for (int r = 0; r < grid.rows(); ++r) {
    for (int c = 0; c < grid.cols(); ++c) {
      const auto k = static_cast<std::size_t>(r * grid.cols() + c);
      const bool bit = ((static_cast<unsigned>(bits[k / 8]) >> (k % 8)) & 1U) != 0;
      EXPECT_EQ(bit, grid.Seen(r, c)) << r << ", " << c;
      set += bit ? 1 : 0;
    }
  }
  EXPECT_EQ(set, grid.seen_cells());
  EXPECT_GT(set, 0U);
}

TEST(CoverageGrid, ACellSeenTwiceCountsOnce) {
  CoverageGrid grid({Rect(0, 0, 100, 100)}, {});
  grid.Mark({50.0, 50.0}, kNorth, 20.0, Seed(), -90.0);
  grid.Mark({50.0, 50.0}, kNorth, 20.0, Seed(), -90.0);
  EXPECT_EQ(grid.seen_cells(), 24U);
  // Flying high over everything sees it all, and no more than all.
  grid.Mark({50.0, 50.0}, kNorth, 500.0, Seed(), -90.0);
  EXPECT_DOUBLE_EQ(grid.Fraction(), 1.0);
}

// A camera pitched 45 deg down sees from h / tan(75 deg) to h / tan(15 deg)
// ahead: heading north from the square's south edge it sees into the square,
// heading south it sees the ground beyond the edge (one row of cells at most).
TEST(CoverageGrid, ATiltedCameraLooksAhead) {
  CoverageGrid ahead({Rect(0, 0, 100, 100)}, {});
  ahead.Mark({50.0, 10.0}, kNorth, 20.0, Seed(), -45.0);
  CoverageGrid behind({Rect(0, 0, 100, 100)}, {});
  behind.Mark({50.0, 10.0}, kSouth, 20.0, Seed(), -45.0);
  EXPECT_GT(ahead.seen_cells(), 5 * behind.seen_cells());
  EXPECT_LE(behind.seen_cells(), 20U);
}

// Mark scans each row only where the row crosses the footprint. Whatever the
// heading (the axes, a hair off them, anything), pitch, height and place (off
// the edges too), it marks exactly the searchable cells whose centres lie in
// the footprint, every cell of the raster tested here one by one.
TEST(CoverageGrid, AFootprintAtAnyHeadingMarksExactlyTheCentresInIt) {
  std::mt19937_64 rng(18);
  std::uniform_real_distribution<double> place(-40.0, 340.0);
  std::uniform_real_distribution<double> turn(0.0, 2.0 * std::numbers::pi);
  std::uniform_real_distribution<double> height(3.0, 120.0);
  std::uniform_real_distribution<double> tilt(-90.0, -20.0);
  const std::vector<double> headings = {kNorth, kEast, kSouth, 1e-9, kEast - 1e-7, 1e-5};
  const common::CameraModel& camera = Seed();
  std::size_t marked_in_all = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const auto k = static_cast<std::size_t>(trial);
    const double heading = k < headings.size() ? headings[k] : turn(rng);
    const Eigen::Vector2d at(place(rng), place(rng));
    const double h = height(rng);
    const double pitch_deg = trial % 3 == 0 ? -90.0 : tilt(rng);
    CoverageGrid grid({Rect(0, 0, 300, 300)}, {Rect(120, 120, 160, 200)});
    grid.Mark(at, heading, h, camera, pitch_deg);

    const double depression = -pitch_deg * common::kRadPerDeg;
    const double half_v = camera.vfov_deg * common::kRadPerDeg / 2.0;
    const double near_m = h / std::tan(depression + half_v);
    const double far_angle = depression - half_v;
    const double far_m =
        far_angle > 0.0 ? std::min(h / std::tan(far_angle), kFarEdgeCapM) : kFarEdgeCapM;
    const double half_w = common::FootprintWidthM(camera, h, pitch_deg) / 2.0;
    const Eigen::Vector2d forward(std::sin(heading), std::cos(heading));
    const Eigen::Vector2d right(forward.y(), -forward.x());
    std::size_t expected = 0;
    for (int r = 0; r < grid.rows(); ++r) {
      for (int c = 0; c < grid.cols(); ++c) {
        const Eigen::Vector2d d =
            grid.south_west_en_m() + grid.cell_m() * Eigen::Vector2d(c + 0.5, r + 0.5) - at;
        const double along = d.dot(forward);
        const bool inside =
            along >= near_m && along <= far_m && std::abs(d.dot(right)) <= half_w;
        const bool seen = inside && grid.Searchable(r, c);
        ASSERT_EQ(grid.Seen(r, c), seen) << "trial " << trial << " cell " << r << ", " << c;
        expected += seen ? 1 : 0;
      }
    }
    EXPECT_EQ(grid.seen_cells(), expected) << "trial " << trial;
    marked_in_all += expected;
  }
  EXPECT_GT(marked_in_all, 10'000U);  // the footprints did land on the raster
}

// Holes of the area and no-fly zones are not searchable: seeing them adds nothing.
TEST(CoverageGrid, HolesAndNoFlyZonesAreNotCounted) {
  Polygon holed = Rect(0, 0, 100, 100);
  holed.inners().push_back(Rect(40, 40, 60, 60).outer());
  boost::geometry::correct(holed);
  CoverageGrid grid({holed}, {Rect(0, 0, 20, 100)});
  // 400 cells, minus the hole's 16 and the no-fly strip's 80.
  EXPECT_EQ(grid.searchable_cells(), 400U - 16U - 80U);
  grid.Mark({50.0, 50.0}, kNorth, 20.0, Seed(), -90.0);
  EXPECT_EQ(grid.seen_cells(), 24U - 16U);
  grid.Mark({10.0, 50.0}, kNorth, 20.0, Seed(), -90.0);  // over the no-fly strip
  EXPECT_EQ(grid.seen_cells(), 24U - 16U + 4U * 1U);     // its east edge reaches x = 22.5
}

// A star-shaped polygon of `points` vertices around `centre`, radii in [low, high).
Polygon Star(Point centre, double low, double high, int points, std::mt19937& random) {
  std::uniform_real_distribution<double> radius(low, high);
  Polygon star;
  for (int i = 0; i < points; ++i) {
    const double angle = 2.0 * std::numbers::pi * i / points;
    const double r = radius(random);
    star.outer().emplace_back(centre.x() + r * std::cos(angle), centre.y() + r * std::sin(angle));
  }
  star.outer().push_back(star.outer().front());
  return star;
}

// The raster is made row by row (scanline); it must say what Boost.Geometry says
// of every cell centre: covered by the area (holes out), not within a no-fly zone.
// Concave rings, a hole, two overlapping polygons, zones across the boundary and
// overlapping each other, nothing aligned with the cells.
TEST(CoverageGrid, SearchableCellsAreThoseBoostGeometryPlacesInTheAreaOutOfTheZones) {
  std::mt19937 random(7);
  Polygon forest = Star({513.3, 287.9}, 200.0, 500.0, 60, random);
  forest.inners().push_back(Star({480.0, 300.0}, 40.0, 120.0, 25, random).outer());
  Polygon meadow = Rect(700.3, -100.7, 1'100.1, 180.2);
  MultiPolygon area = {forest, meadow};
  Polygon triangle;
  triangle.outer() = {{300.1, 50.2}, {-50.3, 20.7}, {120.9, 400.4}, {300.1, 50.2}};
  MultiPolygon no_fly = {triangle, Star({150.0, 200.0}, 30.0, 90.0, 12, random),
                         Rect(900.2, 0.3, 1'300.7, 60.9)};
  boost::geometry::correct(area);
  boost::geometry::correct(no_fly);
  const CoverageGrid grid(area, no_fly);
  std::size_t searchable = 0;
  std::size_t outside = 0;
  const Eigen::Vector2d origin = grid.south_west_en_m();
  for (int r = 0; r < grid.rows(); ++r) {
    for (int c = 0; c < grid.cols(); ++c) {
      const Point centre(origin.x() + (c + 0.5) * grid.cell_m(),
                         origin.y() + (r + 0.5) * grid.cell_m());
      const bool expected =
          boost::geometry::covered_by(centre, area) && !boost::geometry::within(centre, no_fly);
      ASSERT_EQ(grid.Searchable(r, c), expected) << "row " << r << ", col " << c;
      (expected ? searchable : outside) += 1;
    }
  }
  EXPECT_EQ(grid.searchable_cells(), searchable);
  EXPECT_GT(searchable, 10'000U);
  EXPECT_GT(outside, 10'000U);
}

TEST(CoverageGrid, NothingBelowTheSearchAltitudeOrFromNonsense) {
  CoverageGrid grid({Rect(0, 0, 100, 100)}, {});
  grid.Mark({50.0, 50.0}, kNorth, kMinCoverageAltitudeM - 0.1, Seed(), -90.0);
  constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
  grid.Mark({kNan, 50.0}, kNorth, 20.0, Seed(), -90.0);
  grid.Mark({50.0, 50.0}, kNan, 20.0, Seed(), -90.0);
  grid.Mark({50.0, 50.0}, kNorth, kNan, Seed(), -90.0);
  // Far away (a vehicle reporting a wild position) is off the grid, not a crash.
  grid.Mark({1e12, -1e12}, kNorth, 20.0, Seed(), -90.0);
  EXPECT_EQ(grid.seen_cells(), 0U);
}

TEST(CoverageGrid, AnEmptyAreaHasNothingToSee) {
  CoverageGrid grid({}, {});
  grid.Mark({0.0, 0.0}, kNorth, 20.0, Seed(), -90.0);
  EXPECT_EQ(grid.searchable_cells(), 0U);
  EXPECT_DOUBLE_EQ(grid.Fraction(), 0.0);
}

// A large area gets coarser cells so the raster stays within kMaxCoverageCells.
TEST(CoverageGrid, ALargeAreaGetsCoarserCells) {
  const CoverageGrid grid({Rect(0, 0, 10'000, 10'000)}, {});
  EXPECT_NEAR(grid.cell_m(), std::sqrt(1e8 / kMaxCoverageCells), 1e-9);
  EXPECT_LE(static_cast<double>(grid.searchable_cells()), kMaxCoverageCells);
}

}  // namespace
}  // namespace fireswarm::planner
