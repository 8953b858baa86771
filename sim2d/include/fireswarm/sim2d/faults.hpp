// Faults injected into one simulated vehicle (seed 4.3.2): sensor stream cuts,
// frozen values, added bias, extra noise, a ballast that unbalances the vehicle,
// and total loss. Each is scheduled for a window of simulated time.
#pragma once

#include <Eigen/Core>
#include <limits>

#include "fireswarm/sim2d/vehicle_state.hpp"

namespace fireswarm::sim2d {

enum class SensorKind { kGps, kBaro, kAttitude, kBattery };

enum class FaultKind {
  kStreamCut,   ///< the sensor delivers nothing during the window
  kFrozen,      ///< the sensor keeps delivering, at its rate, the last value before the window
  kBias,        ///< `bias` is added to the sensor's values
  kExtraNoise,  ///< the sensor's white-noise std is multiplied by `noise_factor`
  kBallast,     ///< the centre of mass moves by `ballast_offset_m`; attitude drifts
  kTotalLoss,   ///< the vehicle is gone for good at `start_s`: kLost, no sensors, no collisions
};

/// One scheduled fault, active for start_s <= t < end_s of simulated time.
struct FaultSpec {
  FaultKind kind = FaultKind::kStreamCut;
  SensorKind sensor = SensorKind::kGps;  ///< for the sensor faults only
  double start_s = 0.0;
  double end_s = std::numeric_limits<double>::infinity();  ///< ignored for kTotalLoss
  /// kBias, per sensor: GPS (east_m, north_m, up_m); baro (altitude_m, -, -);
  /// attitude (roll_rad, pitch_rad, heading_rad); battery (voltage_v, -, -).
  Eigen::Vector3d bias = Eigen::Vector3d::Zero();
  double noise_factor = 1.0;  ///< kExtraNoise: >= 1
  /// kBallast: centre-of-mass offset in the body frame, (forward_m, right_m).
  /// Forward makes the nose drop (negative pitch), right makes the right wing drop.
  Vec2 ballast_offset_m = Vec2::Zero();
};

}  // namespace fireswarm::sim2d
