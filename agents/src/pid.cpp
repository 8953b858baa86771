#include "fireswarm/agents/pid.hpp"

#include <algorithm>
#include <cassert>

#include "fireswarm/common/time.hpp"

namespace fireswarm::agents {

namespace {
// seed: `if (dt < 1) { dt = 1; }` -- a zero or negative interval (timer roll-over
// handled badly, or two calls in one tick) must not divide by zero.
constexpr double kMinDtUs = 1.0;
}  // namespace

void Pid::Reset() {
  i_state_ = 0.0;
  has_last_feedback_ = false;
  p_value_ = i_value_ = d_value_ = error_ = 0.0;
}

void Pid::SetGains(double p_gain, double i_gain, double d_gain) {
  p_gain_ = p_gain;
  i_gain_ = i_gain;
  d_gain_ = d_gain;
}

void Pid::SetITermLimits(double min, double max) {
  assert(min <= max);
  i_limit_ = PidLimit{true, min, max};
}

void Pid::SetDTermLimits(double min, double max) {
  assert(min <= max);
  d_limit_ = PidLimit{true, min, max};
}

void Pid::SetOutputLimits(double min, double max) {
  assert(min <= max);
  output_limit_ = PidLimit{true, min, max};
}

double Pid::Clamp(double value, const PidLimit& limit) {
  if (!limit.enabled) return value;
  return std::clamp(value, limit.min, limit.max);
}

double Pid::Update(double feedback, double desire, common::Micros dt) {
  const double dt_s = std::max(dt.count(), kMinDtUs) / common::kMicrosPerSecond;
  error_ = desire - feedback;
  i_state_ += error_ * dt_s;
  p_value_ = p_gain_ * error_;
  i_value_ = Clamp(i_gain_ * i_state_, i_limit_);
  if (anti_windup_ == AntiWindup::kClampState && i_limit_.enabled && i_gain_ != 0.0) {
    // Hold the state where the clamp bites, so the I term leaves the clamp as soon
    // as the error changes sign.
    i_state_ = i_value_ / i_gain_;
  }
  // Derivative on the measurement: a set-point step does not kick the output.
  const double delta_feedback = has_last_feedback_ ? last_feedback_ - feedback : 0.0;
  d_value_ = Clamp(d_gain_ * delta_feedback / dt_s, d_limit_);
  last_feedback_ = feedback;
  has_last_feedback_ = true;
  return Clamp(p_value_ + i_value_ + d_value_, output_limit_);
}

}  // namespace fireswarm::agents
