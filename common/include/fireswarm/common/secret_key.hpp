// The 256-bit keys that secure the fleet: one per vehicle for its radio link,
// one per operator for commands. A key lives in a file of its own that only its
// owner may read; every module reads and writes keys through here.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>

namespace fireswarm::common {

inline constexpr std::size_t kSecretKeyBytes = 32;
using SecretKey = std::array<std::uint8_t, kSecretKeyBytes>;

/// A fresh key from OpenSSL's CSPRNG. Throws std::runtime_error if it fails.
SecretKey GenerateSecretKey();

/// Writes `key` as one line of 64 lowercase hex digits, atomically, with mode
/// 0600 from the first byte on. Throws std::runtime_error naming the path.
void WriteSecretKeyFile(const std::filesystem::path& path, const SecretKey& key);

/// Reads a key file written by WriteSecretKeyFile. Throws std::runtime_error
/// naming the path when it is missing, not a regular file, readable or writable
/// by group or others (the message says which mode and how to fix it), or not
/// exactly 64 hex digits (plus an optional line end).
SecretKey ReadSecretKeyFile(const std::filesystem::path& path);

}  // namespace fireswarm::common
