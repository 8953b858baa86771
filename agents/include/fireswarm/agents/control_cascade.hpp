// The inner loops of the seed's cascade (seed 7.2, Figures 7.2-7.4), each at its
// own rate: attitude stabilisation fastest, then heading and altitude. Navigation
// (navigation.hpp) runs above them and hands down heading, roll, pitch and
// altitude set-points; the cascade turns them into the plant's attitude and climb
// commands (vehicle_io.hpp ActuatorOutputs).
//
//  * attitude (roll, pitch): command = set-point + trim + PID(measured, set-point).
//    The plant holds the commanded angle; the PID's I term removes what it does
//    not (a ballast that shifts the attitude the plant settles at).
//  * heading: yaw rate = PID on the wrapped heading error.
//  * altitude: climb rate = PID(altitude, set-point), unless a climb rate is given
//    directly (take-off, landing).
#pragma once

#include <cstdint>
#include <optional>

#include "fireswarm/agents/pid.hpp"
#include "fireswarm/agents/pid_gains.hpp"
#include "fireswarm/agents/vehicle_io.hpp"
#include "fireswarm/common/time.hpp"

namespace fireswarm::agents {

using common::Nanos;

struct CascadeConfig {
  PidGains roll;      ///< roll error (rad) -> roll command correction (rad)
  PidGains pitch;     ///< pitch error (rad) -> pitch command correction (rad)
  PidGains heading;   ///< heading error (rad) -> yaw rate (rad/s)
  PidGains altitude;  ///< altitude error (m) -> climb rate (m/s)
  double roll_trim_rad = 0.0;
  double pitch_trim_rad = 0.0;
  double max_tilt_rad = 0.44;
  double max_climb_mps = 3.0;
  double max_descent_mps = 2.0;
  double max_yaw_rate_radps = 1.57;
  double attitude_hz = 100.0;  ///< stabilisation: the fastest loop
  double heading_hz = 50.0;
  double altitude_hz = 25.0;
};

/// The measured attitude and altitude the loops close on.
struct CascadeInput {
  double roll_rad = 0.0;
  double pitch_rad = 0.0;
  double heading_rad = 0.0;
  double altitude_m = 0.0;
};

struct CascadeSetpoint {
  double roll_rad = 0.0;
  double pitch_rad = 0.0;
  double heading_rad = 0.0;
  double altitude_m = 0.0;
  /// When set, the climb rate commanded directly (m/s, up positive), bypassing the
  /// altitude loop.
  std::optional<double> climb_rate_mps;
};

class ControlCascade {
 public:
  explicit ControlCascade(const CascadeConfig& config = {});

  /// New gains and limits; integrators are kept.
  void Configure(const CascadeConfig& config);
  /// Clears every loop (on the ground, before a take-off).
  void Reset();

  /// Runs each loop whose period has passed since it last ran (dt to the PIDs in
  /// microseconds from a 32-bit micros() timer, as on the APOne) and returns the
  /// latest commands, `armed` false. `now` must not decrease.
  ActuatorOutputs Step(Nanos now, const CascadeInput& input, const CascadeSetpoint& setpoint);

  const Pid& roll_pid() const { return roll_; }
  const Pid& pitch_pid() const { return pitch_; }
  const Pid& heading_pid() const { return heading_; }
  const Pid& altitude_pid() const { return altitude_; }
  const CascadeConfig& config() const { return config_; }

 private:
  /// One loop's schedule on the 32-bit microsecond timer.
  struct LoopClock {
    bool started = false;
    std::uint32_t last_us = 0;
    /// The time since the loop last ran when it is due at `now_us`, else nullopt.
    std::optional<common::Micros> Due(std::uint32_t now_us, double rate_hz);
  };

  CascadeConfig config_;
  Pid roll_;
  Pid pitch_;
  Pid heading_;
  Pid altitude_;
  LoopClock attitude_clock_;
  LoopClock heading_clock_;
  LoopClock altitude_clock_;
  ActuatorOutputs output_;
};

}  // namespace fireswarm::agents
