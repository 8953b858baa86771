// The APOne radio frame, seed Table 5.3:
//   70 96 AC | receiver ID | message ID | length n | n data bytes | checksum
// The checksum covers receiver ID, message ID, length and data (not the preamble).
// XOR mode: one byte, the XOR of those bytes (seed-compatible, seed 5.3.4.5).
// CRC-16 mode: two bytes, little-endian, CRC-16/CCITT-FALSE (polynomial 0x1021,
// initial value 0xFFFF, no reflection, no final XOR; check value 0x29B1 for "123456789").
// Secure mode: the length byte counts the encrypted data; between length and data
// sit a key ID and a 32-bit frame counter, after the data a 64-bit AES-256-GCM tag,
// then the CRC-16 over everything from receiver ID to tag (secure_frame.hpp,
// docs/protocol.md "Secure mode").
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace fireswarm::radio {

inline constexpr std::array<std::uint8_t, 3> kPreamble{0x70, 0x96, 0xAC};
/// The server (the seed's GCS) always has receiver ID 0 (seed 5.3.4.2).
inline constexpr std::uint8_t kServerId = 0;
/// Frames addressed to 255 are for every vehicle.
inline constexpr std::uint8_t kBroadcastId = 255;
/// Lowest and highest receiver ID a vehicle may have.
inline constexpr std::uint8_t kFirstVehicleId = 1;
inline constexpr std::uint8_t kLastVehicleId = 254;
/// Preamble, receiver ID, message ID, length.
inline constexpr std::size_t kHeaderSize = 6;
inline constexpr std::size_t kMaxDataSize = 255;

/// How a frame is protected: kXor and kCrc16 detect noise only; kSecure also
/// authenticates every frame and encrypts its data (AES-256-GCM).
enum class ChecksumMode : std::uint8_t { kXor, kCrc16, kSecure };

/// Secure mode: key ID (1 byte) and frame counter (4 bytes) after the length byte.
inline constexpr std::size_t kSecureHeaderSize = 5;
/// Secure mode: bytes of the GCM tag after the data (64 bits; docs/protocol.md says why).
inline constexpr std::size_t kSecureTagSize = 8;

/// Bytes of checksum after the data: 1 (XOR) or 2 (CRC-16; also closes a secure frame).
constexpr std::size_t ChecksumSize(ChecksumMode mode) {
  return mode == ChecksumMode::kXor ? 1 : 2;
}

/// Bytes a mode adds to a frame besides header, data and checksum: 13 in secure mode.
constexpr std::size_t SecurityOverhead(ChecksumMode mode) {
  return mode == ChecksumMode::kSecure ? kSecureHeaderSize + kSecureTagSize : 0;
}

/// Bytes a frame with `data_size` data bytes occupies on the air.
constexpr std::size_t FrameSize(std::size_t data_size, ChecksumMode mode) {
  return kHeaderSize + data_size + SecurityOverhead(mode) + ChecksumSize(mode);
}

/// Largest frame on the air: 6 + 255 + 13 + 2 = 276 bytes (secure mode).
inline constexpr std::size_t kMaxFrameSize = FrameSize(kMaxDataSize, ChecksumMode::kSecure);

/// "xor", "crc16" or "secure".
std::string_view ToString(ChecksumMode mode);
/// Parses "xor", "crc16" or "secure"; nullopt for anything else.
std::optional<ChecksumMode> ParseChecksumMode(std::string_view text);

/// XOR of every byte (seed 5.3.4.5).
std::uint8_t Xor8(std::span<const std::uint8_t> bytes);
/// CRC-16/CCITT-FALSE of `bytes`.
std::uint16_t Crc16(std::span<const std::uint8_t> bytes);

/// A frame found in a byte stream. `data` points into the parser's buffer and is
/// valid only until the parser is fed again.
struct FrameView {
  std::uint8_t receiver = 0;
  std::uint8_t message_id = 0;
  std::span<const std::uint8_t> data;
  /// Secure mode only: the frame from receiver ID through the tag (what
  /// OpenSecureFrame() authenticates); `data` is then the still encrypted data.
  std::span<const std::uint8_t> sealed;
  /// Stream position of the frame's first preamble byte, in bytes fed since the
  /// parser's construction or Reset().
  std::uint64_t offset = 0;
};

/// Appends one encoded xor or crc16 frame to `out` (secure frames: AppendSecureFrame).
/// Throws std::invalid_argument when `data` is longer than 255 bytes or `mode` is kSecure.
void AppendFrame(std::vector<std::uint8_t>& out, std::uint8_t receiver, std::uint8_t message_id,
                 std::span<const std::uint8_t> data, ChecksumMode mode);

}  // namespace fireswarm::radio
