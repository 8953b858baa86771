// Fast Gaussian sensor noise for the thermal cameras (private to sim2d). A
// thousand cameras at 9 Hz need tens of millions of normal samples per
// simulated second, so std::normal_distribution (tens of ns each) is too slow.
#pragma once

#include <cstddef>
#include <cstdint>

#include "fireswarm/sim2d/random.hpp"

namespace fireswarm::sim2d {

/// 4,096 standard normal quantiles at (i + 0.5) / 4096, rescaled to unit
/// variance (tails cut at about 3.5 sigma). Built once, on first use.
const float* NormalQuantileTable();

/// A stream of N(0, 1) samples for one frame. One 64-bit draw from `rng` seeds
/// a splitmix64 generator; every 64-bit word of it gives five 12-bit indices
/// into NormalQuantileTable(). Deterministic given the rng's state.
class NormalStream {
 public:
  explicit NormalStream(Rng& rng) : table_(NormalQuantileTable()), state_(rng()) {}

  /// Number of entries in NormalQuantileTable(), the range of NextIndex().
  static constexpr std::size_t kTableSize = std::size_t{1} << 12;

  float Next() { return table_[NextIndex()]; }

  /// The table index of the next sample (for callers that map samples through
  /// their own per-index lookup table).
  std::size_t NextIndex() {
    if (left_ == 0) {
      word_ = SplitMix64();
      left_ = kIndicesPerWord;
    }
    const auto index = static_cast<std::size_t>(word_ & kIndexMask);
    word_ >>= kTableBits;
    --left_;
    return index;
  }

 private:
  static constexpr int kTableBits = 12;
  static constexpr std::uint64_t kIndexMask = (std::uint64_t{1} << kTableBits) - 1;
  static constexpr int kIndicesPerWord = 64 / kTableBits;

  std::uint64_t SplitMix64() {
    std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ULL);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
    return z ^ (z >> 31);
  }

  const float* table_;
  std::uint64_t state_;
  std::uint64_t word_ = 0;
  int left_ = 0;
};

}  // namespace fireswarm::sim2d
