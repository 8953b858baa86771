#include "fireswarm/agents/control_cascade.hpp"

#include <algorithm>
#include <cmath>

#include "fireswarm/common/angles.hpp"
#include "fireswarm/common/time.hpp"

namespace fireswarm::agents {

namespace {}  // namespace

std::optional<common::Micros> ControlCascade::LoopClock::Due(std::uint32_t now_us, double rate_hz) {
  if (!started) {
    started = true;
    last_us = now_us;
    return common::Micros{common::kMicrosPerSecond /
                          rate_hz};  // the first run takes one nominal period
  }
  const std::uint32_t elapsed_us = ElapsedMicros(now_us, last_us);
  // Half a microsecond of slack per period so a 100 Hz loop stepped every 10 ms
  // does not skip a beat to rounding.
  if (static_cast<double>(elapsed_us) + 0.5 < common::kMicrosPerSecond / rate_hz)
    return std::nullopt;
  last_us = now_us;
  return common::Micros{static_cast<double>(elapsed_us)};
}

ControlCascade::ControlCascade(const CascadeConfig& config) {
  Configure(config);
}

void ControlCascade::Configure(const CascadeConfig& config) {
  config_ = config;
  ApplyGains(config_.roll, roll_);
  ApplyGains(config_.pitch, pitch_);
  ApplyGains(config_.heading, heading_);
  ApplyGains(config_.altitude, altitude_);
}

void ControlCascade::Reset() {
  roll_.Reset();
  pitch_.Reset();
  heading_.Reset();
  altitude_.Reset();
  attitude_clock_ = LoopClock{};
  heading_clock_ = LoopClock{};
  altitude_clock_ = LoopClock{};
  output_ = ActuatorOutputs{};
}

ActuatorOutputs ControlCascade::Step(Nanos now, const CascadeInput& input,
                                     const CascadeSetpoint& setpoint) {
  // The APOne's micros(): a 32-bit counter that rolls over every 71.6 minutes.
  const auto now_us = static_cast<std::uint32_t>(static_cast<std::uint64_t>(
      std::chrono::duration_cast<std::chrono::microseconds>(now).count()));

  if (const auto dt = attitude_clock_.Due(now_us, config_.attitude_hz)) {
    const double tilt = config_.max_tilt_rad;
    const double roll_target = std::clamp(setpoint.roll_rad, -tilt, tilt);
    const double pitch_target = std::clamp(setpoint.pitch_rad, -tilt, tilt);
    output_.roll_rad = std::clamp(
        roll_target + config_.roll_trim_rad + roll_.Update(input.roll_rad, roll_target, *dt), -tilt,
        tilt);
    output_.pitch_rad = std::clamp(
        pitch_target + config_.pitch_trim_rad + pitch_.Update(input.pitch_rad, pitch_target, *dt),
        -tilt, tilt);
  }
  if (const auto dt = heading_clock_.Due(now_us, config_.heading_hz)) {
    // Close the loop on the wrapped error: feedback -error against a zero set-point
    // keeps the derivative on the measurement (d(-error)/dt = heading rate).
    const double error = common::WrapPi(setpoint.heading_rad - input.heading_rad);
    output_.yaw_rate_radps = std::clamp(heading_.Update(-error, 0.0, *dt),
                                        -config_.max_yaw_rate_radps, config_.max_yaw_rate_radps);
  }
  if (const auto dt = altitude_clock_.Due(now_us, config_.altitude_hz)) {
    const double climb = setpoint.climb_rate_mps
                             ? *setpoint.climb_rate_mps
                             : altitude_.Update(input.altitude_m, setpoint.altitude_m, *dt);
    output_.climb_rate_mps = std::clamp(climb, -config_.max_descent_mps, config_.max_climb_mps);
  }
  output_.armed = false;
  return output_;
}

}  // namespace fireswarm::agents
