#include "fireswarm/agents/state_estimator.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <random>

#include "fireswarm/common/local_frame.hpp"

namespace fireswarm::agents {
namespace {

using common::EastNorth;
using common::LatLon;
using common::LocalFrame;
using std::chrono::milliseconds;

constexpr LatLon kLaunch{45.2, 7.6};
constexpr double kEstimateTolerance = 1e-6;

SensorInputs Fix(LatLon where, double velocity_east_mps = 0.0, double velocity_north_mps = 0.0) {
  SensorInputs inputs;
  GpsInput gps;
  gps.lat_deg = where.lat_deg;
  gps.lon_deg = where.lon_deg;
  gps.velocity_east_mps = velocity_east_mps;
  gps.velocity_north_mps = velocity_north_mps;
  inputs.gps = gps;
  return inputs;
}

SensorInputs Baro(double altitude_m) {
  SensorInputs inputs;
  inputs.baro = BaroInput{altitude_m};
  return inputs;
}

// --- position

TEST(StateEstimator, HasNoPositionOrFrameBeforeTheFirstFix) {
  StateEstimator estimator;
  estimator.Update(Nanos{0}, Baro(100.0));
  EXPECT_FALSE(estimator.estimate().has_position);
  EXPECT_FALSE(estimator.frame().has_value());
}

TEST(StateEstimator, LocalFrameIsSetAtTheFirstFix) {
  StateEstimator estimator;
  estimator.Update(Nanos{0}, Fix(kLaunch));
  ASSERT_TRUE(estimator.frame().has_value());
  EXPECT_EQ(estimator.frame()->origin().lat_deg, kLaunch.lat_deg);
  EXPECT_EQ(estimator.frame()->origin().lon_deg, kLaunch.lon_deg);
  const Estimate& estimate = estimator.estimate();
  EXPECT_TRUE(estimate.has_position);
  EXPECT_NEAR(estimate.position_local.east_m, 0.0, kEstimateTolerance);
  EXPECT_NEAR(estimate.position_local.north_m, 0.0, kEstimateTolerance);
  EXPECT_NEAR(estimator.position().lat_deg, kLaunch.lat_deg, 1e-9);
  EXPECT_NEAR(estimator.position().lon_deg, kLaunch.lon_deg, 1e-9);

  // A later fix elsewhere does not move the origin.
  const LatLon elsewhere = LocalFrame(kLaunch).ToGeodetic({300.0, -200.0});
  estimator.Update(Nanos{milliseconds{100}}, Fix(elsewhere));
  EXPECT_EQ(estimator.frame()->origin().lat_deg, kLaunch.lat_deg);
  EXPECT_EQ(estimator.frame()->origin().lon_deg, kLaunch.lon_deg);
}

TEST(StateEstimator, DeadReckonsWithTheGpsVelocityBetweenFixes) {
  StateEstimator estimator;
  estimator.Update(Nanos{0}, Fix(kLaunch, 2.0, -1.0));
  estimator.Update(Nanos{milliseconds{500}}, {});
  const Estimate& estimate = estimator.estimate();
  EXPECT_NEAR(estimate.position_local.east_m, 1.0, kEstimateTolerance);
  EXPECT_NEAR(estimate.position_local.north_m, -0.5, kEstimateTolerance);
  EXPECT_NEAR(estimate.velocity_east_mps, 2.0, kEstimateTolerance);
  EXPECT_NEAR(estimate.velocity_north_mps, -1.0, kEstimateTolerance);
  EXPECT_NEAR(estimate.gps_age_s, 0.5, kEstimateTolerance);
  // The geodetic position follows the local one.
  const EastNorth back = estimator.frame()->ToLocal(estimator.position());
  EXPECT_NEAR(back.east_m, 1.0, 1e-3);
  EXPECT_NEAR(back.north_m, -0.5, 1e-3);
  // ... also after the next update (position() is converted on demand and kept
  // only until then).
  estimator.Update(Nanos{milliseconds{1000}}, {});
  const EastNorth later = estimator.frame()->ToLocal(estimator.position());
  EXPECT_NEAR(later.east_m, 2.0, 1e-3);
  EXPECT_NEAR(later.north_m, -1.0, 1e-3);

  // Beyond kMaxDeadReckoningS (1 s) the last fix's velocity is stale: the
  // position is held (a vehicle without GPS levels off and slows down).
  estimator.Update(Nanos{milliseconds{1'500}}, {});
  EXPECT_NEAR(estimator.estimate().position_local.east_m, 2.0, kEstimateTolerance);
  EXPECT_NEAR(estimator.estimate().position_local.north_m, -1.0, kEstimateTolerance);
  EXPECT_NEAR(estimator.estimate().gps_age_s, 1.5, kEstimateTolerance);
}

// The first fix after a GPS loss is taken as it is: the estimate carried on
// without fixes is worth less than the fix (blending would drag the old guess
// along for seconds).
TEST(StateEstimator, TheFirstFixAfterALossIsTakenAsItIs) {
  StateEstimator estimator;
  estimator.Update(Nanos{0}, Fix(kLaunch));
  const LatLon thirty_metres_north = LocalFrame(kLaunch).ToGeodetic({0.0, 30.0});
  estimator.Update(Nanos{milliseconds{5'000}}, Fix(thirty_metres_north));
  EXPECT_NEAR(estimator.estimate().position_local.north_m, 30.0, 1e-6);
  EXPECT_NEAR(estimator.estimate().gps_age_s, 0.0, kEstimateTolerance);
}

TEST(StateEstimator, BlendsPartWayTowardANewFix) {
  StateEstimator estimator;
  estimator.Update(Nanos{0}, Fix(kLaunch));
  const LatLon ten_metres_east = LocalFrame(kLaunch).ToGeodetic({10.0, 0.0});
  estimator.Update(Nanos{milliseconds{100}}, Fix(ten_metres_east));
  const EastNorth position = estimator.estimate().position_local;
  // Moved toward the fix, but not onto it (a complementary filter, not a reset).
  EXPECT_GT(position.east_m, 0.5);
  EXPECT_LT(position.east_m, 9.5);
  EXPECT_NEAR(position.north_m, 0.0, 1e-3);
  EXPECT_NEAR(estimator.estimate().gps_age_s, 0.0, kEstimateTolerance);
  // And converges onto it when the fixes agree.
  for (int step = 2; step < 200; ++step) {
    estimator.Update(Nanos{milliseconds{100 * step}}, Fix(ten_metres_east));
  }
  EXPECT_NEAR(estimator.estimate().position_local.east_m, 10.0, 1e-3);
}

TEST(StateEstimator, ReducesTheWhiteNoiseOfTheFixes) {
  // A vehicle hovering at `truth`; 10 Hz fixes with 2 m of white noise per axis
  // and zero velocity. The estimate must spread well under the fixes.
  constexpr int kFixes = 3'000;
  constexpr int kWarmUp = 100;
  constexpr double kNoiseM = 2.0;
  const LocalFrame truth_frame(kLaunch);
  std::mt19937_64 random(20240611u);
  std::normal_distribution<double> noise(0.0, kNoiseM);

  StateEstimator estimator;
  double fix_sum_squares = 0.0;
  double estimate_sum_squares = 0.0;
  double estimate_sum_east = 0.0;
  double estimate_sum_north = 0.0;
  int samples = 0;
  for (int step = 0; step < kFixes; ++step) {
    const EastNorth fix_local{noise(random), noise(random)};
    estimator.Update(Nanos{milliseconds{100 * step}}, Fix(truth_frame.ToGeodetic(fix_local)));
    if (step < kWarmUp) continue;
    // Errors measured in the estimator's frame (its origin is the first noisy fix).
    const EastNorth truth = estimator.frame()->ToLocal(kLaunch);
    const EastNorth fix = estimator.frame()->ToLocal(truth_frame.ToGeodetic(fix_local));
    const EastNorth estimate = estimator.estimate().position_local;
    const double fix_east = fix.east_m - truth.east_m;
    const double fix_north = fix.north_m - truth.north_m;
    const double estimate_east = estimate.east_m - truth.east_m;
    const double estimate_north = estimate.north_m - truth.north_m;
    fix_sum_squares += fix_east * fix_east + fix_north * fix_north;
    estimate_sum_squares += estimate_east * estimate_east + estimate_north * estimate_north;
    estimate_sum_east += estimate_east;
    estimate_sum_north += estimate_north;
    ++samples;
  }
  const auto n = static_cast<double>(samples);
  const double fix_rms = std::sqrt(fix_sum_squares / n);
  const double estimate_rms = std::sqrt(estimate_sum_squares / n);
  EXPECT_NEAR(fix_rms, kNoiseM * std::sqrt(2.0), 0.1);  // the noise is what we made
  // A first-order blend with gain k passes sqrt(k / (2 - k)) of white noise: 0.23 at
  // k = 0.1. Well under half is what a filter worth its name must do.
  EXPECT_LT(estimate_rms, 0.4 * fix_rms);
  // And it is unbiased: it stays on the point.
  EXPECT_NEAR(estimate_sum_east / n, 0.0, 0.2);
  EXPECT_NEAR(estimate_sum_north / n, 0.0, 0.2);
}

// --- barometer

TEST(StateEstimator, FirstBarometerReadingIsTheGround) {
  StateEstimator estimator;
  EXPECT_FALSE(estimator.estimate().has_altitude);
  estimator.Update(Nanos{0}, Baro(312.0));
  EXPECT_TRUE(estimator.estimate().has_altitude);
  EXPECT_NEAR(estimator.estimate().altitude_m, 0.0, kEstimateTolerance);
  estimator.Update(Nanos{milliseconds{100}}, Baro(315.5));
  EXPECT_NEAR(estimator.estimate().altitude_m, 3.5, kEstimateTolerance);
}

TEST(StateEstimator, ZeroAltitudeTakesTheLatestReading) {
  StateEstimator estimator;
  estimator.Update(Nanos{0}, Baro(312.0));
  estimator.Update(Nanos{milliseconds{100}}, Baro(309.0));  // pressure drifted
  EXPECT_NEAR(estimator.estimate().altitude_m, -3.0, kEstimateTolerance);
  estimator.ZeroAltitude();
  EXPECT_NEAR(estimator.estimate().altitude_m, 0.0, kEstimateTolerance);
  estimator.Update(Nanos{milliseconds{200}}, Baro(319.0));
  EXPECT_NEAR(estimator.estimate().altitude_m, 10.0, kEstimateTolerance);
}

TEST(StateEstimator, ZeroAltitudeBeforeAnyReadingLeavesTheFirstAsTheGround) {
  StateEstimator estimator;
  estimator.ZeroAltitude();
  EXPECT_FALSE(estimator.estimate().has_altitude);
  estimator.Update(Nanos{0}, Baro(250.0));
  EXPECT_NEAR(estimator.estimate().altitude_m, 0.0, kEstimateTolerance);
}

TEST(StateEstimator, ClimbRateSign) {
  StateEstimator climbing;
  StateEstimator descending;
  for (int step = 0; step <= 50; ++step) {
    const Nanos now{milliseconds{100 * step}};
    climbing.Update(now, Baro(100.0 + 0.1 * step));    // +1 m/s
    descending.Update(now, Baro(100.0 - 0.2 * step));  // -2 m/s
  }
  // Smoothed over about a second; after five it is nearly there.
  EXPECT_GT(climbing.estimate().climb_rate_mps, 0.9);
  EXPECT_LT(climbing.estimate().climb_rate_mps, 1.0 + kEstimateTolerance);
  EXPECT_LT(descending.estimate().climb_rate_mps, -1.8);
  EXPECT_GT(descending.estimate().climb_rate_mps, -2.0 - kEstimateTolerance);
}

TEST(StateEstimator, ClimbRateIsZeroWhenLevel) {
  StateEstimator estimator;
  for (int step = 0; step <= 20; ++step) {
    estimator.Update(Nanos{milliseconds{100 * step}}, Baro(321.0));
  }
  EXPECT_NEAR(estimator.estimate().climb_rate_mps, 0.0, kEstimateTolerance);
}

// --- passthrough

TEST(StateEstimator, BatteryIsPassedThrough) {
  StateEstimator estimator;
  EXPECT_EQ(estimator.estimate().battery_fraction, 1.0);  // full until told
  SensorInputs inputs;
  inputs.battery = BatteryInput{15.2, 0.63};
  estimator.Update(Nanos{0}, inputs);
  EXPECT_EQ(estimator.estimate().battery_v, 15.2);
  EXPECT_EQ(estimator.estimate().battery_fraction, 0.63);
  // A step without a battery sample keeps the last one.
  estimator.Update(Nanos{milliseconds{100}}, {});
  EXPECT_EQ(estimator.estimate().battery_v, 15.2);
}

TEST(StateEstimator, AttitudeIsPassedThrough) {
  StateEstimator estimator;
  EXPECT_FALSE(estimator.estimate().has_attitude);
  SensorInputs inputs;
  AttitudeInput attitude;
  attitude.roll_rad = 0.1;
  attitude.pitch_rad = -0.2;
  attitude.heading_rad = 3.0;
  inputs.attitude = attitude;
  estimator.Update(Nanos{0}, inputs);
  EXPECT_TRUE(estimator.estimate().has_attitude);
  EXPECT_EQ(estimator.estimate().attitude.roll_rad, 0.1);
  EXPECT_EQ(estimator.estimate().attitude.pitch_rad, -0.2);
  EXPECT_EQ(estimator.estimate().attitude.heading_rad, 3.0);
}

}  // namespace
}  // namespace fireswarm::agents
