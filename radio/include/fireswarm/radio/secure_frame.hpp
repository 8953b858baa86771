// Secure APOne frames: AES-256-GCM through OpenSSL EVP, no hand-written crypto.
//   70 96 AC | receiver | message ID | n | key ID | counter (u32 LE) | n encrypted
//   data bytes | tag (8 bytes) | CRC-16 (LE)
// Receiver, message ID, length, key ID and counter stay readable and are
// authenticated as associated data; the data is encrypted. The CRC-16 (same as
// crc16 mode) lets the parser find frames without keys and keeps noise apart from
// forgery: a frame with a bad CRC is noise, one with a good CRC and a bad tag is
// counted as an authentication failure. docs/protocol.md gives the layout byte by byte.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "fireswarm/common/secret_key.hpp"
#include "fireswarm/radio/frame.hpp"

namespace fireswarm::radio {

/// Key ID of the fleet broadcast key (frames to receiver 255); vehicle keys have
/// their vehicle's ID (1..254) as key ID, in both directions.
inline constexpr std::uint8_t kBroadcastKeyId = kBroadcastId;

/// What the receiver reads before it may decrypt.
struct SecureHeader {
  std::uint8_t key_id = 0;
  std::uint32_t counter = 0;
};

/// 96-bit GCM nonce: key ID, direction (1 = to the server, 0 = from it), two zero
/// bytes, the frame counter as u64 LE. Under one key only the server sends in
/// direction 0 and only its vehicle in direction 1, each from its own counter that
/// never repeats, so no nonce repeats under a key.
std::array<std::uint8_t, 12> SecureNonce(std::uint8_t receiver, const SecureHeader& header);

/// Appends one sealed frame. Throws std::invalid_argument when `plaintext` is longer
/// than 255 bytes, std::runtime_error when OpenSSL fails (it does not for valid input).
void AppendSecureFrame(std::vector<std::uint8_t>& out, std::uint8_t receiver,
                       std::uint8_t message_id, std::span<const std::uint8_t> plaintext,
                       const SecureHeader& header, const common::SecretKey& key);

/// Key ID and counter of a secure frame from the parser (no authentication yet).
SecureHeader ReadSecureHeader(const FrameView& frame);

/// Authenticates `frame` (a kSecure FrameView) under `key` and writes its decrypted
/// data to `plaintext`. False (plaintext cleared) when the tag does not verify.
/// Never throws for bad input.
bool OpenSecureFrame(const FrameView& frame, const common::SecretKey& key,
                     std::vector<std::uint8_t>& plaintext);

}  // namespace fireswarm::radio
