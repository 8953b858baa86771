// A 64-bit FNV-1a hash over the bit patterns of the simulation state, for the
// golden-hash determinism test (STYLE 5).
#pragma once

#include <bit>
#include <cstdint>
#include <optional>

#include "fireswarm/sim2d/vehicle_state.hpp"

namespace fireswarm::sim2d {

class StateHasher {
 public:
  void Add(std::uint64_t word) {
    for (int byte = 0; byte < 8; ++byte) {
      hash_ = (hash_ ^ ((word >> (8 * byte)) & 0xFFU)) * kPrime;
    }
  }
  void Add(double value) { Add(std::bit_cast<std::uint64_t>(value)); }
  void Add(int value) { Add(static_cast<std::uint64_t>(static_cast<std::int64_t>(value))); }
  void Add(bool value) { Add(static_cast<std::uint64_t>(value ? 1 : 0)); }
  void Add(const Vec2& value) {
    Add(value.x());
    Add(value.y());
  }
  /// Adds a presence marker, then the value when there is one.
  template <typename T, typename AddValue>
  void AddOptional(const std::optional<T>& value, AddValue add_value) {
    Add(value.has_value());
    if (value) add_value(*this, *value);
  }

  std::uint64_t value() const { return hash_; }

 private:
  static constexpr std::uint64_t kPrime = 1099511628211ULL;
  std::uint64_t hash_ = 1469598103934665603ULL;
};

}  // namespace fireswarm::sim2d
