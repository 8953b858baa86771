// The CRC-16 tables behind range_checksum.hpp, computed at compile time.
#include "range_checksum.hpp"

namespace fireswarm::radio::detail {
namespace {

// value * x mod P.
constexpr std::uint16_t TimesX(std::uint16_t value) {
  return static_cast<std::uint16_t>((value & 0x8000) != 0 ? (value << 1) ^ kCrc16Polynomial
                                                          : value << 1);
}

constexpr std::array<std::uint16_t, 256> MakeCrc16Table() {
  std::array<std::uint16_t, 256> table{};
  for (std::size_t k = 0; k < table.size(); ++k) {
    auto value = static_cast<std::uint16_t>(k << 8);
    for (int bit = 0; bit < 8; ++bit) value = TimesX(value);
    table[k] = value;
  }
  return table;
}

constexpr std::uint16_t Crc16StepConstexpr(const std::array<std::uint16_t, 256>& table,
                                           std::uint16_t crc, std::uint8_t byte) {
  return static_cast<std::uint16_t>((crc << 8) ^ table[(crc >> 8) ^ byte]);
}

constexpr std::array<std::array<std::uint16_t, 256>, 3> MakeCrc16Ahead(
    const std::array<std::uint16_t, 256>& table) {
  std::array<std::array<std::uint16_t, 256>, 3> ahead{};
  for (std::size_t k = 0; k < 256; ++k) {
    std::uint16_t crc = table[k];
    for (std::array<std::uint16_t, 256>& row : ahead) {
      crc = Crc16StepConstexpr(table, crc, 0);
      row[k] = crc;
    }
  }
  return ahead;
}

constexpr std::array<std::array<std::uint32_t, 16>, kMaxFrameSize + 1> MakeZeroBytesTimes() {
  std::array<std::array<std::uint32_t, 16>, kMaxFrameSize + 1> table{};
  std::uint16_t shift = 1;  // x^(8n) mod P
  for (std::array<std::uint32_t, 16>& row : table) {
    for (std::uint32_t k = 0; k < row.size(); ++k) {
      std::uint32_t product = 0;
      for (unsigned bit = 0; bit < 4; ++bit) {
        if (((k >> bit) & 1U) != 0) product ^= std::uint32_t{shift} << bit;
      }
      row[k] = product;
    }
    for (int bit = 0; bit < 8; ++bit) shift = TimesX(shift);
  }
  return table;
}

}  // namespace

constexpr std::array<std::uint16_t, 256> kCrc16Table = MakeCrc16Table();
constexpr std::array<std::array<std::uint16_t, 256>, 3> kCrc16Ahead = MakeCrc16Ahead(kCrc16Table);
constexpr std::array<std::array<std::uint32_t, 16>, kMaxFrameSize + 1> kZeroBytesTimes =
    MakeZeroBytesTimes();

}  // namespace fireswarm::radio::detail
