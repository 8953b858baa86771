// Checksums of byte ranges from running checksum states (private to the radio
// module). The parser checks a candidate frame at every preamble, and candidates
// may overlap heavily (a preamble every 4 bytes, each promising 263 bytes), so
// checksumming each candidate in full costs up to ~90 times the stream. Instead the
// parser keeps the running state after every buffered byte, computes each once, and
// gets any candidate's checksum from the states at its two ends in constant time.
//
// XOR: the XOR of a range is the XOR of the running states at its ends.
// CRC-16/CCITT-FALSE is affine in its register: n bytes d taken from register r
// leave r * x^(8n) + L(d) mod P (L linear, P the polynomial 0x1021 with x^16). So
// from one running CRC's states s_first and s_last n bytes apart, the CRC of the
// range alone (started from the initial value I) is s_last + (s_first + I) * x^(8n)
// mod P, where + is XOR.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "fireswarm/radio/frame.hpp"

namespace fireswarm::radio::detail {

/// CRC-16/CCITT-FALSE (frame.hpp): width 16, polynomial 0x1021, initial value 0xFFFF,
/// no reflection, no final XOR.
inline constexpr std::uint16_t kCrc16Polynomial = 0x1021;  // x^12 + x^5 + 1, x^16 implied
inline constexpr std::uint16_t kCrc16Initial = 0xFFFF;

/// kCrc16Table[k] = k * x^16 mod P: the byte-at-a-time CRC table, which also folds a
/// byte above bit 15 back into 16 bits.
extern const std::array<std::uint16_t, 256> kCrc16Table;
/// kCrc16Ahead[j][k]: the register that byte k, fed to a zero register, leaves after j + 1
/// more zero bytes (kCrc16Ahead[j][k] = k * x^(16 + 8 (j + 1)) mod P). With them the register
/// after four bytes comes from the register before them in one step (slicing by four),
/// not four dependent table lookups.
extern const std::array<std::array<std::uint16_t, 256>, 3> kCrc16Ahead;
/// kZeroBytesTimes[n][k] = (x^(8n) mod P) * k, carry-less and not reduced (19 bits),
/// for 4-bit k: what n bytes of shifting do to a register, a nibble at a time.
extern const std::array<std::array<std::uint32_t, 16>, kMaxFrameSize + 1> kZeroBytesTimes;

/// The CRC-16 register after one more byte: Crc16() and the parser's states use it.
inline std::uint16_t Crc16Step(std::uint16_t crc, std::uint8_t byte) {
  return static_cast<std::uint16_t>((crc << 8) ^ kCrc16Table[(crc >> 8) ^ byte]);
}

/// The state a running checksum starts from: 0 (XOR) or 0xFFFF (CRC-16, also secure mode).
inline std::uint16_t InitialChecksumState(ChecksumMode mode) {
  return mode == ChecksumMode::kXor ? 0 : kCrc16Initial;
}

/// Sets states[i + 1] to the running checksum after bytes[i], for i in [from, to).
/// Precondition: states[from] holds the state before bytes[from].
inline void ExtendChecksumStates(ChecksumMode mode, const std::uint8_t* bytes,
                                 std::uint16_t* states, std::size_t from, std::size_t to) {
  if (mode == ChecksumMode::kXor) {
    for (std::size_t i = from; i < to; ++i) states[i + 1] = states[i] ^ bytes[i];
    return;
  }
  // Every state is stored, but only each fourth one is on the dependency chain from
  // one group of four bytes to the next; the three between are worked out beside it.
  // The same states as byte by byte (tests/radio/range_checksum_test.cpp), about three
  // times faster: a vehicle's receiver runs every byte on the shared channel through it.
  std::size_t i = from;
  for (; i + 4 <= to; i += 4) {
    const std::uint16_t crc = states[i];
    states[i + 4] = static_cast<std::uint16_t>(
        kCrc16Ahead[2][(crc >> 8) ^ bytes[i]] ^ kCrc16Ahead[1][(crc & 0xFFU) ^ bytes[i + 1]] ^
        kCrc16Ahead[0][bytes[i + 2]] ^ kCrc16Table[bytes[i + 3]]);
    states[i + 1] = Crc16Step(crc, bytes[i]);
    states[i + 2] = Crc16Step(states[i + 1], bytes[i + 1]);
    states[i + 3] = Crc16Step(states[i + 2], bytes[i + 2]);
  }
  for (; i < to; ++i) states[i + 1] = Crc16Step(states[i], bytes[i]);
}

/// The checksum (Xor8() or Crc16() value) of the `size` bytes between two states of
/// one running checksum, `at_first` before the range and `at_last` after it.
/// Precondition: size <= kMaxFrameSize.
inline std::uint16_t ChecksumBetween(ChecksumMode mode, std::uint16_t at_first,
                                     std::uint16_t at_last, std::size_t size) {
  if (mode == ChecksumMode::kXor) return at_first ^ at_last;
  // (at_first + I) * x^(8 size) mod P: a carry-less product a nibble at a time, then
  // its bits 16..30 folded back a byte at a time (bits 24..30 land in bits 8..23).
  const auto a = static_cast<std::uint16_t>(at_first ^ kCrc16Initial);
  const std::array<std::uint32_t, 16>& times = kZeroBytesTimes[size];
  std::uint32_t product = times[a & 0xFU] ^ (times[(a >> 4) & 0xFU] << 4) ^
                          (times[(a >> 8) & 0xFU] << 8) ^ (times[a >> 12] << 12);
  product ^= std::uint32_t{kCrc16Table[product >> 24]} << 8;
  product &= 0xFFFFFFU;
  return static_cast<std::uint16_t>(at_last ^ product ^ kCrc16Table[product >> 16]);
}

}  // namespace fireswarm::radio::detail
