#include "fireswarm/sim2d/lane_pilot.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "fireswarm/common/angles.hpp"
#include "fireswarm/common/units.hpp"

namespace fireswarm::sim2d {
namespace {

constexpr double kMaxClimbCommandMps = 3.0;
constexpr double kLandingDescentMps = 1.0;
// Below this altitude the pilot only climbs (no tilt near the ground).
constexpr double kTakeOffClearanceM = 3.0;

}  // namespace

LanePilot::LanePilot(std::vector<Vec2> waypoints_m, LanePilotParams params)
    : waypoints_(std::move(waypoints_m)), params_(params) {
  const std::pair<const char*, double> positive[] = {
      {"altitude_m", params.altitude_m},
      {"speed_mps", params.speed_mps},
      {"acceptance_radius_m", params.acceptance_radius_m},
      {"velocity_gain_per_s", params.velocity_gain_per_s},
      {"altitude_gain_per_s", params.altitude_gain_per_s},
      {"max_tilt_rad", params.max_tilt_rad},
      {"heading_gain_per_s", params.heading_gain_per_s}};
  for (const auto& [name, value] : positive) {
    if (!(value > 0.0)) {
      throw std::invalid_argument(std::string("lane pilot: ") + name + " must be > 0, got " +
                                  std::to_string(value));
    }
  }
}

ActuatorCommand LanePilot::Command(const VehicleTruth& truth) {
  ActuatorCommand command;
  command.armed = true;
  while (!finished() &&
         (waypoints_[next_] - truth.position_m).norm() < params_.acceptance_radius_m) {
    ++next_;
  }
  if (finished()) {
    // Land, holding position over the last waypoint.
    command.armed = truth.phase != FlightPhase::kOnGround;
    command.climb_rate_mps = -kLandingDescentMps;
  } else {
    command.climb_rate_mps =
        std::clamp(params_.altitude_gain_per_s * (params_.altitude_m - truth.altitude_m),
                   -kMaxClimbCommandMps, kMaxClimbCommandMps);
    if (truth.altitude_m < kTakeOffClearanceM) return command;
  }
  if (waypoints_.empty() || truth.phase == FlightPhase::kOnGround) return command;
  const Vec2 target = finished() ? waypoints_.back() : waypoints_[next_];
  SteerToward(target, truth, command);
  return command;
}

void LanePilot::SteerToward(const Vec2& target_m, const VehicleTruth& truth,
                            ActuatorCommand& command) const {
  // Velocity toward the target, slowing down inside the last few metres.
  const Vec2 to_target = target_m - truth.position_m;
  const double distance_m = to_target.norm();
  const double speed_mps = std::min(params_.speed_mps, params_.velocity_gain_per_s * distance_m);
  const Vec2 desired_velocity =
      distance_m > 0.0 ? Vec2(to_target / distance_m * speed_mps) : Vec2::Zero();
  const Vec2 accel = params_.velocity_gain_per_s * (desired_velocity - truth.velocity_mps);

  // Body axes from the heading (clockwise from north): forward and right in ENU.
  const double heading = truth.heading_rad;
  const Vec2 forward(std::sin(heading), std::cos(heading));
  const Vec2 right(std::cos(heading), -std::sin(heading));
  // Nose down (negative pitch) accelerates forward; right wing down accelerates right.
  command.pitch_rad = std::clamp(-std::atan(accel.dot(forward) / common::kGravityMps2),
                                 -params_.max_tilt_rad, params_.max_tilt_rad);
  command.roll_rad = std::clamp(std::atan(accel.dot(right) / common::kGravityMps2),
                                -params_.max_tilt_rad, params_.max_tilt_rad);
  if (distance_m > params_.acceptance_radius_m) {
    const double desired_heading = std::atan2(to_target.x(), to_target.y());
    command.yaw_rate_radps = params_.heading_gain_per_s * common::WrapPi(desired_heading - heading);
  }
}

std::vector<Vec2> LawnmowerLanes(const Vec2& min_m, const Vec2& max_m, double spacing_m) {
  if (!(spacing_m > 0.0)) {
    throw std::invalid_argument("lawnmower lanes: spacing_m must be > 0, got " +
                                std::to_string(spacing_m));
  }
  std::vector<Vec2> waypoints;
  bool north = true;
  for (double x = min_m.x() + spacing_m / 2.0; x <= max_m.x(); x += spacing_m) {
    waypoints.emplace_back(x, north ? min_m.y() : max_m.y());
    waypoints.emplace_back(x, north ? max_m.y() : min_m.y());
    north = !north;
  }
  if (waypoints.empty()) {
    const double x = (min_m.x() + max_m.x()) / 2.0;
    waypoints.emplace_back(x, min_m.y());
    waypoints.emplace_back(x, max_m.y());
  }
  return waypoints;
}

}  // namespace fireswarm::sim2d
