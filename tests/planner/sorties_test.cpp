#include "sorties.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <boost/geometry.hpp>
#include <stdexcept>

#include "fireswarm/planner/plan.hpp"

namespace fireswarm::planner {
namespace {

namespace bg = boost::geometry;
using ::testing::HasSubstr;

// Four 1 km lanes 100 m apart, flown at 10 m/s from a launch point at the origin.
Route FourLanes() {
  Route route;
  route.speed_mps = 10.0;
  route.Extend({0, 50}, -1, 0);
  for (int k = 0; k < 4; ++k) {
    const double y = 50.0 + 100.0 * k;
    const bool east = k % 2 == 0;
    if (k > 0) route.Extend({east ? 0.0 : 1000.0, y}, -1, 4.0);
    route.Extend({east ? 1000.0 : 0.0, y}, k, 0);
  }
  return route;
}

TransitPlanner Open() {
  return TransitPlanner(MultiPolygon{}, Box{{-500, -500}, {1500, 1000}}, 1);
}

TEST(FlyShare, OneSortieWhenItFits) {
  const Route route = FourLanes();
  const TransitPlanner transit = Open();
  const Flight flight = FlyShare(route, Share{0, route.TotalS(), 0}, {0, 0}, 1e5, transit);
  EXPECT_EQ(flight.sorties, 1);
  EXPECT_NEAR(flight.time_s, 5.0 + route.TotalS() + 35.0, 1e-9);
  EXPECT_EQ(bg::distance(flight.points.front().point, Point{0, 0}), 0.0);
  EXPECT_EQ(bg::distance(flight.points.back().point, Point{0, 0}), 0.0);
}

TEST(FlyShare, SplitsIntoSortiesWhenEnduranceIsShort) {
  const Route route = FourLanes();
  const TransitPlanner transit = Open();
  const double endurance_s = 250.0;  // about two lanes per sortie
  const Flight flight = FlyShare(route, Share{0, route.TotalS(), 0}, {0, 0}, endurance_s, transit);
  EXPECT_GE(flight.sorties, 2);
  // Every sortie fits: time between departures from and returns to launch.
  double sortie_s = 0.0;
  int returns = 0;
  for (std::size_t i = 1; i < flight.points.size(); ++i) {
    const double leg_m = bg::distance(flight.points[i - 1].point, flight.points[i].point);
    sortie_s += leg_m / route.speed_mps;
    if (flight.points[i].is_return) {
      EXPECT_EQ(bg::distance(flight.points[i].point, Point{0, 0}), 0.0);
      EXPECT_LE(sortie_s, endurance_s);
      sortie_s = 0.0;
      ++returns;
    }
  }
  EXPECT_EQ(returns, flight.sorties - 1);
}

TEST(FlyShare, RefusesWhenOneLaneExceedsTheEndurance) {
  const Route route = FourLanes();
  const TransitPlanner transit = Open();
  try {
    FlyShare(route, Share{0, route.TotalS(), 0}, {0, 0}, 150.0, transit);  // a lane is 100 s
    FAIL() << "accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr("endurance_s"));
  }
}

TEST(PlanSearch, SortiesAndRefusalThroughThePlan) {
  Polygon square{{{0, 0}, {0, 1000}, {1000, 1000}, {1000, 0}, {0, 0}}};
  const SearchArea area{common::LocalFrame{common::LatLon{46, 7}}, {square}, {}};
  FleetSpec fleet;
  fleet.receiver_ids = {1, 2};
  fleet.launch_points = {{0, 0}};
  fleet.camera = &common::CameraModelByName("seed");
  fleet.endurance_s = 600.0;
  const Plan plan = PlanSearch(area, fleet);
  for (const DronePlan& drone : plan.drones) EXPECT_GE(drone.sorties, 2);
  EXPECT_GE(plan.coverage, 0.995);
  fleet.endurance_s = 150.0;  // a 1 km lane and back from its far end alone takes longer
  EXPECT_THROW(PlanSearch(area, fleet), std::runtime_error);
}

}  // namespace
}  // namespace fireswarm::planner
