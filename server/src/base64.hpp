// Base64 (RFC 4648, with padding) by OpenSSL's EVP_EncodeBlock: the one encoder
// of the tree, for binary data inside JSON (the command center's coverage bitset).
#pragma once

#include <cstdint>
#include <span>
#include <string>

namespace fireswarm::server::internal {

/// `bytes` in standard base64 (alphabet A-Z a-z 0-9 + /, '=' padding).
std::string Base64Encode(std::span<const std::uint8_t> bytes);

}  // namespace fireswarm::server::internal
