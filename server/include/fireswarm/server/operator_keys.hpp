// The operators' keys from a fleet key store: KEYS/operators/<operator ID>.key,
// one per operator, written by `fireswarm keys operator` (or
// common::WriteSecretKeyFile) and read through common::ReadSecretKeyFile (which
// refuses files open to group or others).
#pragma once

#include <filesystem>
#include <map>
#include <string>

#include "fireswarm/common/secret_key.hpp"

namespace fireswarm::server {

/// The key store's sub-directory of operator keys.
inline constexpr const char* kOperatorKeysDir = "operators";

/// Every `<id>.key` in `key_store`/operators (other files are ignored), ID -> key;
/// empty when the store has no operators (it may hold vehicle keys only). Throws
/// std::runtime_error naming the path when the store is missing, a key file is
/// unreadable, open to others or malformed, or its name is not a valid operator
/// ID (command_auth.hpp's IsValidOperatorId).
std::map<std::string, common::SecretKey> LoadOperatorKeys(const std::filesystem::path& key_store);

}  // namespace fireswarm::server
