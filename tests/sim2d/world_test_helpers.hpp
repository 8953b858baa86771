// Small pilots and set-ups shared by the sim2d world tests.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include "fireswarm/common/units.hpp"
#include "fireswarm/sim2d/world.hpp"

namespace fireswarm::sim2d::testing {

inline constexpr double kG = common::kGravityMps2;

/// A vehicle with default parameters standing at `launch_m`.
inline VehicleConfig VehicleAt(int id, Vec2 launch_m) {
  VehicleConfig vehicle;
  vehicle.id = id;
  vehicle.launch_position_m = launch_m;
  return vehicle;
}

/// Armed, level, holding the current height.
inline ActuatorCommand Hover() {
  ActuatorCommand command;
  command.armed = true;
  return command;
}

inline ActuatorCommand Climb(double climb_rate_mps) {
  ActuatorCommand command = Hover();
  command.climb_rate_mps = climb_rate_mps;
  return command;
}

/// A position pilot for a vehicle with heading 0 (nose north): position P ->
/// velocity P -> tilt (east from roll, north from nose-down pitch); climb P on height.
inline ActuatorCommand FlyTo(const VehicleTruth& truth, const Vec2& target_m, double altitude_m,
                             double max_speed_mps = 3.0) {
  Vec2 velocity_wanted = 0.6 * (target_m - truth.position_m);
  if (velocity_wanted.norm() > max_speed_mps) {
    velocity_wanted *= max_speed_mps / velocity_wanted.norm();
  }
  const Vec2 accel_wanted = 1.5 * (velocity_wanted - truth.velocity_mps);
  constexpr double kMaxTilt = 0.35;
  ActuatorCommand command = Hover();
  command.roll_rad = std::clamp(std::atan(accel_wanted.x() / kG), -kMaxTilt, kMaxTilt);
  command.pitch_rad = std::clamp(-std::atan(accel_wanted.y() / kG), -kMaxTilt, kMaxTilt);
  command.climb_rate_mps = std::clamp(1.0 * (altitude_m - truth.altitude_m), -1.0, 2.0);
  return command;
}

/// Steps `world` for `duration_s`, calling `before_step` before each step.
inline void RunWith(World& world, double duration_s, const std::function<void()>& before_step) {
  const auto steps = static_cast<long>(std::llround(duration_s / world.step_s()));
  for (long i = 0; i < steps; ++i) {
    before_step();
    world.Step();
  }
}

/// Climbs vehicle `id` straight up to `altitude_m` (a proportional climb command),
/// lets it settle, and leaves it commanded to hover.
inline void TakeOffTo(World& world, int id, double altitude_m) {
  RunWith(world, altitude_m / 2.0 + 10.0, [&] {
    const VehicleTruth& truth = world.Truth(id);
    world.SetCommand(id, Climb(std::clamp(altitude_m - truth.altitude_m, -1.0, 2.0)));
  });
  world.SetCommand(id, Hover());
}

/// Counts events of one kind.
inline long CountEvents(const World& world, EventKind kind) {
  return std::count_if(world.events().begin(), world.events().end(),
                       [kind](const WorldEvent& e) { return e.kind == kind; });
}

inline std::vector<WorldEvent> EventsOf(const World& world, EventKind kind) {
  std::vector<WorldEvent> found;
  for (const WorldEvent& e : world.events()) {
    if (e.kind == kind) found.push_back(e);
  }
  return found;
}

}  // namespace fireswarm::sim2d::testing
