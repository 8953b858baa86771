#include <algorithm>
#include <cmath>
#include <numbers>

#include "multirotor_dynamics.hpp"

namespace fireswarm::sim2d {
namespace {

// One lag step toward `target` with the change limited to max_rate * dt; returns
// the new value and writes the rate actually achieved.
double LagToward(double value, double target, double blend, double max_rate, double dt_s,
                 double& rate_out) {
  const double max_change = max_rate * dt_s;
  const double change = std::clamp((target - value) * blend, -max_change, max_change);
  rate_out = change / dt_s;
  return value + change;
}

// Linear plus quadratic drag on one velocity (m/s): returns the force factor
// such that force = -factor * velocity.
double DragFactor(const MultirotorParams& params, double speed_mps) {
  return params.linear_drag_n_per_mps + params.quadratic_drag_n_per_mps2 * speed_mps;
}

}  // namespace

double WrapTwoPi(double angle_rad) {
  constexpr double kTwoPi = 2.0 * std::numbers::pi;
  double wrapped = std::fmod(angle_rad, kTwoPi);
  if (wrapped < 0.0) wrapped += kTwoPi;
  return wrapped >= kTwoPi ? 0.0 : wrapped;
}

AttitudeTrig AttitudeTrig::Of(const VehicleTruth& truth) {
  AttitudeTrig trig;
  trig.sin_roll = std::sin(truth.roll_rad);
  trig.cos_roll = std::cos(truth.roll_rad);
  trig.sin_pitch = std::sin(truth.pitch_rad);
  trig.cos_pitch = std::cos(truth.pitch_rad);
  trig.sin_heading = std::sin(truth.heading_rad);
  trig.cos_heading = std::cos(truth.heading_rad);
  return trig;
}

MultirotorCoefficients MakeCoefficients(const MultirotorParams& params, double dt_s) {
  MultirotorCoefficients c;
  c.dt_s = dt_s;
  c.attitude_blend = 1.0 - std::exp(-dt_s / params.attitude_time_constant_s);
  c.yaw_blend = 1.0 - std::exp(-dt_s / params.yaw_time_constant_s);
  c.thrust_blend = 1.0 - std::exp(-dt_s / params.thrust_time_constant_s);
  c.hover_thrust_n = params.mass_kg * kGravityMps2;
  const double tau = params.attitude_time_constant_s;
  const double stiffness_nm_per_rad = params.roll_pitch_inertia_kgm2 / (tau * tau);
  c.ballast_rad_per_m = c.hover_thrust_n / stiffness_nm_per_rad;
  return c;
}

void StepAttitude(const MultirotorParams& params, const MultirotorCoefficients& coefficients,
                  const ActuatorCommand& command, const Vec2& ballast_offset_m,
                  VehicleTruth& truth) {
  const double tilt = params.max_tilt_rad;
  // The ballast's torque shifts the attitude the inner loop settles at: a
  // forward centre of mass drops the nose, a right one drops the right wing.
  const double roll_target = std::clamp(command.roll_rad, -tilt, tilt) +
                             coefficients.ballast_rad_per_m * ballast_offset_m.y();
  const double pitch_target = std::clamp(command.pitch_rad, -tilt, tilt) -
                              coefficients.ballast_rad_per_m * ballast_offset_m.x();
  const double dt = coefficients.dt_s;
  truth.roll_rad = LagToward(truth.roll_rad, roll_target, coefficients.attitude_blend,
                             params.max_attitude_rate_radps, dt, truth.roll_rate_radps);
  truth.pitch_rad = LagToward(truth.pitch_rad, pitch_target, coefficients.attitude_blend,
                              params.max_attitude_rate_radps, dt, truth.pitch_rate_radps);
  const double yaw_target =
      std::clamp(command.yaw_rate_radps, -params.max_yaw_rate_radps, params.max_yaw_rate_radps);
  truth.yaw_rate_radps += (yaw_target - truth.yaw_rate_radps) * coefficients.yaw_blend;
  truth.heading_rad = WrapTwoPi(truth.heading_rad + truth.yaw_rate_radps * dt);
}

double CommandedThrust(const MultirotorParams& params, const MultirotorCoefficients& coefficients,
                       const ActuatorCommand& command, const VehicleTruth& truth,
                       const AttitudeTrig& trig) {
  if (!command.armed) return 0.0;
  const double climb_cmd =
      std::clamp(command.climb_rate_mps, -params.max_descent_rate_mps, params.max_climb_rate_mps);
  const double climb = truth.climb_rate_mps;
  const double accel_cmd = params.climb_gain_per_s * (climb_cmd - climb);
  // The loop feeds the vertical drag forward, so a steady climb matches its command.
  const double drag_n = DragFactor(params, std::abs(climb)) * climb;
  const double tilt_cos = trig.tilt_cos();
  // Never divide by a vanishing cosine: beyond ~84 deg the loop gives up on height.
  constexpr double kMinTiltCos = 0.1;
  const double thrust = (coefficients.hover_thrust_n * (1.0 + accel_cmd / kGravityMps2) + drag_n) /
                        std::max(tilt_cos, kMinTiltCos);
  return std::clamp(thrust, 0.0, params.max_thrust_n);
}

double StepThrust(const MultirotorCoefficients& coefficients, double thrust_n, double target_n) {
  return thrust_n + (target_n - thrust_n) * coefficients.thrust_blend;
}

Vec2 HorizontalForce(const MultirotorParams& params, const VehicleTruth& truth,
                     const AttitudeTrig& trig, double thrust_n, const Vec2& wind_mps) {
  // Thrust along body -z, rotated by R = Rz(heading) Ry(pitch) Rx(roll) into NED.
  const double sr = trig.sin_roll;
  const double cr = trig.cos_roll;
  const double sp = trig.sin_pitch;
  const double sh = trig.sin_heading;
  const double ch = trig.cos_heading;
  const double north = -ch * sp * cr - sh * sr;
  const double east = -sh * sp * cr + ch * sr;
  const Vec2 air_velocity_mps = truth.velocity_mps - wind_mps;
  const double drag_factor = DragFactor(params, air_velocity_mps.norm());
  return thrust_n * Vec2(east, north) - drag_factor * air_velocity_mps;
}

double VerticalAcceleration(const MultirotorParams& params, const VehicleTruth& truth,
                            const AttitudeTrig& trig, double thrust_n) {
  const double lift_n = thrust_n * trig.tilt_cos();
  const double climb = truth.climb_rate_mps;
  const double drag_n = DragFactor(params, std::abs(climb)) * climb;
  return (lift_n - drag_n) / params.mass_kg - kGravityMps2;
}

Touchdown StepVertical(const MultirotorParams& params, const MultirotorCoefficients& coefficients,
                       const AttitudeTrig& trig, double thrust_n, VehicleTruth& truth,
                       double& impact_speed_mps) {
  const double dt = coefficients.dt_s;
  truth.climb_rate_mps += VerticalAcceleration(params, truth, trig, thrust_n) * dt;
  truth.altitude_m += truth.climb_rate_mps * dt;
  if (truth.altitude_m > 0.0) return Touchdown::kNone;
  const double sink_mps = std::max(0.0, -truth.climb_rate_mps);
  const double horizontal_mps = truth.velocity_mps.norm();
  impact_speed_mps = std::hypot(sink_mps, horizontal_mps);
  truth.altitude_m = 0.0;
  truth.climb_rate_mps = 0.0;
  const bool too_fast = sink_mps > params.crash_vertical_speed_mps ||
                        horizontal_mps > params.crash_horizontal_speed_mps;
  return too_fast ? Touchdown::kCrashed : Touchdown::kLanded;
}

}  // namespace fireswarm::sim2d
