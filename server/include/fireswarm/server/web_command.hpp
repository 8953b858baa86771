// POST /api/command bodies (docs/command_center.md "Commands") -> the operator
// commands the server core takes, the same as operator_command_t on LCM.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "fireswarm/server/command_auth.hpp"
#include "fireswarm/server/operator_command.hpp"

namespace fireswarm::server {

/// The longest `reason` a web command may carry, bytes.
inline constexpr std::size_t kMaxReasonBytes = 200;

/// Parses one command body: {"kind": K, ...}. Kinds and their fields:
/// - per drone: `hold`, `resume`, `return`, `land` (`vehicle` required); `retask`
///   (`vehicle`, `lat`, `lon` required, `radius_m` optional);
/// - `investigate` (`lat`, `lon` required; `vehicle`, `radius_m` optional);
/// - fleet: `start`, `hold_all`, `resume_all`, `return_all`, `abort`;
/// - every kind: `reason` optional (a string of at most kMaxReasonBytes bytes),
///   `auth` (ParseWebCredentials; not read here).
/// `vehicle` is an integer 1..254, `lat` a number in [-90, 90], `lon` in
/// [-180, 180], `radius_m` a number in [0, 10000] (0 = the server's default).
/// Returns nullopt with `why` (when not null) naming the field and the problem,
/// e.g. "vehicle: must be an integer 1..254", "kind: unknown 'foo'",
/// "lat: not taken by 'hold'". Never throws.
std::optional<OperatorCommand> ParseWebCommand(const nlohmann::json& body, std::string* why);

/// The body's signature, {"auth": {"operator": ID, "utime": integer microseconds
/// on the server's clock, "nonce": 16 hex digits (64 bits, big-endian), "mac": 64
/// hex digits}} (command_auth.hpp; docs/command_center.md). Absent fields in the
/// command count as 0 (and "") in the MAC's bytes. Returns nullopt with `why`
/// naming the field ("auth.mac: must be 64 hex digits"). Never throws.
std::optional<CommandCredentials> ParseWebCredentials(const nlohmann::json& body, std::string* why);
/// `credentials` as the body's `auth` member (what ParseWebCredentials reads).
nlohmann::json WebCredentialsJson(const CommandCredentials& credentials);

}  // namespace fireswarm::server
