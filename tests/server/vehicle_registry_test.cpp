#include "fireswarm/server/vehicle_registry.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "fireswarm/vehicle_state_t.hpp"

namespace fireswarm::server {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::IsEmpty;

// The LCM bridge copies LinkState into vehicle_state_t.link_state unchanged.
static_assert(static_cast<int>(LinkState::kNeverHeard) == vehicle_state_t::LINK_NEVER_HEARD);
static_assert(static_cast<int>(LinkState::kOk) == vehicle_state_t::LINK_OK);
static_assert(static_cast<int>(LinkState::kDegraded) == vehicle_state_t::LINK_DEGRADED);
static_assert(static_cast<int>(LinkState::kLost) == vehicle_state_t::LINK_LOST);

radio::Telemetry TelemetryFrom(std::uint8_t sender, std::uint16_t sequence) {
  radio::Telemetry telemetry;
  telemetry.header.sender = sender;
  telemetry.header.sequence = sequence;
  telemetry.lat_deg = 46.5;
  telemetry.lon_deg = 6.6;
  telemetry.altitude_m = 40.0;
  telemetry.mode = radio::FlightMode::kSearch;
  telemetry.flags = radio::telemetry_flags::kGpsFix;
  return telemetry;
}

std::string MessageOfRegister(VehicleRegistry& registry, int id) {
  try {
    registry.Register(id);
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

TEST(VehicleRegistry, RefusesADuplicateIdNamingIt) {
  VehicleRegistry registry;
  registry.Register(7);
  EXPECT_THAT(MessageOfRegister(registry, 7), HasSubstr("7 is already registered"));
  EXPECT_EQ(registry.size(), 1U);
}

TEST(VehicleRegistry, RefusesIdsOutsideOneTo254) {
  VehicleRegistry registry;
  for (const int id : {0, 255, 256, 300, -1}) {
    EXPECT_THAT(MessageOfRegister(registry, id), HasSubstr(std::to_string(id) + " is outside"))
        << id;
  }
  EXPECT_EQ(registry.size(), 0U);
  registry.Register(kFirstVehicleId);
  registry.Register(kLastVehicleId);
  EXPECT_THAT(registry.ids(), ElementsAre(1, 254));
}

TEST(VehicleRegistry, ListsIdsAscendingWhateverTheRegistrationOrder) {
  VehicleRegistry registry;
  for (const int id : {42, 3, 200, 17}) registry.Register(id);
  EXPECT_THAT(registry.ids(), ElementsAre(3, 17, 42, 200));
  EXPECT_TRUE(registry.Contains(17));
  EXPECT_FALSE(registry.Contains(18));
}

TEST(VehicleRegistry, RefusesThresholdsOutOfOrder) {
  EXPECT_THROW(VehicleRegistry(LinkThresholds{10.0, 3.0}), std::invalid_argument);
  EXPECT_THROW(VehicleRegistry(LinkThresholds{0.0, 3.0}), std::invalid_argument);
  EXPECT_THROW(VehicleRegistry(LinkThresholds{3.0, 3.0}), std::invalid_argument);
}

TEST(VehicleRegistry, LinkGoesNeverHeardOkDegradedLostWithSilence) {
  VehicleRegistry registry;  // degraded after 3 s, lost after 10 s
  registry.Register(5);
  EXPECT_EQ(registry.LinkAt(5, 0.0), LinkState::kNeverHeard);
  EXPECT_EQ(registry.LinkAt(5, 1000.0), LinkState::kNeverHeard);

  ASSERT_TRUE(registry.OnTelemetry(TelemetryFrom(5, 1), 100.0));
  EXPECT_EQ(registry.LinkAt(5, 100.0), LinkState::kOk);
  EXPECT_EQ(registry.LinkAt(5, 102.9), LinkState::kOk);
  EXPECT_EQ(registry.LinkAt(5, 103.0), LinkState::kDegraded);
  EXPECT_EQ(registry.LinkAt(5, 109.9), LinkState::kDegraded);
  EXPECT_EQ(registry.LinkAt(5, 110.0), LinkState::kLost);
  EXPECT_THAT(registry.LostAt(110.0), ElementsAre(5));

  // Heard again: back to Ok.
  ASSERT_TRUE(registry.OnTelemetry(TelemetryFrom(5, 2), 111.0));
  EXPECT_EQ(registry.LinkAt(5, 111.5), LinkState::kOk);
  EXPECT_THAT(registry.LostAt(111.5), IsEmpty());
}

TEST(VehicleRegistry, UsesConfiguredThresholds) {
  VehicleRegistry registry(LinkThresholds{1.0, 2.0});
  registry.Register(9);
  ASSERT_TRUE(registry.OnReply(9, 0.0));
  EXPECT_EQ(registry.LinkAt(9, 0.5), LinkState::kOk);
  EXPECT_EQ(registry.LinkAt(9, 1.5), LinkState::kDegraded);
  EXPECT_EQ(registry.LinkAt(9, 2.0), LinkState::kLost);
}

TEST(VehicleRegistry, KeepsTheLatestTelemetryWithItsReceptionTime) {
  VehicleRegistry registry;
  registry.Register(3);
  EXPECT_FALSE(registry.state(3).telemetry.has_value());
  EXPECT_EQ(registry.TelemetryAgeS(3, 5.0), std::nullopt);

  radio::Telemetry first = TelemetryFrom(3, 1);
  radio::Telemetry second = TelemetryFrom(3, 2);
  second.altitude_m = 55.0;
  ASSERT_TRUE(registry.OnTelemetry(first, 10.0));
  ASSERT_TRUE(registry.OnTelemetry(second, 12.0));
  EXPECT_EQ(registry.state(3).telemetry, second);
  EXPECT_DOUBLE_EQ(registry.state(3).telemetry_time_s, 12.0);
  EXPECT_DOUBLE_EQ(*registry.TelemetryAgeS(3, 14.5), 2.5);

  // A late duplicate stamped earlier does not replace newer telemetry.
  EXPECT_FALSE(registry.OnTelemetry(first, 11.0));
  EXPECT_EQ(registry.state(3).telemetry, second);
}

TEST(VehicleRegistry, IgnoresTelemetryFromUnregisteredSenders) {
  VehicleRegistry registry;
  registry.Register(3);
  EXPECT_FALSE(registry.OnTelemetry(TelemetryFrom(4, 1), 1.0));
  EXPECT_FALSE(registry.OnReply(4, 1.0));
  EXPECT_FALSE(registry.OnMissedReply(4));
  EXPECT_EQ(registry.LinkAt(3, 1.0), LinkState::kNeverHeard);
  EXPECT_THAT(registry.ids(), ElementsAre(3));
}

TEST(VehicleRegistry, CountsConsecutiveMissedRepliesUntilAnAnswer) {
  VehicleRegistry registry;
  registry.Register(8);
  for (int turn = 0; turn < 3; ++turn) ASSERT_TRUE(registry.OnMissedReply(8));
  EXPECT_EQ(registry.state(8).missed_replies, 3U);

  ASSERT_TRUE(registry.OnReply(8, 4.0));
  EXPECT_EQ(registry.state(8).missed_replies, 0U);
  ASSERT_TRUE(registry.OnMissedReply(8));
  ASSERT_TRUE(registry.OnTelemetry(TelemetryFrom(8, 1), 6.0));  // telemetry answers too
  EXPECT_EQ(registry.state(8).missed_replies, 0U);

  EXPECT_EQ(registry.state(8).total_missed_replies, 4U);
  EXPECT_EQ(registry.state(8).total_replies, 2U);
}

TEST(VehicleRegistry, AnyReplyKeepsTheLinkAliveButNotTheTelemetryAge) {
  VehicleRegistry registry;
  registry.Register(2);
  ASSERT_TRUE(registry.OnTelemetry(TelemetryFrom(2, 1), 0.0));
  ASSERT_TRUE(registry.OnReply(2, 8.0));  // e.g. a fire report
  EXPECT_EQ(registry.LinkAt(2, 9.0), LinkState::kOk);
  EXPECT_DOUBLE_EQ(*registry.TelemetryAgeS(2, 9.0), 9.0);
  // A reply handled late does not move the last-heard time back.
  ASSERT_TRUE(registry.OnReply(2, 1.0));
  EXPECT_EQ(registry.LinkAt(2, 9.0), LinkState::kOk);
}

TEST(VehicleRegistry, SplitsActiveFromLostAndNeverHeard) {
  VehicleRegistry registry;
  for (const int id : {1, 2, 3, 4}) registry.Register(id);
  ASSERT_TRUE(registry.OnTelemetry(TelemetryFrom(4, 1), 0.0));   // lost at 20
  ASSERT_TRUE(registry.OnTelemetry(TelemetryFrom(2, 1), 15.0));  // degraded at 20
  ASSERT_TRUE(registry.OnTelemetry(TelemetryFrom(1, 1), 19.0));  // ok at 20
  // 3 never heard: neither active nor lost.
  EXPECT_THAT(registry.ActiveAt(20.0), ElementsAre(1, 2));
  EXPECT_THAT(registry.LostAt(20.0), ElementsAre(4));
  EXPECT_EQ(registry.LinkAt(3, 20.0), LinkState::kNeverHeard);
}

TEST(VehicleRegistry, QueriesOfAnUnknownIdThrowNamingIt) {
  VehicleRegistry registry;
  try {
    (void)registry.state(77);
    FAIL() << "no exception";
  } catch (const std::out_of_range& error) {
    EXPECT_THAT(error.what(), HasSubstr("77 is not registered"));
  }
  EXPECT_THROW((void)registry.LinkAt(77, 0.0), std::out_of_range);
  EXPECT_THROW((void)registry.TelemetryAgeS(77, 0.0), std::out_of_range);
}

TEST(LinkState, NamesEveryState) {
  EXPECT_EQ(ToString(LinkState::kNeverHeard), "never_heard");
  EXPECT_EQ(ToString(LinkState::kOk), "ok");
  EXPECT_EQ(ToString(LinkState::kDegraded), "degraded");
  EXPECT_EQ(ToString(LinkState::kLost), "lost");
}

}  // namespace
}  // namespace fireswarm::server
