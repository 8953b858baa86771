// The scorer's stores that grow with time are bounded (issue 19's soak): the
// telemetry ages go to a fixed-memory histogram (tests/common/age_histogram_test.cpp),
// and a vehicle's track is thinned when it fills.
#include <gtest/gtest.h>

#include <utility>
#include <vector>

#include "fireswarm/run/runner.hpp"
#include "fireswarm/run/scenario.hpp"
#include "scoring.hpp"

namespace fireswarm::run::internal {
namespace {

// Three hours of a drone flying its rounds and parked between them: the
// report's track stays within kMaxTrackPoints (every 5 s would be 2,200 points)
// and still reaches across the area; the coverage series within kMaxSeriesPoints
// (every 10 s would be 1,100), still from start to end.
TEST(ScorerTrack, AVehiclesTrackIsThinnedWhenItFills) {
  const Scenario scenario = ParseScenario(R"(name: long
seed: 3
duration_s: 11000
area:
  polygon: [[7.0, 45.0], [7.010146, 45.0], [7.010146, 45.0045], [7.0, 45.0045]]
fleet:
  count: 1
  launch: {lat: 44.9995, lon: 7.005}
  swap_s: 60
patrol: {every_s: 900}
)",
                                          "long.yaml", ".");
  const RunResult result = RunScenario(scenario);
  ASSERT_GE(result.missions, 4) << "rounds flown";
  const VehicleOutcome& vehicle = result.report.vehicles.at(1);
  EXPECT_LE(vehicle.track.size(), kMaxTrackPoints + 1);
  EXPECT_GE(vehicle.track.size(), kMaxTrackPoints / 2);
  // It flew the area every round: the thinned track still reaches across it.
  double north_most = -90.0;
  for (const common::LatLon& p : vehicle.track) north_most = std::max(north_most, p.lat_deg);
  EXPECT_GT(north_most, 45.004);

  const std::vector<std::pair<double, double>>& series = result.report.coverage_over_time;
  EXPECT_LE(series.size(), kMaxSeriesPoints + 1);
  EXPECT_GE(series.size(), kMaxSeriesPoints / 2);
  EXPECT_LT(series.front().first, kCoverageSeriesS);
  EXPECT_EQ(series.back().first, 11'000.0);
}

}  // namespace
}  // namespace fireswarm::run::internal
