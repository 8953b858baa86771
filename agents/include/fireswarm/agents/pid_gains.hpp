// One PID's tuning, as the parameters store it: gains and symmetric clamps.
#pragma once

#include "fireswarm/agents/pid.hpp"

namespace fireswarm::agents {

struct PidGains {
  double kp = 0.0;
  double ki = 0.0;
  double kd = 0.0;
  // Each clamp is symmetric; 0 means none (the seed's PID has no limits until set).
  double i_limit = 0.0;    ///< I term clamped to [-i_limit, i_limit]
  double d_limit = 0.0;    ///< D term clamped to [-d_limit, d_limit]
  double out_limit = 0.0;  ///< output clamped to [-out_limit, out_limit]
};

/// Sets `pid`'s gains and its three symmetric clamps (a 0 limit: no clamp), with
/// state anti-wind-up.
/// Keeps the integrator: a gain change in flight must not jolt the vehicle.
inline void ApplyGains(const PidGains& gains, Pid& pid) {
  pid.SetGains(gains.kp, gains.ki, gains.kd);
  pid.ClearLimits();
  if (gains.i_limit > 0.0) pid.SetITermLimits(-gains.i_limit, gains.i_limit);
  if (gains.d_limit > 0.0) pid.SetDTermLimits(-gains.d_limit, gains.d_limit);
  if (gains.out_limit > 0.0) pid.SetOutputLimits(-gains.out_limit, gains.out_limit);
  pid.SetAntiWindup(AntiWindup::kClampState);
}

}  // namespace fireswarm::agents
