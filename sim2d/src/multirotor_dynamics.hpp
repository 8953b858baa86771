// The multirotor plant beside Box2D: attitude lag, thrust from the inner climb
// loop, the horizontal force handed to Box2D, and the vertical axis with ground
// contact. Pure functions over VehicleTruth; the world owns the Box2D body.
#pragma once

#include "fireswarm/common/units.hpp"
#include "fireswarm/sim2d/multirotor.hpp"
#include "fireswarm/sim2d/vehicle_state.hpp"

namespace fireswarm::sim2d {

using common::kGravityMps2;

/// Step-size dependent constants, computed once per vehicle (no exp() per step).
struct MultirotorCoefficients {
  double dt_s = 0.0;
  double attitude_blend = 0.0;  ///< 1 - exp(-dt / attitude_time_constant_s)
  double yaw_blend = 0.0;       ///< 1 - exp(-dt / yaw_time_constant_s)
  double thrust_blend = 0.0;    ///< 1 - exp(-dt / thrust_time_constant_s)
  double hover_thrust_n = 0.0;  ///< m g
  /// Steady attitude error per metre of centre-of-mass offset: the disturbing
  /// torque m g d over the attitude loop's stiffness I / tau^2.
  double ballast_rad_per_m = 0.0;
};

MultirotorCoefficients MakeCoefficients(const MultirotorParams& params, double dt_s);

/// Sines and cosines of the attitude, computed once per sub-step and shared by
/// the thrust, force and vertical computations.
struct AttitudeTrig {
  double sin_roll = 0.0;
  double cos_roll = 1.0;
  double sin_pitch = 0.0;
  double cos_pitch = 1.0;
  double sin_heading = 0.0;
  double cos_heading = 1.0;

  static AttitudeTrig Of(const VehicleTruth& truth);
  double tilt_cos() const { return cos_roll * cos_pitch; }
};

/// Roll and pitch follow the (clamped) command plus the ballast's offset through
/// a first-order lag with a rate limit; the yaw rate follows its command likewise
/// and the heading integrates it. Sets the angles and the three rates.
/// `ballast_offset_m` is (forward_m, right_m) in the body frame.
void StepAttitude(const MultirotorParams& params, const MultirotorCoefficients& coefficients,
                  const ActuatorCommand& command, const Vec2& ballast_offset_m,
                  VehicleTruth& truth);

/// The thrust (N) the inner climb-rate loop asks for: m (g + k (climb_cmd - climb))
/// over the tilt's cosine, within [0, max_thrust_n]. Not armed -> 0.
double CommandedThrust(const MultirotorParams& params, const MultirotorCoefficients& coefficients,
                       const ActuatorCommand& command, const VehicleTruth& truth,
                       const AttitudeTrig& trig);

/// The motor lag: thrust moves toward `target_n`.
double StepThrust(const MultirotorCoefficients& coefficients, double thrust_n, double target_n);

/// The horizontal force (N, local ENU) of the tilted thrust vector plus linear and
/// quadratic drag on the air-relative velocity. `wind_mps` is where the air moves to.
Vec2 HorizontalForce(const MultirotorParams& params, const VehicleTruth& truth,
                     const AttitudeTrig& trig, double thrust_n, const Vec2& wind_mps);

/// The vertical acceleration (m/s^2, up) from thrust, gravity and vertical drag.
double VerticalAcceleration(const MultirotorParams& params, const VehicleTruth& truth,
                            const AttitudeTrig& trig, double thrust_n);

enum class Touchdown { kNone, kLanded, kCrashed };

/// Integrates climb rate and altitude over dt for an airborne vehicle. When the
/// ground is reached, altitude and climb rate become 0 and the outcome says
/// whether the touch-down was soft (both speeds within the crash limits).
/// `impact_speed_mps` receives the 3D speed at touch-down.
Touchdown StepVertical(const MultirotorParams& params, const MultirotorCoefficients& coefficients,
                       const AttitudeTrig& trig, double thrust_n, VehicleTruth& truth,
                       double& impact_speed_mps);

/// Wraps an angle into [0, 2 pi).
double WrapTwoPi(double angle_rad);

}  // namespace fireswarm::sim2d
