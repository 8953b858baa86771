// Little-endian byte writing and reading for frames and payloads (private to the
// radio module). Every multi-byte field of the protocol is little-endian,
// low byte first (docs/protocol.md).
#pragma once

#include <bit>
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace fireswarm::radio::detail {

/// Appends `value` to `out` in little-endian byte order.
template <std::unsigned_integral Uint>
void AppendLittleEndian(std::vector<std::uint8_t>& out, Uint value) {
  for (std::size_t i = 0; i < sizeof(Uint); ++i) {
    out.push_back(static_cast<std::uint8_t>(value >> (8 * i)));
  }
}

/// Appends a signed value as its two's-complement bytes, little-endian.
template <std::signed_integral Int>
void AppendLittleEndian(std::vector<std::uint8_t>& out, Int value) {
  AppendLittleEndian(out, static_cast<std::make_unsigned_t<Int>>(value));
}

/// Reads fields front to back from a byte span. Reading past the end never touches
/// memory outside the span: it yields 0 and sets overrun().
class LittleEndianReader {
 public:
  explicit LittleEndianReader(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}

  template <std::unsigned_integral Uint>
  Uint Read() {
    if (bytes_.size() - position_ < sizeof(Uint)) {
      position_ = bytes_.size();
      overrun_ = true;
      return 0;
    }
    Uint value = 0;
    for (std::size_t i = 0; i < sizeof(Uint); ++i) {
      value = static_cast<Uint>(value | static_cast<Uint>(Uint{bytes_[position_ + i]} << (8 * i)));
    }
    position_ += sizeof(Uint);
    return value;
  }

  template <std::signed_integral Int>
  Int Read() {
    // Two's complement is guaranteed since C++20, so the conversion is exact.
    return static_cast<Int>(Read<std::make_unsigned_t<Int>>());
  }

  std::size_t remaining() const { return bytes_.size() - position_; }
  bool overrun() const { return overrun_; }

 private:
  std::span<const std::uint8_t> bytes_;
  std::size_t position_ = 0;
  bool overrun_ = false;
};

}  // namespace fireswarm::radio::detail
