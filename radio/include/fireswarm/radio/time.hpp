// Time on the radio link: airtimes of serial bytes. The time type itself is the
// tree's one (common/time.hpp); the radio module names it unqualified.
#pragma once

#include <cstddef>
#include <cstdint>

#include "fireswarm/common/time.hpp"

namespace fireswarm::radio {

using common::FromSeconds;
using common::Nanos;
using common::ToSeconds;

/// Bits a serial 8N1 byte occupies on the air: start bit, 8 data bits, stop bit.
inline constexpr int kBitsPerByte8N1 = 10;

/// Time `bytes` occupy on a serial link of `baud` bits/s, rounded up to whole ns.
/// 100 bytes at 57,600 baud 8N1 (5,760 bytes/s) take 17,361,112 ns.
constexpr Nanos Airtime(std::size_t bytes, int baud, int bits_per_byte = kBitsPerByte8N1) {
  const auto bits = static_cast<std::int64_t>(bytes) * bits_per_byte;
  return Nanos{(bits * 1'000'000'000 + baud - 1) / baud};
}

}  // namespace fireswarm::radio
