// What a simulated vehicle's sensors report (seed 4.3, 4.3.2): each sensor has
// its own rate (a refresh-rate adapter drops the samples between its slots),
// Gaussian noise, and for GPS and baro a slowly wandering Gauss-Markov bias.
#pragma once

#include <optional>

#include "fireswarm/common/local_frame.hpp"
#include "fireswarm/sim2d/vehicle_state.hpp"

namespace fireswarm::sim2d {

/// A u-blox SAM-M8Q-like receiver (seed 2.9: 2.5 m CEP, up to 18 Hz).
/// The horizontal error per axis has standard deviation sigma = CEP / 1.1774; a
/// share `bias_variance_fraction` of its variance is a first-order Gauss-Markov
/// bias (correlated over `bias_time_constant_s`), the rest white noise.
struct GpsParams {
  double rate_hz = 10.0;
  double horizontal_cep_m = 2.5;
  double vertical_std_m = 4.0;          ///< altitude error, split like the horizontal
  double bias_variance_fraction = 0.7;  ///< in [0, 1]
  double bias_time_constant_s = 60.0;
  double velocity_std_mps = 0.05;  ///< per axis, white
};

/// A BMP280-like barometric altimeter (seed 2.8: +-1 m relative accuracy).
struct BaroParams {
  double rate_hz = 25.0;
  double noise_std_m = 0.2;
  double bias_std_m = 1.0;  ///< stationary std of the Gauss-Markov bias
  double bias_time_constant_s = 300.0;
};

/// Attitude and body rates from the autopilot's IMU. A rate above 1 / step_s is
/// rejected: the world delivers at most one sample per step.
struct AttitudeSensorParams {
  double rate_hz = 100.0;
  double angle_noise_std_rad = 0.0087;   ///< roll and pitch, 0.5 deg
  double heading_noise_std_rad = 0.017;  ///< 1 deg
  double rate_noise_std_radps = 0.01;
};

/// The battery monitor (voltage and current sense).
struct BatterySensorParams {
  double rate_hz = 5.0;
  double voltage_noise_std_v = 0.02;
  double current_noise_std_a = 0.1;
};

struct SensorParams {
  GpsParams gps;
  BaroParams baro;
  AttitudeSensorParams attitude;
  BatterySensorParams battery;
};

/// Every reading carries the simulated time (s) at which it was sampled.
struct GpsReading {
  double time_s = 0.0;
  common::LatLon position;           ///< WGS84, through the world's LocalFrame
  double altitude_m = 0.0;           ///< above the (flat) ground
  Vec2 velocity_mps = Vec2::Zero();  ///< ground velocity, local ENU
};

struct BaroReading {
  double time_s = 0.0;
  double altitude_m = 0.0;  ///< above the ground
};

struct AttitudeReading {
  double time_s = 0.0;
  double roll_rad = 0.0;
  double pitch_rad = 0.0;
  double heading_rad = 0.0;  ///< clockwise from north, [0, 2 pi)
  double roll_rate_radps = 0.0;
  double pitch_rate_radps = 0.0;
  double yaw_rate_radps = 0.0;
};

struct BatteryReading {
  double time_s = 0.0;
  double voltage_v = 0.0;
  double current_a = 0.0;
  double fraction = 0.0;  ///< the fuel gauge's charge estimate, 0..1
};

/// One vehicle's sensor output of one world step: a field is set only when that
/// sensor produced a sample in this step (its rate slot came up, it is not cut,
/// and the vehicle is not lost).
struct SensorSample {
  std::optional<GpsReading> gps;
  std::optional<BaroReading> baro;
  std::optional<AttitudeReading> attitude;
  std::optional<BatteryReading> battery;
};

}  // namespace fireswarm::sim2d
