// Fast Gaussian sensor noise for the thermal cameras (private to sim2d). A
// thousand cameras at 9 Hz need tens of millions of normal samples per
// simulated second, so std::normal_distribution (tens of ns each) is too slow.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include "fireswarm/sim2d/random.hpp"

namespace fireswarm::sim2d {

/// 4,096 standard normal quantiles at (i + 0.5) / 4096, rescaled to unit
/// variance (tails cut at about 3.5 sigma). Built once, on first use.
const float* NormalQuantileTable();

/// A stream of N(0, 1) samples for one frame. One 64-bit draw from `rng` seeds
/// a wyrand generator; every 64-bit word of it gives four 16-bit uniform
/// samples (low bits first), and a sample's top 12 bits index
/// NormalQuantileTable(). Deterministic given the rng's state.
class NormalStream {
 public:
  explicit NormalStream(Rng& rng) : table_(NormalQuantileTable()), state_(rng()) {}

  /// Number of entries in NormalQuantileTable(), the range of NextIndex().
  static constexpr std::size_t kTableSize = std::size_t{1} << 12;
  /// NextIndex() is NextUniform16() shifted right by this many bits, so a
  /// uniform sample u selects table entry k exactly when
  /// (k << kIndexShift) <= u < ((k + 1) << kIndexShift).
  static constexpr int kIndexShift = 4;

  float Next() { return table_[NextIndex()]; }

  /// The table index of the next sample (for callers that map samples through
  /// their own per-index lookup table).
  std::size_t NextIndex() { return static_cast<std::size_t>(NextUniform16() >> kIndexShift); }

  /// The next sample as a uniform 16-bit number (for callers that compare it
  /// with thresholds on the table index instead of looking it up).
  std::uint16_t NextUniform16() {
    if (left_ == 0) {
      word_ = NextWord();
      left_ = kSamplesPerWord;
    }
    const auto sample = static_cast<std::uint16_t>(word_);
    word_ >>= kSampleBits;
    --left_;
    return sample;
  }

  /// The next out.size() samples of NextUniform16(), the same sequence, whole
  /// words at a time (no per-sample branch).
  void FillUniform16(std::span<std::uint16_t> out) {
    std::size_t i = 0;
    for (; i < out.size() && left_ > 0; ++i) out[i] = NextUniform16();
    for (; i + kSamplesPerWord <= out.size(); i += kSamplesPerWord) {
      // Spelled out (the compiler merges them into one store on little-endian machines).
      const std::uint64_t word = NextWord();
      out[i] = static_cast<std::uint16_t>(word);
      out[i + 1] = static_cast<std::uint16_t>(word >> kSampleBits);
      out[i + 2] = static_cast<std::uint16_t>(word >> (2 * kSampleBits));
      out[i + 3] = static_cast<std::uint16_t>(word >> (3 * kSampleBits));
    }
    for (; i < out.size(); ++i) out[i] = NextUniform16();
  }

 private:
  static constexpr int kSampleBits = 16;
  static constexpr std::size_t kSamplesPerWord = 64 / kSampleBits;
  static_assert(kSamplesPerWord == 4, "FillUniform16 spells out four samples per word");
  static_assert((std::size_t{1} << (kSampleBits - kIndexShift)) == kTableSize);

  // wyrand (Wang Yi, public domain; passes BigCrush and PractRand): a Weyl
  // sequence mixed by one 64x64->128-bit multiply, a third cheaper per word
  // than splitmix64's two multiplies, which matters at 1,500 words per frame.
  std::uint64_t NextWord() {
    state_ += 0xA0761D6478BD642FULL;
    const __uint128_t product = static_cast<__uint128_t>(state_) * (state_ ^ 0xE7037ED1A0B428DBULL);
    return static_cast<std::uint64_t>(product >> 64) ^ static_cast<std::uint64_t>(product);
  }

  const float* table_;
  std::uint64_t state_;
  std::uint64_t word_ = 0;
  std::size_t left_ = 0;
};

}  // namespace fireswarm::sim2d
