// Time on the radio link. Simulated links use exact integer nanoseconds since the
// scenario start; real links (serial, UDP) use the steady clock since the process
// start. Integer nanoseconds keep airtimes exact enough (1 ns) and deterministic.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>

namespace fireswarm::radio {

using Nanos = std::chrono::nanoseconds;

/// Bits a serial 8N1 byte occupies on the air: start bit, 8 data bits, stop bit.
inline constexpr int kBitsPerByte8N1 = 10;

/// Time `bytes` occupy on a serial link of `baud` bits/s, rounded up to whole ns.
/// 100 bytes at 57,600 baud 8N1 (5,760 bytes/s) take 17,361,112 ns.
constexpr Nanos Airtime(std::size_t bytes, int baud, int bits_per_byte = kBitsPerByte8N1) {
  const auto bits = static_cast<std::int64_t>(bytes) * bits_per_byte;
  return Nanos{(bits * 1'000'000'000 + baud - 1) / baud};
}

/// Converts seconds to nanoseconds, rounded to the nearest. Precondition: finite.
inline Nanos FromSeconds(double seconds) {
  return std::chrono::round<Nanos>(std::chrono::duration<double>(seconds));
}

/// Converts nanoseconds to seconds as a double, for figures and JSON.
constexpr double ToSeconds(Nanos t) {
  return static_cast<double>(t.count()) * 1e-9;
}

}  // namespace fireswarm::radio
