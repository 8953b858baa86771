#include "fireswarm/agents/pid.hpp"

#include <gtest/gtest.h>

#include <cstdint>

namespace fireswarm::agents {
namespace {

constexpr common::Micros kOneSecondUs{1e6};
constexpr common::Micros kTenthSecondUs{1e5};
constexpr double kPidTolerance = 1e-9;

// --- gains and arithmetic

TEST(Pid, SetGainsStoresEachGain) {
  // The seed's setK assigned the members to themselves; each gain must really land.
  Pid proportional;
  proportional.SetGains(3.0, 0.0, 0.0);
  EXPECT_NEAR(proportional.Update(1.0, 3.0, kOneSecondUs), 3.0 * 2.0, kPidTolerance);

  Pid integral;
  integral.SetGains(0.0, 0.5, 0.0);
  // 2 units of error for 1 s: I state 2, I term 0.5 * 2.
  EXPECT_NEAR(integral.Update(0.0, 2.0, kOneSecondUs), 1.0, kPidTolerance);

  Pid derivative;
  derivative.SetGains(0.0, 0.0, 0.25);
  derivative.Update(0.0, 0.0, kOneSecondUs);
  // The measurement fell by 4 in 1 s: D = 0.25 * 4 / 1.
  EXPECT_NEAR(derivative.Update(-4.0, 0.0, kOneSecondUs), 1.0, kPidTolerance);
}

TEST(Pid, DefaultGainsGiveZero) {
  Pid pid;
  EXPECT_EQ(pid.Update(3.0, -7.0, kOneSecondUs), 0.0);
  EXPECT_EQ(pid.Update(-30.0, 70.0, kOneSecondUs), 0.0);
}

TEST(Pid, MatchesHandComputedTermsOverThreeSteps) {
  Pid pid;
  pid.SetGains(2.0, 0.5, 0.1);
  // dt = 0.1 s. Step 1: err 1, I state 0.1; P 2, I 0.05, D 0 (no history) -> 2.05.
  EXPECT_NEAR(pid.Update(0.0, 1.0, kTenthSecondUs), 2.05, kPidTolerance);
  EXPECT_NEAR(pid.p_value(), 2.0, kPidTolerance);
  EXPECT_NEAR(pid.i_value(), 0.05, kPidTolerance);
  EXPECT_NEAR(pid.d_value(), 0.0, kPidTolerance);
  EXPECT_NEAR(pid.error(), 1.0, kPidTolerance);
  EXPECT_NEAR(pid.integrator_state(), 0.1, kPidTolerance);
  // Step 2: feedback 0.2, err 0.8, I state 0.18; P 1.6, I 0.09,
  // D 0.1 * (0 - 0.2) / 0.1 = -0.2 -> 1.49.
  EXPECT_NEAR(pid.Update(0.2, 1.0, kTenthSecondUs), 1.49, kPidTolerance);
  EXPECT_NEAR(pid.d_value(), -0.2, kPidTolerance);
  EXPECT_NEAR(pid.integrator_state(), 0.18, kPidTolerance);
  // Step 3: feedback 0.5, err 0.5, I state 0.23; P 1.0, I 0.115,
  // D 0.1 * (0.2 - 0.5) / 0.1 = -0.3 -> 0.815.
  EXPECT_NEAR(pid.Update(0.5, 1.0, kTenthSecondUs), 0.815, kPidTolerance);
  EXPECT_NEAR(pid.p_value(), 1.0, kPidTolerance);
  EXPECT_NEAR(pid.i_value(), 0.115, kPidTolerance);
  EXPECT_NEAR(pid.d_value(), -0.3, kPidTolerance);
}

TEST(Pid, IntegratesOverDtInMicroseconds) {
  Pid pid;
  pid.SetGains(0.0, 1.0, 0.0);
  // 1 unit of error for 250 ms, then for 2.5 s.
  EXPECT_NEAR(pid.Update(0.0, 1.0, common::Micros{250'000.0}), 0.25, kPidTolerance);
  EXPECT_NEAR(pid.Update(0.0, 1.0, common::Micros{2'500'000.0}), 2.75, kPidTolerance);
}

// --- derivative on the measurement

TEST(Pid, SetPointStepGivesNoDerivativeKick) {
  Pid pid;
  pid.SetGains(0.0, 0.0, 1.0);
  pid.Update(5.0, 0.0, kTenthSecondUs);
  EXPECT_EQ(pid.Update(5.0, 100.0, kTenthSecondUs), 0.0);
  EXPECT_EQ(pid.d_value(), 0.0);
}

TEST(Pid, MeasurementStepGivesDerivativeAgainstTheChange) {
  Pid pid;
  pid.SetGains(0.0, 0.0, 1.0);
  pid.Update(5.0, 5.0, kTenthSecondUs);
  // The measurement rose by 1 in 0.1 s: D = -(1 / 0.1).
  EXPECT_NEAR(pid.Update(6.0, 5.0, kTenthSecondUs), -10.0, kPidTolerance);
  // And falls back: D = +10.
  EXPECT_NEAR(pid.Update(5.0, 5.0, kTenthSecondUs), 10.0, kPidTolerance);
}

TEST(Pid, FirstUpdateHasNoDerivativeKick) {
  // The seed never initialised lastFeedback: the first D was dGain * (garbage - x) / dt.
  Pid pid;
  pid.SetGains(0.0, 0.0, 1.0);
  EXPECT_EQ(pid.Update(123.0, 0.0, kTenthSecondUs), 0.0);
}

TEST(Pid, FirstUpdateAfterResetHasNoDerivativeKick) {
  Pid pid;
  pid.SetGains(0.0, 0.0, 1.0);
  pid.Update(0.0, 0.0, kTenthSecondUs);
  pid.Reset();
  EXPECT_EQ(pid.Update(500.0, 0.0, kTenthSecondUs), 0.0);
  EXPECT_EQ(pid.d_value(), 0.0);
  // The history restarts from the re-engagement value.
  EXPECT_NEAR(pid.Update(501.0, 0.0, kTenthSecondUs), -10.0, kPidTolerance);
}

TEST(Pid, ResetClearsTheIntegrator) {
  Pid pid;
  pid.SetGains(0.0, 1.0, 0.0);
  pid.Update(0.0, 1.0, kOneSecondUs);
  ASSERT_NEAR(pid.integrator_state(), 1.0, kPidTolerance);
  pid.Reset();
  EXPECT_EQ(pid.integrator_state(), 0.0);
  EXPECT_EQ(pid.i_value(), 0.0);
  EXPECT_NEAR(pid.Update(0.0, 1.0, kOneSecondUs), 1.0, kPidTolerance);
}

// --- the seed's dt guard

TEST(Pid, ZeroDtIsTakenAsOneMicrosecond) {
  Pid pid;
  pid.SetGains(0.0, 1.0, 0.0);
  EXPECT_NEAR(pid.Update(0.0, 1.0, common::Micros{0.0}), 1e-6, 1e-15);

  Pid derivative;
  derivative.SetGains(0.0, 0.0, 1.0);
  derivative.Update(0.0, 0.0, common::Micros{0.0});
  // Finite, not a division by zero: -1 / 1e-6.
  EXPECT_NEAR(derivative.Update(1.0, 0.0, common::Micros{0.0}), -1e6, 1e-3);
}

TEST(Pid, NegativeDtIsTakenAsOneMicrosecond) {
  Pid pid;
  pid.SetGains(0.0, 1.0, 0.0);
  // A negative dt must not integrate backwards.
  EXPECT_NEAR(pid.Update(0.0, 1.0, common::Micros{-5'000.0}), 1e-6, 1e-15);

  Pid derivative;
  derivative.SetGains(0.0, 0.0, 1.0);
  derivative.Update(0.0, 0.0, common::Micros{-1.0});
  EXPECT_NEAR(derivative.Update(1.0, 0.0, common::Micros{-1e9}), -1e6, 1e-3);
}

TEST(Pid, SubMicrosecondDtIsTakenAsOneMicrosecond) {
  Pid pid;
  pid.SetGains(0.0, 1.0, 0.0);
  EXPECT_NEAR(pid.Update(0.0, 1.0, common::Micros{0.25}), 1e-6, 1e-15);
}

// --- limits

TEST(Pid, LimitsAreOffByDefault) {
  // The seed starts with no clamp: huge terms pass through.
  Pid proportional;
  proportional.SetGains(1.0, 0.0, 0.0);
  EXPECT_EQ(proportional.Update(0.0, 1e9, kOneSecondUs), 1e9);
  EXPECT_EQ(proportional.Update(0.0, -1e9, kOneSecondUs), -1e9);

  Pid integral;
  integral.SetGains(0.0, 1.0, 0.0);
  EXPECT_NEAR(integral.Update(0.0, 1e6, 100.0 * kOneSecondUs), 1e8, 1e-3);

  Pid derivative;
  derivative.SetGains(0.0, 0.0, 1.0);
  derivative.Update(0.0, 0.0, common::Micros{1.0});
  EXPECT_NEAR(derivative.Update(-1e3, 0.0, common::Micros{1.0}), 1e9, 1e-3);
}

TEST(Pid, ITermClampedAtItsMaximum) {
  Pid pid;
  pid.SetGains(0.0, 1.0, 0.0);
  pid.SetITermLimits(-0.3, 0.5);
  EXPECT_NEAR(pid.Update(0.0, 0.4, kOneSecondUs), 0.4, kPidTolerance);  // inside
  EXPECT_NEAR(pid.Update(0.0, 0.4, kOneSecondUs), 0.5, kPidTolerance);  // 0.8 -> 0.5
  EXPECT_NEAR(pid.i_value(), 0.5, kPidTolerance);
}

TEST(Pid, ITermClampedAtItsMinimum) {
  Pid pid;
  pid.SetGains(0.0, 1.0, 0.0);
  pid.SetITermLimits(-0.3, 0.5);
  EXPECT_NEAR(pid.Update(0.0, -0.2, kOneSecondUs), -0.2, kPidTolerance);  // inside
  EXPECT_NEAR(pid.Update(0.0, -0.2, kOneSecondUs), -0.3, kPidTolerance);  // -0.4 -> -0.3
  EXPECT_NEAR(pid.i_value(), -0.3, kPidTolerance);
}

TEST(Pid, DTermClampedAtItsMaximum) {
  Pid pid;
  pid.SetGains(0.0, 0.0, 1.0);
  pid.SetDTermLimits(-2.0, 3.0);
  pid.Update(0.0, 0.0, kOneSecondUs);
  EXPECT_NEAR(pid.Update(-2.5, 0.0, kOneSecondUs), 2.5, kPidTolerance);   // inside
  EXPECT_NEAR(pid.Update(-10.0, 0.0, kOneSecondUs), 3.0, kPidTolerance);  // 7.5 -> 3
  EXPECT_NEAR(pid.d_value(), 3.0, kPidTolerance);
}

TEST(Pid, DTermClampedAtItsMinimum) {
  Pid pid;
  pid.SetGains(0.0, 0.0, 1.0);
  pid.SetDTermLimits(-2.0, 3.0);
  pid.Update(0.0, 0.0, kOneSecondUs);
  EXPECT_NEAR(pid.Update(1.5, 0.0, kOneSecondUs), -1.5, kPidTolerance);   // inside
  EXPECT_NEAR(pid.Update(11.5, 0.0, kOneSecondUs), -2.0, kPidTolerance);  // -10 -> -2
  EXPECT_NEAR(pid.d_value(), -2.0, kPidTolerance);
}

TEST(Pid, OutputClampedAtItsMaximum) {
  Pid pid;
  pid.SetGains(1.0, 0.0, 0.0);
  pid.SetOutputLimits(-4.0, 6.0);
  EXPECT_NEAR(pid.Update(0.0, 5.0, kOneSecondUs), 5.0, kPidTolerance);
  EXPECT_NEAR(pid.Update(0.0, 50.0, kOneSecondUs), 6.0, kPidTolerance);
  // The terms themselves are not clamped by the output limit.
  EXPECT_NEAR(pid.p_value(), 50.0, kPidTolerance);
}

TEST(Pid, OutputClampedAtItsMinimum) {
  Pid pid;
  pid.SetGains(1.0, 0.0, 0.0);
  pid.SetOutputLimits(-4.0, 6.0);
  EXPECT_NEAR(pid.Update(0.0, -3.0, kOneSecondUs), -3.0, kPidTolerance);
  EXPECT_NEAR(pid.Update(0.0, -50.0, kOneSecondUs), -4.0, kPidTolerance);
}

TEST(Pid, OutputClampAppliesToTheSumOfTheTerms) {
  Pid pid;
  pid.SetGains(1.0, 1.0, 0.0);
  pid.SetITermLimits(-10.0, 10.0);
  pid.SetOutputLimits(-1.0, 1.0);
  // P 0.8 and I 0.8: each inside the output limit, their sum is not.
  EXPECT_NEAR(pid.Update(0.0, 0.8, kOneSecondUs), 1.0, kPidTolerance);
}

// --- wind-up

// 100 steps of 0.1 s at error +10 (I state 100, the I term pinned at +1), then
// error -10 until the I term leaves the clamp. Returns the steps it took.
int StepsToLeaveTheClampAfterSaturation(AntiWindup mode) {
  constexpr int kSaturatedSteps = 100;
  constexpr int kGiveUpSteps = 1000;
  Pid pid;
  pid.SetGains(0.0, 1.0, 0.0);
  pid.SetITermLimits(-1.0, 1.0);
  pid.SetAntiWindup(mode);
  for (int step = 0; step < kSaturatedSteps; ++step) pid.Update(0.0, 10.0, kTenthSecondUs);
  EXPECT_NEAR(pid.i_value(), 1.0, kPidTolerance);
  for (int step = 1; step <= kGiveUpSteps; ++step) {
    pid.Update(0.0, -10.0, kTenthSecondUs);
    if (pid.i_value() < 1.0 - 1e-6) return step;
  }
  return kGiveUpSteps + 1;
}

TEST(Pid, SeedAntiWindupLetsTheStateGrowWithoutBound) {
  Pid pid;
  pid.SetGains(0.0, 1.0, 0.0);
  pid.SetITermLimits(-1.0, 1.0);
  for (int step = 0; step < 100; ++step) pid.Update(0.0, 10.0, kTenthSecondUs);
  EXPECT_NEAR(pid.integrator_state(), 100.0, 1e-6);
  EXPECT_NEAR(pid.i_value(), 1.0, kPidTolerance);
}

TEST(Pid, SeedAntiWindupKeepsTheITermPinnedAsLongAsItWasSaturated) {
  // The I state went up by 1 per step for 100 steps and comes down by 1 per step:
  // the I term stays at the clamp until the state is back under 1, 99 steps, and
  // leaves it on the 100th.
  EXPECT_EQ(StepsToLeaveTheClampAfterSaturation(AntiWindup::kSeed), 100);
}

TEST(Pid, ClampStateAntiWindupRecoversAtOnce) {
  EXPECT_EQ(StepsToLeaveTheClampAfterSaturation(AntiWindup::kClampState), 1);
}

TEST(Pid, ClampStateHoldsTheStateAtTheClampOnBothSides) {
  Pid pid;
  pid.SetGains(0.0, 2.0, 0.0);
  pid.SetITermLimits(-0.4, 1.0);
  pid.SetAntiWindup(AntiWindup::kClampState);
  for (int step = 0; step < 50; ++step) pid.Update(0.0, 10.0, kTenthSecondUs);
  EXPECT_NEAR(pid.integrator_state(), 0.5, kPidTolerance);  // 2 * 0.5 = the 1.0 clamp
  for (int step = 0; step < 50; ++step) pid.Update(0.0, -10.0, kTenthSecondUs);
  EXPECT_NEAR(pid.integrator_state(), -0.2, kPidTolerance);  // 2 * -0.2 = the -0.4 clamp
  EXPECT_NEAR(pid.i_value(), -0.4, kPidTolerance);
}

TEST(Pid, ClampStateWithoutAnITermLimitIntegratesFreely) {
  Pid pid;
  pid.SetGains(0.0, 1.0, 0.0);
  pid.SetAntiWindup(AntiWindup::kClampState);
  for (int step = 0; step < 10; ++step) pid.Update(0.0, 10.0, kTenthSecondUs);
  EXPECT_NEAR(pid.integrator_state(), 10.0, 1e-9);
}

// --- the 32-bit microsecond timer

TEST(ElapsedMicros, CountsForwardWithoutWrap) {
  EXPECT_EQ(ElapsedMicros(1'500u, 1'000u), 500u);
  EXPECT_EQ(ElapsedMicros(7u, 7u), 0u);
}

TEST(ElapsedMicros, CountsAcrossTheRollOver) {
  constexpr std::uint32_t kJustBeforeWrap = 0xFFFF'FFF0u;
  static_assert(ElapsedMicros(5u, kJustBeforeWrap) == 21u);
  EXPECT_EQ(ElapsedMicros(5u, kJustBeforeWrap), 21u);
  EXPECT_EQ(ElapsedMicros(0u, 0xFFFF'FFFFu), 1u);
  // A 10 ms period straddling the wrap.
  EXPECT_EQ(ElapsedMicros(5'000u, 0xFFFF'FFFFu - 4'999u), 10'000u);
}

}  // namespace
}  // namespace fireswarm::agents
