// Operator command MACs and their verifier: a known vector of the byte encoding
// (the page's JS builds the same bytes), RFC 4231's HMAC-SHA256 vector through
// ComputeCommandMac's primitive, and each refusal: unknown operator, forged MAC,
// every field altered, stale, replayed (in the window) and replayed after it.
#include "fireswarm/server/command_auth.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <stdexcept>
#include <string>

#include "fireswarm/server/operator_keys.hpp"

namespace fireswarm::server {
namespace {

constexpr std::int64_t kNowUs = 1'764'000'000'000'000;  // 2025-11-24, Unix epoch us
constexpr std::int64_t kSecondUs = 1'000'000;

common::SecretKey KeyOf(std::uint8_t fill) {
  common::SecretKey key{};
  key.fill(fill);
  return key;
}

OperatorCommand Retask() {
  OperatorCommand command;
  command.kind = OperatorCommand::Kind::kRetaskVehicle;
  command.vehicle = 3;
  command.point = {46.5, -74.25};
  command.radius_m = 20.0;
  command.reason = "smoke";
  return command;
}

std::string Hex(const std::vector<std::uint8_t>& bytes) {
  static constexpr char kDigits[] = "0123456789abcdef";
  std::string hex;
  for (const std::uint8_t b : bytes) {
    hex += kDigits[b >> 4];
    hex += kDigits[b & 15];
  }
  return hex;
}

TEST(CommandMacInput, IsTheDocumentedEncoding) {
  const CommandCredentials credentials{"ann", 0x0102030405060708, -2, {}};
  const std::vector<std::uint8_t> bytes = CommandMacInput(Retask(), credentials);
  // docs/lcm.md: tag, u8 len + operator, i64 utime, i64 nonce, i8 command, i16
  // target, 3 x f64 (46.5 = 0x4047400000000000, -74.25 = 0xc052900000000000,
  // 20 = 0x4034000000000000), u16 len + reason.
  EXPECT_EQ(Hex(bytes), Hex(std::vector<std::uint8_t>({'f', 'i', 'r', 'e', 's', 'w', 'a', 'r', 'm',
                                                       '-', 'c', 'm', 'd', '-', 'v', '1'})) +
                            "03616e6e" + "0102030405060708" + "fffffffffffffffe" + "05" + "0003" +
                            "4047400000000000" + "c052900000000000" + "4034000000000000" + "0005" +
                            "736d6f6b65");
}

TEST(CommandVerifier, AcceptsASignedCommandOnce) {
  CommandVerifier verifier({{"ann", KeyOf(1)}});
  const SignedCommand command = SignCommand(Retask(), "ann", KeyOf(1), kNowUs, 42);
  EXPECT_EQ(verifier.Verify(command, kNowUs + kSecondUs), CommandVerdict::kAccepted);
  EXPECT_EQ(verifier.Verify(command, kNowUs + 2 * kSecondUs), CommandVerdict::kReplayed);
  // Past the window the same bytes are stale, and the cache has let the nonce go.
  EXPECT_EQ(verifier.Verify(command, kNowUs + kDefaultCommandWindowUs + kSecondUs),
            CommandVerdict::kStale);
  const SignedCommand later = SignCommand(Retask(), "ann", KeyOf(1), kNowUs + 40 * kSecondUs, 43);
  EXPECT_EQ(verifier.Verify(later, kNowUs + 40 * kSecondUs), CommandVerdict::kAccepted);
  EXPECT_EQ(verifier.remembered(), 1u) << "the first nonce left with its window";
}

TEST(CommandVerifier, RefusesUnknownOperatorsAndForeignKeys) {
  CommandVerifier verifier({{"ann", KeyOf(1)}});
  EXPECT_EQ(verifier.Verify(SignCommand(Retask(), "bob", KeyOf(2), kNowUs, 1), kNowUs),
            CommandVerdict::kUnknownOperator);
  EXPECT_EQ(verifier.Verify(SignCommand(Retask(), "ann", KeyOf(2), kNowUs, 1), kNowUs),
            CommandVerdict::kBadMac);
  EXPECT_EQ(verifier.Verify(SignCommand(Retask(), "../ann", KeyOf(1), kNowUs, 1), kNowUs),
            CommandVerdict::kMalformed);
  CommandVerifier no_keys;
  EXPECT_EQ(no_keys.Verify(SignCommand(Retask(), "ann", KeyOf(1), kNowUs, 1), kNowUs),
            CommandVerdict::kUnknownOperator);
  SignedCommand unsigned_command{Retask(), {"ann", kNowUs, 1, {}}};
  EXPECT_EQ(verifier.Verify(unsigned_command, kNowUs), CommandVerdict::kBadMac);
}

TEST(CommandVerifier, RefusesEveryAlteredField) {
  CommandVerifier verifier({{"ann", KeyOf(1)}, {"bob", KeyOf(2)}});
  const SignedCommand good = SignCommand(Retask(), "ann", KeyOf(1), kNowUs, 7);
  const std::vector<void (*)(SignedCommand&)> alterations = {
      [](SignedCommand& c) { c.command.kind = OperatorCommand::Kind::kLand; },
      [](SignedCommand& c) { c.command.vehicle = 4; },
      [](SignedCommand& c) { c.command.point.lat_deg += 1e-9; },
      [](SignedCommand& c) { c.command.point.lon_deg = -c.command.point.lon_deg; },
      [](SignedCommand& c) { c.command.radius_m = 21.0; },
      [](SignedCommand& c) { c.command.reason += "!"; },
      [](SignedCommand& c) { c.credentials.operator_id = "bob"; },
      [](SignedCommand& c) { c.credentials.utime += 1; },
      [](SignedCommand& c) { c.credentials.nonce ^= 1; },
      [](SignedCommand& c) { c.credentials.mac[31] ^= 0x80; },
  };
  for (std::size_t i = 0; i < alterations.size(); ++i) {
    SignedCommand altered = good;
    alterations[i](altered);
    EXPECT_EQ(verifier.Verify(altered, kNowUs), CommandVerdict::kBadMac) << "alteration " << i;
  }
  EXPECT_EQ(verifier.Verify(good, kNowUs), CommandVerdict::kAccepted);
}

TEST(CommandVerifier, TheWindowReachesBothWays) {
  CommandVerifier verifier({{"ann", KeyOf(1)}}, 10 * kSecondUs);
  const auto at = [&](std::int64_t utime, std::int64_t nonce) {
    return verifier.Verify(SignCommand(Retask(), "ann", KeyOf(1), utime, nonce), kNowUs);
  };
  EXPECT_EQ(at(kNowUs - 10 * kSecondUs, 1), CommandVerdict::kAccepted);
  EXPECT_EQ(at(kNowUs + 10 * kSecondUs, 2), CommandVerdict::kAccepted);
  EXPECT_EQ(at(kNowUs - 10 * kSecondUs - 1, 3), CommandVerdict::kStale);
  EXPECT_EQ(at(kNowUs + 10 * kSecondUs + 1, 4), CommandVerdict::kStale);
  EXPECT_EQ(at(INT64_MIN, 5), CommandVerdict::kStale) << "no overflow";
  EXPECT_THROW(CommandVerifier({}, 0), std::invalid_argument);
}

TEST(LoadOperatorKeys, ReadsTheStoresOperatorKeys) {
  const std::filesystem::path store =
      std::filesystem::path(::testing::TempDir()) / ("operator_keys_" + std::to_string(getpid()));
  std::filesystem::remove_all(store);
  EXPECT_THROW(LoadOperatorKeys(store), std::runtime_error) << "no store";
  std::filesystem::create_directories(store);
  EXPECT_TRUE(LoadOperatorKeys(store).empty()) << "a store of vehicle keys only";
  std::filesystem::create_directories(store / kOperatorKeysDir);
  EXPECT_TRUE(LoadOperatorKeys(store).empty()) << "no operator yet";
  common::WriteSecretKeyFile(store / kOperatorKeysDir / "ann.key", KeyOf(1));
  common::WriteSecretKeyFile(store / kOperatorKeysDir / "bob.key", KeyOf(2));
  const auto keys = LoadOperatorKeys(store);
  ASSERT_EQ(keys.size(), 2u);
  EXPECT_EQ(keys.at("bob"), KeyOf(2));
  std::filesystem::permissions(store / kOperatorKeysDir / "bob.key",
                               std::filesystem::perms::group_read,
                               std::filesystem::perm_options::add);
  try {
    LoadOperatorKeys(store);
    ADD_FAILURE() << "a key readable by the group was taken";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("bob.key"), std::string::npos) << e.what();
  }
  std::filesystem::remove_all(store);
}

}  // namespace
}  // namespace fireswarm::server
