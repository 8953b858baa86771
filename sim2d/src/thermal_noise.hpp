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

  /// Bits of a uniform table index per sample: NextIndex() < 2^kIndexBits.
  static constexpr int kIndexBits = 12;
  /// 64 samples' table indices, bit-sliced: bit i of planes[j] is bit j of
  /// sample i's index (each bit uniform and independent, so every index is
  /// uniform over the table, as NextIndex()'s). Only planes from `from_bit` up
  /// are drawn; the ones below are left as they are, for callers that compare
  /// the indices only with thresholds that have no 1 below from_bit (their
  /// comparison never reads those bits). Whole fresh words: a word that
  /// NextUniform16() has begun is not reused.
  void NextIndexPlanes(std::span<std::uint64_t, kIndexBits> planes, int from_bit = 0) {
    // The state in a local: stores to `planes` cannot then alias it.
    std::uint64_t state = state_;
    for (auto bit = static_cast<std::size_t>(from_bit); bit < planes.size(); ++bit) {
      planes[bit] = WyRand(state);
    }
    state_ = state;
  }

 private:
  static constexpr int kSampleBits = 16;
  static constexpr std::size_t kSamplesPerWord = 64 / kSampleBits;
  static_assert((std::size_t{1} << (kSampleBits - kIndexShift)) == kTableSize);
  static_assert((std::size_t{1} << kIndexBits) == kTableSize);

  // wyrand (Wang Yi, public domain; passes BigCrush and PractRand): a Weyl
  // sequence mixed by one 64x64->128-bit multiply, a third cheaper per word
  // than splitmix64's two multiplies, which matters at 1,500 words per frame.
  static std::uint64_t WyRand(std::uint64_t& state) {
    state += 0xA0761D6478BD642FULL;
    const __uint128_t product = static_cast<__uint128_t>(state) * (state ^ 0xE7037ED1A0B428DBULL);
    return static_cast<std::uint64_t>(product >> 64) ^ static_cast<std::uint64_t>(product);
  }
  std::uint64_t NextWord() { return WyRand(state_); }

  const float* table_;
  std::uint64_t state_;
  std::uint64_t word_ = 0;
  std::size_t left_ = 0;
};

/// The most grey levels above `base` that FillPlainGround() handles (more
/// levels of noise than this: look each pixel's index up instead).
inline constexpr std::size_t kMaxPlainGroundSteps = 8;

/// The lowest index bit that a comparison with any of `index_steps` reads:
/// below every step's lowest 1 no comparison depends on a bit, so those bits
/// need not be drawn (kIndexBits when there are no steps).
int LowestIndexBitRead(std::span<const std::uint16_t> index_steps);

/// Fills `pixels` with plain ground's grey levels under fixed gain: a pixel whose
/// noise sample has table index k reads `base` plus the number of `index_steps`
/// at or below k. Equal, sample for sample, to looking each index up in a table
/// whose entry k is that sum; 64 pixels at a time from NextIndexPlanes() (from
/// LowestIndexBitRead() up), with no per-pixel draw or compare. The seed camera
/// over 25 C ground: 1.8 instructions a pixel, against 6.4 for a 16-bit sample
/// and vector compares per pixel (callgrind, `fireswarm sim-bench`). Requires
/// index_steps ascending, each in [1, kTableSize), at most kMaxPlainGroundSteps
/// of them, and base + index_steps.size() <= 255.
void FillPlainGround(std::uint8_t base, std::span<const std::uint16_t> index_steps,
                     NormalStream& noise, std::span<std::uint8_t> pixels);

}  // namespace fireswarm::sim2d
