// A minimal pilot that flies one simulated vehicle through a list of waypoints
// from its truth state: take off, fly each leg at a set speed and altitude, and
// land after the last. For benchmarks and simulator tests, before (and apart
// from) the real APOne autopilot in agents/. It cheats by reading truth, which
// vehicle software never may.
#pragma once

#include <vector>

#include "fireswarm/sim2d/vehicle_state.hpp"

namespace fireswarm::sim2d {

struct LanePilotParams {
  double altitude_m = 60.0;
  double speed_mps = 10.0;
  double acceptance_radius_m = 5.0;  ///< a waypoint counts as reached this close
  double velocity_gain_per_s = 0.8;  ///< desired acceleration per m/s of velocity error
  double altitude_gain_per_s = 0.8;  ///< climb rate per metre of altitude error
  double max_tilt_rad = 0.35;
  double heading_gain_per_s = 1.5;  ///< yaw rate per radian of heading error
};

class LanePilot {
 public:
  /// Throws std::invalid_argument when a parameter is not positive.
  LanePilot(std::vector<Vec2> waypoints_m, LanePilotParams params);

  /// The command for this step. Takes off first, lands after the last waypoint.
  ActuatorCommand Command(const VehicleTruth& truth);

  bool finished() const { return next_ >= waypoints_.size(); }
  std::size_t next_waypoint() const { return next_; }

 private:
  // Sets roll, pitch and yaw rate to fly toward `target_m` at the set speed.
  void SteerToward(const Vec2& target_m, const VehicleTruth& truth, ActuatorCommand& command) const;

  std::vector<Vec2> waypoints_;
  LanePilotParams params_;
  std::size_t next_ = 0;
};

/// Back-and-forth lanes (north-south) over the box [min_m, max_m], `spacing_m`
/// apart, starting at the south-west corner.
std::vector<Vec2> LawnmowerLanes(const Vec2& min_m, const Vec2& max_m, double spacing_m);

}  // namespace fireswarm::sim2d
