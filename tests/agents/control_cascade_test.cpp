#include "fireswarm/agents/control_cascade.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>

#include "fireswarm/common/angles.hpp"

namespace fireswarm::agents {
namespace {

using std::chrono::microseconds;
using std::chrono::milliseconds;

constexpr milliseconds kStep{2};
constexpr int kStepsPerSecond = 500;
constexpr double kCascadeTolerance = 1e-9;

// An integral-only loop with wide limits: every time it runs on a constant error
// its output moves, so counting output changes counts the runs.
PidGains IntegralOnly() {
  PidGains gains;
  gains.ki = 1.0;
  gains.i_limit = 100.0;
  gains.out_limit = 100.0;
  return gains;
}

CascadeConfig CountingConfig() {
  CascadeConfig config;
  config.roll = config.pitch = config.heading = config.altitude = IntegralOnly();
  config.max_tilt_rad = 10.0;
  config.max_yaw_rate_radps = 100.0;
  config.max_climb_mps = 100.0;
  config.max_descent_mps = 100.0;
  return config;  // 100 / 50 / 25 Hz by default
}

// Constant errors: roll 0.1 rad, heading 1 rad, altitude 1 m.
CascadeSetpoint CountingSetpoint() {
  CascadeSetpoint setpoint;
  setpoint.roll_rad = 0.1;
  setpoint.heading_rad = 1.0;
  setpoint.altitude_m = 1.0;
  return setpoint;
}

struct RunCounts {
  int attitude = 0;
  int heading = 0;
  int altitude = 0;
};

// Steps the cascade every 2 ms for one second from `start` and counts how often
// each loop's output changed.
RunCounts CountRuns(ControlCascade& cascade, Nanos start) {
  RunCounts counts;
  ActuatorOutputs previous;
  for (int step = 0; step < kStepsPerSecond; ++step) {
    const ActuatorOutputs out = cascade.Step(start + step * kStep, {}, CountingSetpoint());
    counts.attitude += out.roll_rad != previous.roll_rad ? 1 : 0;
    counts.heading += out.yaw_rate_radps != previous.yaw_rate_radps ? 1 : 0;
    counts.altitude += out.climb_rate_mps != previous.climb_rate_mps ? 1 : 0;
    previous = out;
  }
  return counts;
}

TEST(ControlCascade, EachLoopRunsAtItsOwnRate) {
  ControlCascade cascade(CountingConfig());
  const RunCounts counts = CountRuns(cascade, Nanos{0});
  EXPECT_EQ(counts.attitude, 100);
  EXPECT_EQ(counts.heading, 50);
  EXPECT_EQ(counts.altitude, 25);
  // Stabilisation is the fastest loop.
  EXPECT_GT(counts.attitude, counts.heading);
  EXPECT_GT(counts.heading, counts.altitude);
  // Each loop integrated its error over one second of its own dt: 0.1 * 1 s, ...
  EXPECT_NEAR(cascade.roll_pid().i_value(), 0.1, 1e-9);
  EXPECT_NEAR(cascade.heading_pid().i_value(), 1.0, 1e-9);
  EXPECT_NEAR(cascade.altitude_pid().i_value(), 1.0, 1e-9);
}

TEST(ControlCascade, RatesFollowTheConfiguration) {
  CascadeConfig config = CountingConfig();
  config.attitude_hz = 250.0;
  config.heading_hz = 20.0;
  config.altitude_hz = 10.0;
  ControlCascade cascade(config);
  const RunCounts counts = CountRuns(cascade, Nanos{0});
  EXPECT_EQ(counts.attitude, 250);
  EXPECT_EQ(counts.heading, 20);
  EXPECT_EQ(counts.altitude, 10);
}

TEST(ControlCascade, KeepsItsRatesAcrossTheMicrosecondRollOver) {
  // The 32-bit micros() wraps at 2^32 us (about 4294.97 s); start half a second
  // before and run one second across it.
  constexpr std::int64_t kWrapUs = std::int64_t{1} << 32;
  const Nanos start = microseconds{kWrapUs - 500'000};
  ControlCascade cascade(CountingConfig());
  const RunCounts counts = CountRuns(cascade, start);
  EXPECT_EQ(counts.attitude, 100);
  EXPECT_EQ(counts.heading, 50);
  EXPECT_EQ(counts.altitude, 25);
  // No giant dt at the wrap: the I terms are what one second of error gives (a
  // single 71-minute dt would have hit the 100 clamp).
  EXPECT_NEAR(cascade.roll_pid().i_value(), 0.1, 1e-9);
  EXPECT_NEAR(cascade.heading_pid().i_value(), 1.0, 1e-9);
  EXPECT_NEAR(cascade.altitude_pid().i_value(), 1.0, 1e-9);
}

TEST(ControlCascade, HeadingErrorWraps) {
  CascadeConfig config;
  config.heading.kp = 1.0;
  config.heading.out_limit = 10.0;
  {
    ControlCascade cascade(config);
    CascadeInput input;
    input.heading_rad = 10.0 * common::kRadPerDeg;
    CascadeSetpoint setpoint;
    setpoint.heading_rad = 350.0 * common::kRadPerDeg;
    // 20 deg to the left, not 340 to the right.
    EXPECT_NEAR(cascade.Step(Nanos{0}, input, setpoint).yaw_rate_radps, -20.0 * common::kRadPerDeg,
                kCascadeTolerance);
  }
  {
    ControlCascade cascade(config);
    CascadeInput input;
    input.heading_rad = 350.0 * common::kRadPerDeg;
    CascadeSetpoint setpoint;
    setpoint.heading_rad = 10.0 * common::kRadPerDeg;
    EXPECT_NEAR(cascade.Step(Nanos{0}, input, setpoint).yaw_rate_radps, 20.0 * common::kRadPerDeg,
                kCascadeTolerance);
  }
}

TEST(ControlCascade, ClimbRateOverrideBypassesTheAltitudeLoop) {
  CascadeConfig config;
  config.altitude.kp = 1.0;
  config.altitude.out_limit = 10.0;
  ControlCascade cascade(config);
  CascadeSetpoint setpoint;
  setpoint.altitude_m = 100.0;  // the loop alone would climb at the limit
  setpoint.climb_rate_mps = -1.5;
  EXPECT_NEAR(cascade.Step(Nanos{0}, {}, setpoint).climb_rate_mps, -1.5, kCascadeTolerance);
  EXPECT_EQ(cascade.altitude_pid().error(), 0.0);  // the PID did not run
  EXPECT_EQ(cascade.altitude_pid().p_value(), 0.0);
  // Without the override the loop takes over.
  setpoint.climb_rate_mps.reset();
  EXPECT_NEAR(cascade.Step(Nanos{milliseconds{40}}, {}, setpoint).climb_rate_mps,
              config.max_climb_mps, kCascadeTolerance);
  EXPECT_NEAR(cascade.altitude_pid().error(), 100.0, kCascadeTolerance);
}

TEST(ControlCascade, ClimbRateOverrideIsClamped) {
  CascadeConfig config;
  ControlCascade cascade(config);
  CascadeSetpoint setpoint;
  setpoint.climb_rate_mps = 50.0;
  EXPECT_NEAR(cascade.Step(Nanos{0}, {}, setpoint).climb_rate_mps, config.max_climb_mps,
              kCascadeTolerance);
  setpoint.climb_rate_mps = -50.0;
  EXPECT_NEAR(cascade.Step(Nanos{milliseconds{40}}, {}, setpoint).climb_rate_mps,
              -config.max_descent_mps, kCascadeTolerance);
}

TEST(ControlCascade, OutputsAreClampedToTheirLimits) {
  CascadeConfig config;
  // Strong loops with wide PID limits: only the cascade's own limits stop them.
  for (PidGains* gains : {&config.roll, &config.pitch, &config.heading, &config.altitude}) {
    gains->kp = 10.0;
    gains->out_limit = 1e3;
  }
  config.max_tilt_rad = 0.44;
  config.max_climb_mps = 3.0;
  config.max_descent_mps = 2.0;
  config.max_yaw_rate_radps = 1.57;

  struct Case {
    double sign;
    double climb_limit;
  };
  for (const Case& c : {Case{1.0, 3.0}, Case{-1.0, -2.0}}) {
    ControlCascade cascade(config);
    CascadeSetpoint setpoint;
    setpoint.roll_rad = c.sign * 1.0;  // beyond max_tilt
    setpoint.pitch_rad = c.sign * 1.0;
    setpoint.heading_rad = c.sign * 2.0;
    setpoint.altitude_m = c.sign * 100.0;
    CascadeInput input;
    input.roll_rad = -c.sign * 0.3;  // the PID pushes further out
    input.pitch_rad = -c.sign * 0.3;
    const ActuatorOutputs out = cascade.Step(Nanos{0}, input, setpoint);
    EXPECT_NEAR(out.roll_rad, c.sign * 0.44, kCascadeTolerance) << c.sign;
    EXPECT_NEAR(out.pitch_rad, c.sign * 0.44, kCascadeTolerance) << c.sign;
    EXPECT_NEAR(out.yaw_rate_radps, c.sign * 1.57, kCascadeTolerance) << c.sign;
    EXPECT_NEAR(out.climb_rate_mps, c.climb_limit, kCascadeTolerance) << c.sign;
    EXPECT_FALSE(out.armed);
  }
}

TEST(ControlCascade, AttitudeSetPointIsClampedBeforeThePid) {
  CascadeConfig config;
  config.roll.kp = 1.0;
  config.roll.out_limit = 10.0;
  config.max_tilt_rad = 0.44;
  ControlCascade cascade(config);
  CascadeSetpoint setpoint;
  setpoint.roll_rad = 1.0;
  CascadeInput input;
  input.roll_rad = 0.44;  // already at the limit: nothing left to correct
  cascade.Step(Nanos{0}, input, setpoint);
  EXPECT_NEAR(cascade.roll_pid().error(), 0.0, kCascadeTolerance);
}

TEST(ControlCascade, TrimsAreAdded) {
  CascadeConfig config;  // zero gains: the commands are set-point plus trim
  config.roll_trim_rad = 0.05;
  config.pitch_trim_rad = -0.03;
  ControlCascade cascade(config);
  CascadeSetpoint setpoint;
  setpoint.roll_rad = 0.1;
  setpoint.pitch_rad = -0.2;
  const ActuatorOutputs out = cascade.Step(Nanos{0}, {}, setpoint);
  EXPECT_NEAR(out.roll_rad, 0.15, kCascadeTolerance);
  EXPECT_NEAR(out.pitch_rad, -0.23, kCascadeTolerance);
}

TEST(ControlCascade, ResetRestartsTheLoops) {
  ControlCascade cascade(CountingConfig());
  CountRuns(cascade, Nanos{0});
  ASSERT_GT(cascade.roll_pid().i_value(), 0.0);
  cascade.Reset();
  EXPECT_EQ(cascade.roll_pid().i_value(), 0.0);
  EXPECT_EQ(cascade.altitude_pid().integrator_state(), 0.0);
  // The clocks restart too: the first step after a reset runs every loop.
  const ActuatorOutputs out = cascade.Step(Nanos{milliseconds{1'001}}, {}, CountingSetpoint());
  EXPECT_NE(out.roll_rad, 0.0);
  EXPECT_NE(out.yaw_rate_radps, 0.0);
  EXPECT_NE(out.climb_rate_mps, 0.0);
}

}  // namespace
}  // namespace fireswarm::agents
