// Things that happen in the simulated world, recorded for the report and for
// scoring: collisions, near misses, crashes, losses, take-offs and landings.
#pragma once

namespace fireswarm::sim2d {

enum class EventKind {
  kCollision,  ///< two vehicles' discs touch while their altitude bands overlap
  kNearMiss,   ///< two vehicles came closer (3D) than the near-miss separation
  kCrash,      ///< a vehicle hit the ground (or another vehicle) too hard
  kLoss,       ///< a total-loss fault removed a vehicle
  kTakeOff,
  kLanding,       ///< a soft touch-down
  kBatteryEmpty,  ///< the charge reached zero; the motors stop
  kBatterySwap,   ///< the ground crew put in a full pack (WorldConfig::battery_swap_s)
};

/// One event. `vehicle_b` is 0 for events of one vehicle.
struct WorldEvent {
  EventKind kind = EventKind::kCollision;
  double time_s = 0.0;  ///< simulated time when it began
  int vehicle_a = 0;    ///< receiver ID; for pairs the smaller ID
  int vehicle_b = 0;
  /// kCollision: |v_a - v_b| in 3D just before the impulse. kCrash: the impact
  /// speed (3D) against the ground or the other vehicle.
  double relative_speed_mps = 0.0;
  /// kNearMiss (and kCollision): the smallest 3D centre distance of the encounter.
  /// It keeps shrinking while `open` is true, i.e. while the encounter lasts.
  double min_separation_m = 0.0;
  bool open = false;  ///< kNearMiss: the vehicles are still inside the separation
};

}  // namespace fireswarm::sim2d
