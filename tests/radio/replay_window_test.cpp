#include "fireswarm/radio/replay_window.hpp"

#include <gtest/gtest.h>

namespace fireswarm::radio {
namespace {

TEST(ReplayWindow, AcceptsEachCounterOnceInAnyOrderWithinTheWindow) {
  ReplayWindow window;
  for (const std::uint32_t c : {5U, 3U, 9U, 4U, 100U, 99U, 37U}) {
    ASSERT_TRUE(window.IsFresh(c)) << c;
    window.Mark(c);
    EXPECT_FALSE(window.IsFresh(c)) << c;
  }
  EXPECT_FALSE(window.IsFresh(36U)) << "64 or more below the highest is too old";
  EXPECT_TRUE(window.IsFresh(38U));
  EXPECT_EQ(window.NextFloor(), 101U);
}

TEST(ReplayWindow, FloorRefusesEverythingBelowIt) {
  ReplayWindow window(1000);
  EXPECT_FALSE(window.IsFresh(0));
  EXPECT_FALSE(window.IsFresh(999));
  EXPECT_TRUE(window.IsFresh(1000));
  EXPECT_EQ(window.NextFloor(), 1000U);
}

TEST(ReplayWindow, LargeJumpForgetsTheOldBitmap) {
  ReplayWindow window;
  window.Mark(1);
  window.Mark(1'000'000);
  EXPECT_FALSE(window.IsFresh(1));
  EXPECT_TRUE(window.IsFresh(999'999));
  EXPECT_TRUE(window.IsFresh(1'000'000 - 63));
  EXPECT_FALSE(window.IsFresh(1'000'000 - 64));
}

}  // namespace
}  // namespace fireswarm::radio
