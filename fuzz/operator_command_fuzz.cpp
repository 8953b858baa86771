// LCM operator commands on any bytes, as the LCM bridge takes them: decode an
// operator_command_t (DecodeOperatorCommand), FromLcm and CredentialsFromLcm, then Server::HandleSigned
// (refused unless the MAC is right), and the same command signed with the
// fuzzing operator's key, so Handle's checks see every command that decodes.
// Properties: nothing throws; a command FromLcm takes comes back the same from
// ToLcm (the MAC covers those fields); a forged MAC is never accepted.
#include <cstring>
#include <string>

#include "fireswarm/operator_command_t.hpp"
#include "fireswarm/server/command_auth.hpp"
#include "fireswarm/server/lcm_bridge.hpp"
#include "fireswarm/server/server.hpp"
#include "fuzz_check.hpp"

namespace server = fireswarm::server;

namespace {
using fireswarm::fuzz::Check;

constexpr const char* kOperator = "fuzz";
constexpr std::int64_t kNowUtime = 1'700'000'000'000'000;

const fireswarm::common::SecretKey& OperatorKey() {
  static const fireswarm::common::SecretKey key = [] {
    fireswarm::common::SecretKey bytes{};
    for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<std::uint8_t>(i * 7 + 1);
    return bytes;
  }();
  return key;
}

bool SameBits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

bool SameCommand(const server::OperatorCommand& a, const server::OperatorCommand& b) {
  return a.kind == b.kind && a.vehicle == b.vehicle && SameBits(a.point.lat_deg, b.point.lat_deg) &&
         SameBits(a.point.lon_deg, b.point.lon_deg) && SameBits(a.radius_m, b.radius_m) &&
         a.reason == b.reason;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::optional<fireswarm::operator_command_t> decoded =
      server::DecodeOperatorCommand({data, size});
  if (!decoded) return 0;
  const fireswarm::operator_command_t& message = *decoded;

  server::ServerConfig config;
  config.operators[kOperator] = OperatorKey();
  static const fireswarm::common::LocalFrame frame(fireswarm::common::LatLon{46.5, 6.6});
  server::Server core(config, frame);
  core.AddVehicle(1);
  const fireswarm::common::Nanos now{0};

  std::string why;
  const std::optional<server::OperatorCommand> command = server::FromLcm(message, &why);
  if (!command) {
    core.Refuse({.verdict = server::CommandVerdict::kMalformed,
                 .command = message.command,
                 .vehicle = message.target_vehicle,
                 .operator_id = message.operator_id,
                 .utime = message.utime,
                 .nonce = message.nonce,
                 .why = why},
                now);
    return 0;
  }
  const server::SignedCommand as_sent{*command, server::CredentialsFromLcm(message)};
  server::CommandVerdict verdict = server::CommandVerdict::kAccepted;
  core.HandleSigned(as_sent, now, kNowUtime, &why, nullptr, &verdict);
  if (verdict == server::CommandVerdict::kAccepted) {
    // Only with the right MAC: the fuzzing operator's over these exact fields.
    const server::CommandMac expected =
        server::ComputeCommandMac(OperatorKey(), *command, as_sent.credentials);
    Check(as_sent.credentials.operator_id == kOperator && as_sent.credentials.mac == expected,
          "a command accepted without its operator's MAC");
  }

  const server::SignedCommand signed_command =
      server::SignCommand(*command, kOperator, OperatorKey(), kNowUtime, message.nonce ^ 1);
  const std::optional<server::OperatorCommand> round_trip =
      server::FromLcm(server::ToLcm(signed_command), &why);
  Check(round_trip && SameCommand(*round_trip, *command), "ToLcm then FromLcm changes a command");
  core.HandleSigned(signed_command, now, kNowUtime, &why, nullptr, &verdict);
  return 0;
}
