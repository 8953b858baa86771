// The state of one simulated multirotor and the commands it accepts: the
// contract between the world (dynamics), the sensors, the cameras, and the
// vehicle software that flies it.
//
// Frames: local ENU metres on flat ground around the scenario's geodetic origin
// (x east, y north, altitude up above the ground). Attitude is aerospace
// body FRD relative to NED: roll positive right wing down, pitch positive nose
// up, heading clockwise from true north. A multirotor flies forward with its
// nose pitched down (negative pitch).
#pragma once

#include <Eigen/Core>

namespace fireswarm::sim2d {

/// A horizontal vector in the local frame: x east, y north, metres (or m/s).
using Vec2 = Eigen::Vector2d;

enum class FlightPhase {
  kOnGround,  ///< resting on the ground, motors idle or spooling up
  kFlying,
  kCrashed,  ///< hit the ground (or another drone) too hard; no longer moves
  kLost,     ///< removed by a total-loss fault; no longer moves or senses
};

/// Truth about one vehicle. Used by the cameras and for scoring; the vehicle's
/// own software sees only sensor readings (sensors.hpp) and images.
struct VehicleTruth {
  int id = 0;                        ///< receiver ID
  Vec2 position_m = Vec2::Zero();    ///< local ENU
  double altitude_m = 0.0;           ///< above ground
  Vec2 velocity_mps = Vec2::Zero();  ///< local ENU
  double climb_rate_mps = 0.0;       ///< positive up
  double roll_rad = 0.0;
  double pitch_rad = 0.0;
  double heading_rad = 0.0;  ///< clockwise from north, in [0, 2 pi)
  double roll_rate_radps = 0.0;
  double pitch_rate_radps = 0.0;
  double yaw_rate_radps = 0.0;    ///< clockwise seen from above
  double battery_fraction = 1.0;  ///< charge left, 0..1
  FlightPhase phase = FlightPhase::kOnGround;
};

/// The attitude-loop set-points of the seed's cascade (navigation -> attitude):
/// the plant's attitude follows them through a first-order lag with rate limits,
/// and thrust follows the commanded climb rate.
struct ActuatorCommand {
  double roll_rad = 0.0;
  double pitch_rad = 0.0;
  double yaw_rate_radps = 0.0;
  double climb_rate_mps = 0.0;  ///< positive up; on the ground, > 0 takes off
  bool armed = false;           ///< motors on; disarmed in the air means falling
};

}  // namespace fireswarm::sim2d
