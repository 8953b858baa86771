// The seed's PID controller (seed 6.5, Appendix A.1), kept line for line in its
// behaviour: proportional on the error, integral of the error over dt, derivative
// on the measurement (no kick when the set-point jumps), each term and the output
// clamped when a limit is set, dt in microseconds with the seed's roll-over guard.
//
// Fixes of the listing's evident typos, each tested:
//  * setK and the limit setters assigned members to themselves (`iMax = iMax`);
//    here they assign the arguments.
//  * lastFeedback was never initialised, so the first D term was
//    dGain * (garbage - feedback) / dt; here the first update after Reset() has D = 0.
//  * `last micros = 0;` in the constructor was a stray line; the caller owns the timer.
//
// One behaviour of the seed is kept but made optional: the seed clamps the I term
// (iValue) but lets the integrator state (iState) grow without bound, so after a
// long saturation the I term stays pinned until the error has been of the other
// sign for as long (wind-up). `AntiWindup::kClampState` stops the state at the
// clamp instead; the control cascade uses it.
#pragma once

#include <cstdint>

#include "fireswarm/common/time.hpp"

namespace fireswarm::agents {

enum class AntiWindup : std::uint8_t {
  kSeed,        ///< the seed's behaviour: iState unbounded, only iValue clamped
  kClampState,  ///< iState held where iGain * iState meets the I-term clamp
};

/// Symmetric or asymmetric clamp; unset (`enabled = false`) by default, as in the seed.
struct PidLimit {
  bool enabled = false;
  double min = 0.0;
  double max = 0.0;
};

class Pid {
 public:
  /// Gains zero, no limits, integrator and derivative history cleared.
  Pid() = default;

  /// Clears the integrator and the derivative history (seed reset(), which cleared
  /// iState only; clearing the last feedback too avoids a D kick on re-engagement).
  void Reset();
  /// seed setK(Kp, Ki, Kd).
  void SetGains(double p_gain, double i_gain, double d_gain);
  /// seed set_ITerm_Limits(min, max). Requires min <= max.
  void SetITermLimits(double min, double max);
  /// seed set_dTerm_Limits(min, max). Requires min <= max.
  void SetDTermLimits(double min, double max);
  /// seed set_output_Limits(min, max). Requires min <= max.
  void SetOutputLimits(double min, double max);
  void SetAntiWindup(AntiWindup mode) { anti_windup_ = mode; }
  /// Turns the three clamps off again (the state after construction).
  void ClearLimits() { i_limit_ = d_limit_ = output_limit_ = PidLimit{}; }

  /// seed updatePID(feedback, desire, dt): one controller step. `dt` is the time
  /// since the previous call (the seed counts it in microseconds); below 1 us it is
  /// taken as 1 us (the seed's guard for a timer that rolled over or did not advance).
  double Update(double feedback, double desire, common::Micros dt);

  double p_value() const { return p_value_; }
  double i_value() const { return i_value_; }
  double d_value() const { return d_value_; }
  double error() const { return error_; }
  double integrator_state() const { return i_state_; }

 private:
  static double Clamp(double value, const PidLimit& limit);

  double p_gain_ = 0.0;
  double i_gain_ = 0.0;
  double d_gain_ = 0.0;
  PidLimit i_limit_;
  PidLimit d_limit_;
  PidLimit output_limit_;
  AntiWindup anti_windup_ = AntiWindup::kSeed;

  double i_state_ = 0.0;
  double last_feedback_ = 0.0;
  bool has_last_feedback_ = false;
  double p_value_ = 0.0;
  double i_value_ = 0.0;
  double d_value_ = 0.0;
  double error_ = 0.0;
};

/// Microseconds from `last_us` to `now_us` on a free-running 32-bit microsecond
/// timer (the Arduino micros() the seed used), correct across its roll-over every
/// 71.6 minutes: unsigned subtraction wraps.
constexpr std::uint32_t ElapsedMicros(std::uint32_t now_us, std::uint32_t last_us) {
  return now_us - last_us;
}

}  // namespace fireswarm::agents
