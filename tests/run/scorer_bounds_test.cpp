// The scorer's stores that grow with time are bounded (issue 19's soak): the
// telemetry ages go to a fixed-memory histogram whose percentiles agree with the
// exact nearest-rank ones, and a vehicle's track is thinned when it fills.
#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

#include "fireswarm/run/runner.hpp"
#include "fireswarm/run/scenario.hpp"
#include "scoring.hpp"

namespace fireswarm::run::internal {
namespace {

TEST(AgeHistogram, PercentilesAreTheExactOnesWithinABin) {
  std::mt19937_64 rng(7);
  std::exponential_distribution<double> ages(1.0 / 0.6);  // mean 0.6 s, a tail to seconds
  AgeHistogram histogram;
  std::vector<double> exact;
  for (int i = 0; i < 100'000; ++i) {
    const double age = ages(rng);
    histogram.Add(age);
    exact.push_back(age);
  }
  for (const double p : {0.01, 0.5, 0.9, 0.99, 0.999}) {
    const double want = Percentile(exact, p);
    const double got = histogram.Percentile(p);
    EXPECT_GE(got, want) << "p" << p;  // the bin's upper edge
    EXPECT_LE(got, want + 0.0101) << "p" << p;
  }
  EXPECT_EQ(histogram.count(), 100'000U);
}

TEST(AgeHistogram, CoarseBinsAboveTenSecondsAndTheLargestAgeCaps) {
  AgeHistogram histogram;
  EXPECT_EQ(histogram.Percentile(0.5), 0.0) << "empty";
  histogram.Add(12.3);
  histogram.Add(0.25);
  histogram.Add(5'000.0);  // beyond the last bin
  EXPECT_DOUBLE_EQ(histogram.Percentile(0.3), 0.26);
  EXPECT_DOUBLE_EQ(histogram.Percentile(0.6), 13.0);
  EXPECT_DOUBLE_EQ(histogram.Percentile(1.0), 5'000.0);
  AgeHistogram one;
  one.Add(0.123);
  EXPECT_DOUBLE_EQ(one.Percentile(0.99), 0.123) << "never above the largest age";
}

// 100 minutes of a drone flying its rounds and parked between them: the report's
// track stays within kMaxTrackPoints (every 5 s would be 1,200 points) and still
// reaches across the area.
TEST(ScorerTrack, AVehiclesTrackIsThinnedWhenItFills) {
  const Scenario scenario = ParseScenario(R"(name: long
seed: 3
duration_s: 6000
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
}

}  // namespace
}  // namespace fireswarm::run::internal
