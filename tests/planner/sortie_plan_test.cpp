// Large-area planning: launch sites, sorties with swaps, lanes split between
// sorties, refusals, and the lower bound against a brute-force optimum.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <boost/geometry.hpp>
#include <cmath>
#include <cstdio>
#include <functional>
#include <stdexcept>
#include <string>

#include "fireswarm/planner/area_io.hpp"
#include "fireswarm/planner/footprint.hpp"
#include "fireswarm/planner/plan.hpp"
#include "planner_test_helpers.hpp"

namespace fireswarm::planner {
namespace {

using testing::Fleet;
using ::testing::HasSubstr;
using testing::Rect;

SearchArea Area(MultiPolygon area) {
  return SearchArea{common::LocalFrame{common::LatLon{50.0, 15.0}}, std::move(area), {}};
}

// Sorties flown by a drone: its landings between sorties plus the last one.
int Landings(const DronePlan& drone) {
  int returns = 0;
  for (const Waypoint& w : drone.waypoints) returns += w.is_return ? 1 : 0;
  return returns + 1;
}

TEST(LargeAreaPlan, TwoSitesAtTheEndsOfALongStripShareTheFleetEvenly) {
  const SearchArea area = Area({Rect(0, 0, 24'000, 3'000)});
  FleetSpec fleet = Fleet(6, {0, 1'500});
  fleet.launch_points = {{0, 1'500}, {24'000, 1'500}};
  fleet.endurance_s = 2'400;
  fleet.speed_mps = 12.0;
  const Plan plan = PlanSearch(area, fleet);
  int at_first = 0;
  double fastest_s = 1e300;
  for (const DronePlan& drone : plan.drones) {
    at_first += drone.site == 0 ? 1 : 0;
    EXPECT_EQ(drone.launch.x(), fleet.launch_points[drone.site].x());
    EXPECT_EQ(drone.waypoints.front().local.x(), drone.launch.x());
    EXPECT_EQ(drone.waypoints.back().local.x(), drone.launch.x());
    EXPECT_LE(drone.longest_sortie_s, fleet.endurance_s);
    fastest_s = std::min(fastest_s, drone.time_s);
  }
  EXPECT_EQ(at_first, 3);
  EXPECT_GE(plan.coverage, 0.995);
  EXPECT_LE(plan.makespan_s / plan.lower_bound_s, 1.25) << plan.lower_bound_basis;
  EXPECT_GE(fastest_s, 0.8 * plan.makespan_s);
}

TEST(LargeAreaPlan, FixedDronesPerSiteAreKept) {
  const SearchArea area = Area({Rect(0, 0, 12'000, 3'000)});
  FleetSpec fleet = Fleet(4, {0, 0});
  fleet.launch_points = {{0, 0}, {12'000, 0}, {6'000, 3'000}};
  fleet.site_drones = {0, 1, 3};
  const Plan plan = PlanSearch(area, fleet);
  std::vector<int> per_site(3, 0);
  for (const DronePlan& drone : plan.drones) ++per_site[drone.site];
  EXPECT_EQ(per_site, (std::vector<int>{0, 1, 3}));
  EXPECT_GE(plan.coverage, 0.995);
}

TEST(LargeAreaPlan, AnAreaNeedingThreeSortiesPerDroneCountsTheSwaps) {
  const SearchArea area = Area({Rect(0, 0, 2'000, 2'000)});
  FleetSpec fleet = Fleet(2, {1'000, 1'000});
  fleet.endurance_s = 1'200;
  fleet.swap_s = 300;
  const Plan plan = PlanSearch(area, fleet);
  for (const DronePlan& drone : plan.drones) {
    EXPECT_GE(drone.sorties, 3) << "drone " << drone.receiver_id;
    EXPECT_EQ(Landings(drone), drone.sorties);
    EXPECT_DOUBLE_EQ(drone.ground_s, (drone.sorties - 1) * fleet.swap_s);
    // Each sortie climbs to 60 m at 3 m/s and descends at 1 m/s.
    EXPECT_DOUBLE_EQ(drone.vertical_s, drone.sorties * (20.0 + 60.0));
    EXPECT_NEAR(drone.time_s,
                drone.sweep_s + drone.turn_s + drone.transit_s + drone.vertical_s + drone.ground_s,
                1e-6 * drone.time_s);
    EXPECT_LE(drone.longest_sortie_s, fleet.endurance_s);
  }
  EXPECT_GE(plan.coverage, 0.995);
}

// One lane 16 km long, 5 km beside the site: flying it whole and back takes 2,536 s,
// more than a sortie, though each end is within reach. It is split between
// sorties, and the pieces leave no gap.
TEST(LargeAreaPlan, ALaneLongerThanASortieIsSplitWithoutAGap) {
  FleetSpec fleet = Fleet(1, {8'000, 0});
  fleet.endurance_s = 2'400;
  fleet.speed_mps = 12.0;
  fleet.altitude_m = 60.0;
  const double half_m = SweepWidthM(fleet) / 2.0 * 0.9;
  const Plan plan = PlanSearch(Area({Rect(0, 5'000 - half_m, 16'000, 5'000 + half_m)}), fleet);
  ASSERT_EQ(plan.drones.size(), 1u);
  EXPECT_EQ(plan.drones[0].sorties, 2);
  EXPECT_GE(plan.coverage, 0.999);
  EXPECT_LE(plan.drones[0].longest_sortie_s, fleet.endurance_s);
}

TEST(LargeAreaPlan, RefusesAPointOutOfReachNamingItAndAcceptsWithASiteNearIt) {
  const SearchArea area = Area({Rect(0, 0, 2'000, 2'000), Rect(30'000, 0, 32'000, 2'000)});
  FleetSpec fleet = Fleet(2, {1'000, 1'000});
  fleet.endurance_s = 2'400;
  fleet.speed_mps = 12.0;
  try {
    PlanSearch(area, fleet);
    FAIL() << "planned an area 31 km out with 14 km of range";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr("endurance_s 2400 s is too short"));
    EXPECT_THAT(e.what(), HasSubstr("the area at (50.0"));  // lat, lon of the far corner
    EXPECT_THAT(e.what(), HasSubstr("from the nearest launch site"));
  }
  fleet.launch_points.push_back({31'000, 1'000});
  const Plan plan = PlanSearch(area, fleet);
  EXPECT_GE(plan.coverage, 0.995);
  EXPECT_NE(plan.drones[0].site, plan.drones[1].site);
}

// Thayatal's ragged valley (OSM): every sortie's ground is a few pieces at most,
// not the dozens of strips a route cut into shares gave. Its own separate parts
// (a MultiPolygon) and the bays a block crosses are what splits a sortie.
TEST(LargeAreaPlan, SortiesOnARaggedBoundaryAreFewPieces) {
  const SearchArea area =
      LoadSearchArea(std::filesystem::path(FIRESWARM_OSM_AREAS) / "thayatal.geojson");
  FleetSpec fleet = Fleet(10, DefaultLaunchPoint(area));
  fleet.altitude_m = 100.0;
  fleet.speed_mps = 12.0;
  fleet.endurance_s = 2'400;
  const Plan plan = PlanSearch(area, fleet);
  std::size_t sorties = 0, pieces = 0, single = 0;
  for (const DronePlan& drone : plan.drones) {
    ASSERT_EQ(drone.sortie_regions.size(), static_cast<std::size_t>(drone.sorties));
    for (const MultiPolygon& region : drone.sortie_regions) {
      ++sorties;
      pieces += region.size();
      single += region.size() == 1 ? 1U : 0U;
      EXPECT_LE(region.size(), 4U) << "drone " << drone.receiver_id;
    }
  }
  std::printf("[ figures  ] thayatal, 10 drones: %zu sorties, %zu pieces, %zu in one piece\n",
              sorties, pieces, single);
  EXPECT_LE(static_cast<double>(pieces) / static_cast<double>(sorties), 2.0);
  EXPECT_GE(plan.coverage, 0.995);
}

// A strip one lane wide from a site at its west end: any plan flies sorties out to
// x_k and back, each no longer than the endurance, with a swap between them. The
// brute-force optimum over cut points (every 10 m) is never below the bound, and
// the planner's makespan never below the optimum.
TEST(LowerBound, NeverAboveABruteForceOptimumOnAOneLaneStrip) {
  for (const double length_m : {1'500.0, 4'000.0, 7'000.0}) {
    for (const double endurance_s : {700.0, 1'000.0, 2'000.0}) {
      FleetSpec fleet = Fleet(1, {0, 0});
      fleet.speed_mps = 10.0;
      fleet.endurance_s = endurance_s;
      fleet.swap_s = 120.0;
      fleet.turn_cost_s = 0.0;
      const double half_m = SweepWidthM(fleet) / 2.0 * 0.9;
      const SearchArea area = Area({Rect(0, -half_m, length_m, half_m)});
      // Optimum: sorties reaching x_1 < x_2 < ... < x_k = length, each 2 x_i / v
      // and its climb and descent.
      const double vertical_s =
          fleet.altitude_m / fleet.climb_mps + fleet.altitude_m / fleet.descent_mps;
      const double step_m = 10.0;
      const auto steps = static_cast<int>(length_m / step_m);
      std::vector<double> best(static_cast<std::size_t>(steps) + 1, 1e300);
      best[0] = -fleet.swap_s;  // no swap before the first sortie
      for (int i = 1; i <= steps; ++i) {
        const double sortie_s = 2.0 * i * step_m / fleet.speed_mps + vertical_s;
        if (sortie_s > endurance_s) break;
        for (int j = 0; j < i; ++j) {
          // The sortie that reaches i sweeps (j, i]: out and back through the swept part.
          best[static_cast<std::size_t>(i)] =
              std::min(best[static_cast<std::size_t>(i)],
                       best[static_cast<std::size_t>(j)] + fleet.swap_s + sortie_s);
        }
      }
      const double optimum_s = best[static_cast<std::size_t>(steps)];
      SCOPED_TRACE(std::to_string(length_m) + " m, endurance " + std::to_string(endurance_s));
      if (optimum_s >= 1e299) {
        if (2.0 * (length_m - SweepWidthM(fleet)) / fleet.speed_mps + vertical_s > endurance_s) {
          EXPECT_THROW(PlanSearch(area, fleet), std::runtime_error);
        }
        continue;
      }
      const Plan plan = PlanSearch(area, fleet);
      EXPECT_LE(plan.lower_bound_s, optimum_s + 1e-6) << plan.lower_bound_basis;
      EXPECT_GE(plan.makespan_s, optimum_s - 2.0 * step_m / fleet.speed_mps);
    }
  }
}

}  // namespace
}  // namespace fireswarm::planner
