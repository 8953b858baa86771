#include "fireswarm/agents/loiter.hpp"

#include <algorithm>
#include <cmath>

#include "fireswarm/common/units.hpp"

namespace fireswarm::agents {

namespace {
// Closer than this to the centre the bearing to it is noise: keep the heading.
constexpr double kMinRangeM = 1.0;
// The radius integrator runs only this close to the circle.
constexpr double kIntegrateWithinM = 5.0;
}  // namespace

Loiter::Loiter(const LoiterConfig& config) {
  Configure(config);
}

void Loiter::Configure(const LoiterConfig& config) {
  config_ = config;
  PidGains radial = config_.radial;
  radial.kd = 0.0;  // damped with the GPS velocity instead (DampingTilt)
  ApplyGains(radial, radial_pid_);
  ApplyGains(config_.speed, speed_pid_);
}

void Loiter::Start(common::EastNorth center, double radius_m, double altitude_m) {
  center_ = center;
  radius_m_ = radius_m;
  altitude_m_ = altitude_m;
  radial_pid_.Reset();
  speed_pid_.Reset();
}

NavigationSetpoint Loiter::Step(const NavigationInput& input, common::Micros dt) {
  const double to_center_east = center_.east_m - input.position_local.east_m;
  const double to_center_north = center_.north_m - input.position_local.north_m;
  const double range = std::hypot(to_center_east, to_center_north);
  NavigationSetpoint setpoint;
  setpoint.altitude_m = altitude_m_;
  if (range < kMinRangeM) {
    setpoint.heading_rad = input.heading_rad;
    radius_error_m_ = -radius_m_;
    return setpoint;
  }
  // seed 7.4: the heading set-point is the direction of the target.
  const double inward_east = to_center_east / range;
  const double inward_north = to_center_north / range;
  setpoint.heading_rad = std::atan2(inward_east, inward_north);
  radius_error_m_ = range - radius_m_;
  // Tangent: the inward direction turned 90 deg clockwise (the vehicle's right).
  const double tangent_east = inward_north;
  const double tangent_north = -inward_east;
  const double tangential_speed =
      input.velocity_east_mps * tangent_east + input.velocity_north_mps * tangent_north;
  // Too far out (range > radius) -> tilt inward. The centripetal acceleration
  // v^2 / r is fed forward so the PID only trims.
  const double centripetal_tilt = config_.speed_mps * config_.speed_mps /
                                  std::max(radius_m_, kMinRangeM) / common::kGravityMps2;
  // Far from the circle the integrator would only wind up on the approach.
  if (std::abs(radius_error_m_) > kIntegrateWithinM) radial_pid_.Reset();
  const double range_rate =
      -(input.velocity_east_mps * inward_east + input.velocity_north_mps * inward_north);
  const double tilt_inward = centripetal_tilt - radial_pid_.Update(range, radius_m_, dt) +
                             DampingTilt(config_.radial, range_rate);
  const double tilt_along = speed_pid_.Update(tangential_speed, config_.speed_mps, dt);
  const BodyTilt body = TiltToBody(tilt_inward * inward_east + tilt_along * tangent_east,
                                   tilt_inward * inward_north + tilt_along * tangent_north,
                                   input.heading_rad, config_.max_tilt_rad);
  setpoint.roll_rad = body.roll_rad;
  setpoint.pitch_rad = body.pitch_rad;
  return setpoint;
}

}  // namespace fireswarm::agents
