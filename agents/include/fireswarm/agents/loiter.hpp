// Investigate (seed 7.4): circle a point at a given radius with the heading, and so
// a forward-looking or nadir camera's forward edge, on the point. The heading
// set-point is the bearing to the centre; a radial PID holds the radius (forward
// tilt, toward the centre) and a speed PID the tangential speed (roll: the vehicle
// circles clockwise seen from above, moving to its right).
#pragma once

#include "fireswarm/agents/navigation.hpp"
#include "fireswarm/agents/pid.hpp"
#include "fireswarm/agents/pid_gains.hpp"
#include "fireswarm/common/local_frame.hpp"
#include "fireswarm/common/time.hpp"

namespace fireswarm::agents {

struct LoiterConfig {
  PidGains radial;  ///< radius error (m) -> tilt toward the centre (rad)
  PidGains speed;   ///< tangential speed error (m/s) -> tilt along the circle (rad)
  double speed_mps = 3.0;
  double max_tilt_rad = 0.35;
};

class Loiter {
 public:
  explicit Loiter(const LoiterConfig& config = {});
  void Configure(const LoiterConfig& config);
  /// Starts circling `center` (local frame) at `radius_m` and `altitude_m`.
  void Start(common::EastNorth center, double radius_m, double altitude_m);
  NavigationSetpoint Step(const NavigationInput& input, common::Micros dt);

  common::EastNorth center() const { return center_; }
  double radius_m() const { return radius_m_; }
  /// Distance from the centre minus the radius at the last step (m).
  double radius_error_m() const { return radius_error_m_; }

 private:
  LoiterConfig config_;
  common::EastNorth center_;
  double radius_m_ = 0.0;
  double altitude_m_ = 0.0;
  double radius_error_m_ = 0.0;
  Pid radial_pid_;
  Pid speed_pid_;
};

}  // namespace fireswarm::agents
