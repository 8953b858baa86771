#include "fireswarm/server/web_command.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

namespace fireswarm::server {
namespace {

using Kind = OperatorCommand::Kind;

std::string Why(const nlohmann::json& body) {
  std::string why;
  EXPECT_FALSE(ParseWebCommand(body, &why)) << body.dump();
  return why;
}

TEST(ParseWebCommand, PerDroneKinds) {
  const std::pair<const char*, Kind> kinds[] = {{"hold", Kind::kHold},
                                                {"resume", Kind::kResume},
                                                {"return", Kind::kReturnVehicle},
                                                {"land", Kind::kLand}};
  for (const auto& [name, kind] : kinds) {
    std::string why;
    const std::optional<OperatorCommand> command =
        ParseWebCommand({{"kind", name}, {"vehicle", 3}, {"reason", "smoke"}}, &why);
    ASSERT_TRUE(command) << name << ": " << why;
    EXPECT_EQ(command->kind, kind) << name;
    EXPECT_EQ(command->vehicle, 3);
    EXPECT_EQ(command->reason, "smoke");
    EXPECT_EQ(Why({{"kind", name}}), "vehicle: required");
  }
}

TEST(ParseWebCommand, FleetKindsTakeNoVehicle) {
  const std::pair<const char*, Kind> kinds[] = {{"start", Kind::kStart},
                                                {"hold_all", Kind::kHoldAll},
                                                {"resume_all", Kind::kResumeAll},
                                                {"return_all", Kind::kReturnAll},
                                                {"abort", Kind::kAbort}};
  for (const auto& [name, kind] : kinds) {
    const std::optional<OperatorCommand> command = ParseWebCommand({{"kind", name}}, nullptr);
    ASSERT_TRUE(command) << name;
    EXPECT_EQ(command->kind, kind);
    EXPECT_EQ(command->vehicle, 0);
    EXPECT_EQ(Why({{"kind", name}, {"vehicle", 3}}),
              std::string("vehicle: not taken by '") + name + "'");
  }
}

TEST(ParseWebCommand, RetaskAndInvestigateTakeAPoint) {
  std::optional<OperatorCommand> command = ParseWebCommand(
      {{"kind", "retask"}, {"vehicle", 254}, {"lat", 46.5}, {"lon", 6.6}, {"radius_m", 30}},
      nullptr);
  ASSERT_TRUE(command);
  EXPECT_EQ(command->kind, Kind::kRetaskVehicle);
  EXPECT_EQ(command->vehicle, 254);
  EXPECT_DOUBLE_EQ(command->point.lat_deg, 46.5);
  EXPECT_DOUBLE_EQ(command->point.lon_deg, 6.6);
  EXPECT_DOUBLE_EQ(command->radius_m, 30.0);
  command = ParseWebCommand({{"kind", "investigate"}, {"lat", -10}, {"lon", 170}}, nullptr);
  ASSERT_TRUE(command);
  EXPECT_EQ(command->kind, Kind::kInvestigatePoint);
  EXPECT_EQ(command->vehicle, 0) << "the server chooses";
  EXPECT_DOUBLE_EQ(command->radius_m, 0.0) << "the server's default";
  command =
      ParseWebCommand({{"kind", "investigate"}, {"lat", 1}, {"lon", 2}, {"vehicle", 7}}, nullptr);
  ASSERT_TRUE(command);
  EXPECT_EQ(command->vehicle, 7);
}

TEST(ParseWebCommand, EveryErrorNamesTheField) {
  EXPECT_EQ(Why(nlohmann::json::array()), "body: must be a JSON object");
  EXPECT_EQ(Why("hold"), "body: must be a JSON object");
  EXPECT_EQ(Why(nlohmann::json::object()), "kind: required");
  EXPECT_EQ(Why({{"kind", 3}}), "kind: must be a string");
  EXPECT_EQ(Why({{"kind", "foo"}}), "kind: unknown 'foo'");
  EXPECT_EQ(Why({{"kind", std::string(500, 'x')}}), "kind: unknown '" + std::string(40, 'x') + "'");
  EXPECT_EQ(Why({{"kind", "hold"}, {"vehicle", 3}, {"speed", 2}}), "speed: unknown field");
  for (const nlohmann::json& vehicle :
       {nlohmann::json(0), nlohmann::json(255), nlohmann::json(-1), nlohmann::json(3.5),
        nlohmann::json("3"), nlohmann::json(nullptr), nlohmann::json(1ULL << 63)}) {
    EXPECT_EQ(Why({{"kind", "hold"}, {"vehicle", vehicle}}), "vehicle: must be an integer 1..254")
        << vehicle.dump();
  }
  EXPECT_EQ(Why({{"kind", "retask"}, {"vehicle", 3}, {"lon", 6.6}}), "lat: required");
  EXPECT_EQ(Why({{"kind", "investigate"}, {"lat", 1}}), "lon: required");
  EXPECT_EQ(Why({{"kind", "investigate"}, {"lat", 91}, {"lon", 0}}),
            "lat: must be a number in [-90, 90]");
  EXPECT_EQ(Why({{"kind", "investigate"}, {"lat", 0}, {"lon", "east"}}),
            "lon: must be a number in [-180, 180]");
  EXPECT_EQ(Why({{"kind", "investigate"}, {"lat", 0}, {"lon", 0}, {"radius_m", -1}}),
            "radius_m: must be a number in [0, 10000]");
  EXPECT_EQ(Why({{"kind", "hold"}, {"vehicle", 3}, {"lat", 1}}), "lat: not taken by 'hold'");
  EXPECT_EQ(Why({{"kind", "hold"}, {"vehicle", 3}, {"radius_m", 5}}),
            "radius_m: not taken by 'hold'");
  EXPECT_EQ(Why({{"kind", "abort"}, {"reason", 7}}),
            "reason: must be a string of at most 200 bytes");
  EXPECT_EQ(Why({{"kind", "abort"}, {"reason", std::string(201, 'r')}}),
            "reason: must be a string of at most 200 bytes");
  EXPECT_TRUE(ParseWebCommand({{"kind", "abort"}, {"reason", std::string(200, 'r')}}, nullptr));
}

TEST(ParseWebCredentials, ReadsWhatWebCredentialsJsonWrites) {
  CommandCredentials credentials{"ann.b-2", 1'764'000'000'123'456, -3, {}};
  for (std::size_t i = 0; i < credentials.mac.size(); ++i) {
    credentials.mac[i] = static_cast<std::uint8_t>(i * 7);
  }
  const nlohmann::json auth = WebCredentialsJson(credentials);
  EXPECT_EQ(auth.at("nonce"), "fffffffffffffffd") << "64 bits, big-endian";
  std::string why;
  const auto back = ParseWebCredentials({{"kind", "abort"}, {"auth", auth}}, &why);
  ASSERT_TRUE(back) << why;
  EXPECT_EQ(back->operator_id, credentials.operator_id);
  EXPECT_EQ(back->utime, credentials.utime);
  EXPECT_EQ(back->nonce, credentials.nonce);
  EXPECT_EQ(back->mac, credentials.mac);
  EXPECT_TRUE(ParseWebCommand({{"kind", "abort"}, {"auth", auth}}, &why)) << why;
}

TEST(ParseWebCredentials, NamesTheFieldThatIsWrong) {
  const nlohmann::json good = WebCredentialsJson({"ann", 5, 6, {}});
  const auto why = [&](const std::string& key, const nlohmann::json& value) {
    nlohmann::json auth = good;
    auth[key] = value;
    std::string text;
    EXPECT_FALSE(ParseWebCredentials({{"kind", "abort"}, {"auth", auth}}, &text)) << key;
    return text;
  };
  std::string text;
  EXPECT_FALSE(ParseWebCredentials({{"kind", "abort"}}, &text));
  EXPECT_TRUE(text.starts_with("auth: required")) << text;
  EXPECT_EQ(why("operator", "../etc"), "auth.operator: must be 1..64 of A-Z a-z 0-9 _ . -");
  EXPECT_EQ(why("utime", 1.5), "auth.utime: must be an integer, microseconds");
  EXPECT_EQ(why("nonce", "12"), "auth.nonce: must be 16 hex digits");
  EXPECT_EQ(why("mac", std::string(64, 'g')), "auth.mac: must be 64 hex digits");
  EXPECT_EQ(why("key", "secret"), "auth.key: unknown field");
}

}  // namespace
}  // namespace fireswarm::server
