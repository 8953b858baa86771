#include "fireswarm/radio/simulation_keys.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "radio/secure_link.hpp"

namespace fireswarm::radio {
namespace {

TEST(SimulationKeys, FollowTheSeedAndDifferPerKeyId) {
  EXPECT_EQ(SimulationKey(7, 3), SimulationKey(7, 3));
  EXPECT_NE(SimulationKey(7, 3), SimulationKey(8, 3));
  EXPECT_NE(SimulationKey(7, 3), SimulationKey(7, 4));
  EXPECT_NE(SimulationKey(7, 3), SimulationKey(7, kBroadcastKeyId));
}

TEST(SimulationKeys, ServerAndVehicleOfOneSeedUnderstandEachOtherOnly) {
  const std::vector<std::uint8_t> ids{1, 2};
  auto server = SimulationServerSecurity(42, ids);
  auto vehicle = SimulationVehicleSecurity(42, 2);
  auto other_seed = SimulationVehicleSecurity(43, 2);
  std::vector<std::uint8_t> frame;
  ASSERT_EQ(AppendFrameFor(frame, 2, Poll{{kServerId, 1}}, ChecksumMode::kSecure, server.get()),
            SealStatus::kOk);
  EXPECT_EQ(secure_test::OpenAll(*vehicle, frame), std::vector{OpenStatus::kOk});
  EXPECT_EQ(secure_test::OpenAll(*other_seed, frame), std::vector{OpenStatus::kAuthFailed});
}

}  // namespace
}  // namespace fireswarm::radio
