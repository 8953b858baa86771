#include <gtest/gtest.h>

#include "fireswarm/radio/time.hpp"

namespace fireswarm::radio {
namespace {

TEST(Airtime, HundredBytesAt57600BaudTake17_36ms) {
  // 57,600 baud 8N1 carries 5,760 bytes/s, not 7,200: 100 bytes = 17.3611 ms.
  EXPECT_EQ(Airtime(100, 57'600).count(), 17'361'112);
  EXPECT_EQ(Airtime(5'760, 57'600), std::chrono::seconds(1));
}

}  // namespace
}  // namespace fireswarm::radio
