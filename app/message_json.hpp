// JSON views of radio messages for the `fireswarm` subcommands (radio-decode, and
// any command that prints or logs frames). Keys carry their units (lat_deg,
// altitude_m, time_ms, ...); enums appear by name, as in docs/protocol.md.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <span>
#include <string>

#include "fireswarm/radio/messages.hpp"

namespace fireswarm::app {

/// The decoded fields of `message`, keys in the message's declaration order:
/// {"sender": 3, "sequence": 513, "time_ms": ..., "lat_deg": 47.3977419, ...}.
nlohmann::ordered_json MessageToJson(const radio::Message& message);

/// Lower-case hex of `bytes` without separators ("0a1bff").
std::string HexString(std::span<const std::uint8_t> bytes);

}  // namespace fireswarm::app
