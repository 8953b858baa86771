// Range checksums from running states; the algebra is in range_checksum.hpp.
#include "range_checksum.hpp"

#include <array>
#include <cassert>

namespace fireswarm::radio::detail {
namespace {

constexpr std::uint16_t kCrc16Polynomial = 0x1021;  // x^12 + x^5 + 1, the x^16 implied
constexpr std::uint16_t kCrc16Initial = 0xFFFF;

// value * x mod P.
constexpr std::uint16_t TimesX(std::uint16_t value) {
  return static_cast<std::uint16_t>((value & 0x8000) != 0 ? (value << 1) ^ kCrc16Polynomial
                                                          : value << 1);
}

// kTimesX16[k] = k * x^16 mod P: folds a byte above bit 15 back into 16 bits.
constexpr std::array<std::uint16_t, 256> kTimesX16 = [] {
  std::array<std::uint16_t, 256> table{};
  for (std::size_t k = 0; k < table.size(); ++k) {
    auto value = static_cast<std::uint16_t>(k << 8);
    for (int bit = 0; bit < 8; ++bit) value = TimesX(value);
    table[k] = value;
  }
  return table;
}();

// kZeroBytes[n] = x^(8n) mod P: what n bytes of shifting do to a register.
constexpr std::array<std::uint16_t, kMaxFrameSize + 1> kZeroBytes = [] {
  std::array<std::uint16_t, kMaxFrameSize + 1> table{};
  std::uint16_t value = 1;
  for (std::uint16_t& entry : table) {
    entry = value;
    for (int bit = 0; bit < 8; ++bit) value = TimesX(value);
  }
  return table;
}();

// a * b mod P: a carry-less 16 x 16 bit product, then its bits 16..30 folded back a
// byte at a time (bits 24..30 first, whose fold lands in bits 8..23).
std::uint16_t MultiplyModP(std::uint16_t a, std::uint16_t b) {
  std::uint32_t product = 0;
  for (unsigned bit = 0; bit < 16; ++bit) {
    product ^= (0U - ((a >> bit) & 1U)) & (std::uint32_t{b} << bit);
  }
  product ^= std::uint32_t{kTimesX16[product >> 24]} << 8;
  product &= 0xFFFFFFU;
  return static_cast<std::uint16_t>(product ^ kTimesX16[product >> 16]);
}

static_assert(kZeroBytes[0] == 1 && kZeroBytes[2] == kTimesX16[1]);

}  // namespace

std::uint16_t InitialChecksumState(ChecksumMode mode) {
  return mode == ChecksumMode::kXor ? 0 : kCrc16Initial;
}

void ExtendChecksumStates(ChecksumMode mode, const std::uint8_t* bytes, std::uint16_t* states,
                          std::size_t from, std::size_t to) {
  if (mode == ChecksumMode::kXor) {
    for (std::size_t i = from; i < to; ++i) states[i + 1] = states[i] ^ bytes[i];
    return;
  }
  Crc16Register crc(states[from]);
  for (std::size_t i = from; i < to; ++i) {
    crc.process_byte(bytes[i]);
    states[i + 1] = crc.checksum();
  }
}

std::uint16_t ChecksumBetween(ChecksumMode mode, std::uint16_t at_first, std::uint16_t at_last,
                              std::size_t size) {
  if (mode == ChecksumMode::kXor) return at_first ^ at_last;
  assert(size < kZeroBytes.size());
  return at_last ^ MultiplyModP(at_first ^ kCrc16Initial, kZeroBytes[size]);
}

}  // namespace fireswarm::radio::detail
