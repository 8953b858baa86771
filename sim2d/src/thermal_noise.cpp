#include "thermal_noise.hpp"

#include <array>
#include <cmath>
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

}  // namespace

const float* NormalQuantileTable() {
  static const std::array<float, kTableSize> table = MakeTable();
  return table.data();
}

}  // namespace fireswarm::sim2d
