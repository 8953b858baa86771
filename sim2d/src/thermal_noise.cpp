#include "thermal_noise.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cassert>
#include <cmath>
#include <cstring>
#include <numbers>

namespace fireswarm::sim2d {
namespace {

constexpr std::size_t kTableSize = NormalStream::kTableSize;

// Standard normal quantile by bisection on the CDF (table set-up only).
double NormalQuantile(double p) {
  double lo = -10.0, hi = 10.0;
  for (int i = 0; i < 100; ++i) {
    const double mid = 0.5 * (lo + hi);
    const double cdf = 0.5 * std::erfc(-mid / std::numbers::sqrt2);
    (cdf < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

std::array<float, kTableSize> MakeTable() {
  std::array<double, kTableSize> z{};
  double sum_sq = 0.0;
  for (std::size_t i = 0; i < kTableSize; ++i) {
    z[i] = NormalQuantile((static_cast<double>(i) + 0.5) / static_cast<double>(kTableSize));
    sum_sq += z[i] * z[i];
  }
  // Rescale so the table's variance is exactly 1 (cutting the tails lowers it).
  const double scale = 1.0 / std::sqrt(sum_sq / static_cast<double>(kTableSize));
  std::array<float, kTableSize> table{};
  for (std::size_t i = 0; i < kTableSize; ++i) table[i] = static_cast<float>(z[i] * scale);
  return table;
}

constexpr std::size_t kLanes = 64;  // pixels per block: one bit of each index plane

// Entry m: eight bytes, in memory order, holding bits 0..7 of m as 0 or 1, so
// adding it to eight pixels adds one bit of a 64-lane mask to each.
constexpr std::array<std::uint64_t, 256> MakeSpread() {
  std::array<std::uint64_t, 256> spread{};
  for (std::size_t m = 0; m < spread.size(); ++m) {
    for (int bit = 0; bit < 8; ++bit) {
      if (((m >> bit) & 1U) == 0) continue;
      const int byte = std::endian::native == std::endian::little ? bit : 7 - bit;
      spread[m] |= std::uint64_t{1} << (8 * byte);
    }
  }
  return spread;
}
constexpr std::array<std::uint64_t, 256> kSpread = MakeSpread();

// The lanes whose index is at least `step`, from the index's bit planes: a
// comparison of two binary numbers, bit by bit from the lowest, 64 lanes at once.
// Where step has a 1 the lane needs a 1 there (and, equal so far, the bits below
// decide); where step has a 0 a lane's 1 decides for it. Below step's lowest 1
// every lane is at or above it so far.
std::uint64_t LanesAtOrAbove(std::span<const std::uint64_t, NormalStream::kIndexBits> planes,
                             std::uint16_t step) {
  const unsigned threshold = step;
  std::uint64_t at_or_above = ~std::uint64_t{0};
  for (int bit = std::countr_zero(threshold); bit < NormalStream::kIndexBits; ++bit) {
    const std::uint64_t plane = planes[static_cast<std::size_t>(bit)];
    at_or_above = ((threshold >> bit) & 1U) != 0 ? (plane & at_or_above) : (plane | at_or_above);
  }
  return at_or_above;
}

}  // namespace

int LowestIndexBitRead(std::span<const std::uint16_t> index_steps) {
  int lowest = NormalStream::kIndexBits;
  for (const std::uint16_t step : index_steps) lowest = std::min(lowest, std::countr_zero(step));
  return lowest;
}

void FillPlainGround(std::uint8_t base, std::span<const std::uint16_t> index_steps,
                     NormalStream& noise, std::span<std::uint8_t> pixels) {
  assert(index_steps.size() <= kMaxPlainGroundSteps);
  assert(base + index_steps.size() <= 255);
  assert(std::ranges::is_sorted(index_steps));
  assert(index_steps.empty() || index_steps.front() > 0);
  constexpr std::size_t kWords = kLanes / 8;  // eight pixels a word
  constexpr std::uint64_t kEveryByte = 0x0101010101010101ULL;
  const std::uint64_t base_bytes = base * kEveryByte;
  std::array<std::uint64_t, NormalStream::kIndexBits> planes{};
  std::array<std::uint64_t, kWords> greys{};
  // The seed camera over 25 C ground has one step, at 2048: one plane a block
  // instead of twelve.
  const int from_bit = LowestIndexBitRead(index_steps);
  for (std::size_t start = 0; start < pixels.size(); start += kLanes) {
    noise.NextIndexPlanes(planes, from_bit);
    greys.fill(base_bytes);
    for (const std::uint16_t step : index_steps) {
      const std::uint64_t reached = LanesAtOrAbove(planes, step);
#pragma GCC unroll 8
      for (std::size_t word = 0; word < kWords; ++word) {
        greys[word] += kSpread[(reached >> (8 * word)) & 0xFFU];
      }
    }
    // A whole block in one copy of constant size (no call), a last part block apart.
    if (pixels.size() - start >= kLanes) {
      std::memcpy(pixels.data() + start, greys.data(), kLanes);
    } else {
      std::memcpy(pixels.data() + start, greys.data(), pixels.size() - start);
    }
  }
}

const float* NormalQuantileTable() {
  static const std::array<float, kTableSize> table = MakeTable();
  return table.data();
}

}  // namespace fireswarm::sim2d
