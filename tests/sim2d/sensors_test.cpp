// Sensor rates (refresh-rate adapters), timestamps and noise statistics.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "fireswarm/sim2d/world.hpp"
#include "sensor_suite.hpp"
#include "world_test_helpers.hpp"

namespace fireswarm::sim2d {
namespace {

// The horizontal GPS error (m, local ENU) of a reading against the truth.
Vec2 GpsError(const World& world, const GpsReading& reading, const VehicleTruth& truth) {
  const common::EastNorth local = world.frame().ToLocal(reading.position);
  return Vec2(local.east_m, local.north_m) - truth.position_m;
}

TEST(RateAdapter, LetsOneSampleThroughPerPeriod) {
  RateAdapter adapter(10.0, 0.0);
  int delivered = 0;
  for (int step = 1; step < 1000; ++step) delivered += adapter.Due(step * 0.01) ? 1 : 0;
  EXPECT_EQ(delivered, 100);     // steps 0.01 .. 9.99 s see slots 0.0 .. 9.9 s, each once
  RateAdapter fast(500.0, 0.0);  // faster than the steps: one per step, never two
  int fast_delivered = 0;
  for (int step = 1; step <= 100; ++step) fast_delivered += fast.Due(step * 0.01) ? 1 : 0;
  EXPECT_EQ(fast_delivered, 100);
}

TEST(Sensors, EachSensorDeliversExactlyAtItsOwnRate) {
  WorldConfig config;
  VehicleConfig vehicle;
  vehicle.sensors.attitude.rate_hz = 50.0;
  config.vehicles.push_back(vehicle);
  World world(config);
  // Per whole simulated second [k, k + 1): samples of each sensor.
  std::vector<int> gps(10), baro(10), attitude(10), battery(10);
  for (int step = 0; step < 1000; ++step) {
    world.Step();
    const SensorSample& s = world.Sensors(1);
    const auto second = [](double t) { return static_cast<std::size_t>(std::floor(t + 1e-9)); };
    if (s.gps) {
      EXPECT_EQ(s.gps->time_s, world.time_s());
      if (second(s.gps->time_s) < 10) ++gps[second(s.gps->time_s)];
    }
    if (s.baro && second(s.baro->time_s) < 10) ++baro[second(s.baro->time_s)];
    if (s.attitude && second(s.attitude->time_s) < 10) ++attitude[second(s.attitude->time_s)];
    if (s.battery && second(s.battery->time_s) < 10) ++battery[second(s.battery->time_s)];
  }
  for (std::size_t k = 1; k < 10; ++k) {  // second 0 lacks t = 0 (no step ends there)
    EXPECT_EQ(gps[k], 10) << "second " << k;
    EXPECT_EQ(baro[k], 25) << "second " << k;
    EXPECT_EQ(attitude[k], 50) << "second " << k;
    EXPECT_EQ(battery[k], 5) << "second " << k;
  }
}

TEST(Sensors, AttitudeAtTheStepRateArrivesEveryStep) {
  WorldConfig config;
  config.step_s = 0.002;  // 500 Hz, the seed's HIL frame rate
  VehicleConfig vehicle;
  vehicle.sensors.attitude.rate_hz = 500.0;
  config.vehicles.push_back(vehicle);
  World world(config);
  for (int step = 0; step < 500; ++step) {
    world.Step();
    ASSERT_TRUE(world.Sensors(1).attitude.has_value()) << "step " << step;
  }
}

TEST(Sensors, GpsHorizontalErrorHasTheConfiguredCep) {
  WorldConfig config;
  constexpr int kSide = 20;  // 400 receivers, each with its own bias
  for (int i = 0; i < kSide * kSide; ++i) {
    VehicleConfig vehicle;
    vehicle.id = i + 1;
    vehicle.launch_position_m = Vec2(5.0 * (i % kSide), 5.0 * (i / kSide));
    config.vehicles.push_back(vehicle);
  }
  World world(config);
  std::vector<double> radial_m;
  for (int step = 0; step < 500; ++step) {
    world.Step();
    for (const VehicleTruth& truth : world.Truths()) {
      const SensorSample& s = world.Sensors(truth.id);
      if (s.gps) radial_m.push_back(GpsError(world, *s.gps, truth).norm());
    }
  }
  ASSERT_EQ(radial_m.size(), 400U * 50U);
  const auto middle = radial_m.begin() + static_cast<std::ptrdiff_t>(radial_m.size() / 2);
  std::nth_element(radial_m.begin(), middle, radial_m.end());
  const double cep_m = *middle;
  EXPECT_NEAR(cep_m, 2.5, 0.2);
}

TEST(Sensors, GpsBiasIsCorrelatedOverTimeAndWhiteNoiseIsNot) {
  for (const double bias_fraction : {0.7, 0.0}) {
    WorldConfig config;
    constexpr int kVehicles = 50;
    for (int i = 0; i < kVehicles; ++i) {
      VehicleConfig vehicle;
      vehicle.id = i + 1;
      vehicle.launch_position_m = Vec2(5.0 * i, 0.0);
      vehicle.sensors.gps.bias_variance_fraction = bias_fraction;
      config.vehicles.push_back(vehicle);
    }
    World world(config);
    // Fix-to-fix correlation of the east error, pooled, about the true mean 0:
    // the bias share times e^(-0.1 s / 60 s) = 0.699 with the bias, 0 without.
    std::vector<double> previous(kVehicles, std::nan(""));
    double products = 0.0;
    double squares = 0.0;
    for (int step = 0; step < 6000; ++step) {
      world.Step();
      for (std::size_t i = 0; i < kVehicles; ++i) {
        const auto& gps = world.AllSensors()[i].gps;
        if (!gps) continue;
        const double east_m = GpsError(world, *gps, world.Truths()[i]).x();
        if (!std::isnan(previous[i])) {
          products += east_m * previous[i];
          squares += east_m * east_m;
        }
        previous[i] = east_m;
      }
    }
    const double lag1 = products / squares;
    if (bias_fraction > 0.0) {
      EXPECT_NEAR(lag1, 0.7, 0.1) << "fix-to-fix correlation with a Gauss-Markov bias";
    } else {
      EXPECT_NEAR(lag1, 0.0, 0.05) << "white noise only";
    }
  }
}

TEST(Sensors, BaroNoiseAndBiasHaveTheirConfiguredSizes) {
  WorldConfig config;
  for (int i = 0; i < 200; ++i) {
    VehicleConfig vehicle;
    vehicle.id = i + 1;
    vehicle.launch_position_m = Vec2(5.0 * i, 0.0);
    config.vehicles.push_back(vehicle);
  }
  World world(config);
  // Per vehicle over 4 s: the mean is the bias (its 300 s time constant barely
  // moves it), the spread the white noise.
  std::vector<std::vector<double>> readings(200);
  for (int step = 0; step < 400; ++step) {
    world.Step();
    for (std::size_t i = 0; i < 200; ++i) {
      if (world.AllSensors()[i].baro) readings[i].push_back(world.AllSensors()[i].baro->altitude_m);
    }
  }
  double bias_sq = 0.0;
  double noise_sq = 0.0;
  double noise_n = 0.0;
  for (const auto& series : readings) {
    const double mean =
        std::accumulate(series.begin(), series.end(), 0.0) / static_cast<double>(series.size());
    bias_sq += mean * mean;
    for (const double r : series) noise_sq += (r - mean) * (r - mean);
    noise_n += static_cast<double>(series.size() - 1);
  }
  EXPECT_NEAR(std::sqrt(bias_sq / 200.0), 1.0, 0.15);
  EXPECT_NEAR(std::sqrt(noise_sq / noise_n), 0.2, 0.02);
}

TEST(Sensors, AttitudeAndBatteryReadingsTrackTruth) {
  WorldConfig config;
  config.vehicles.push_back(VehicleConfig{});
  World world(config);
  testing::TakeOffTo(world, 1, 10.0);
  ActuatorCommand command = testing::Hover();
  command.roll_rad = 0.2;
  world.SetCommand(1, command);
  world.RunFor(1.0);
  const SensorSample& s = world.Sensors(1);
  ASSERT_TRUE(s.attitude);
  EXPECT_NEAR(s.attitude->roll_rad, 0.2, 0.05);
  std::optional<BatteryReading> battery;
  for (int step = 0; step < 20 && !battery; ++step) {  // the monitor runs at 5 Hz
    world.Step();
    battery = world.Sensors(1).battery;
  }
  ASSERT_TRUE(battery);
  const double fraction = world.Truth(1).battery_fraction;
  EXPECT_EQ(battery->fraction, fraction);
  EXPECT_NEAR(battery->voltage_v, 13.2 + 3.6 * fraction, 0.1);
  // Hovering: 160 W of motors (a little more for the tilt) and 4 W of avionics.
  EXPECT_NEAR(battery->current_a * battery->voltage_v, 170.0, 15.0);
}

}  // namespace
}  // namespace fireswarm::sim2d
