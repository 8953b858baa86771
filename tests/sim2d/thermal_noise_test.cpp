// NormalStream: the bulk fill the plain-ground fast path uses gives the very
// sequence the per-sample calls give, and the samples are unit normal.
#include "thermal_noise.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

namespace fireswarm::sim2d {
namespace {

TEST(NormalStream, BulkFillIsTheSameSequenceAsSingleSamples) {
  Rng a = MakeRng(7, "noise"), b = MakeRng(7, "noise");
  NormalStream bulk(a), single(b);
  // Odd chunk sizes start and end mid-word.
  for (const std::size_t chunk : {3U, 64U, 1U, 130U, 7U}) {
    std::vector<std::uint16_t> filled(chunk);
    bulk.FillUniform16(filled);
    for (const std::uint16_t sample : filled) EXPECT_EQ(sample, single.NextUniform16());
  }
}

TEST(NormalStream, IndexIsTheSamplesTopBits) {
  Rng a = MakeRng(8, "noise"), b = MakeRng(8, "noise");
  NormalStream by_index(a), by_sample(b);
  for (int i = 0; i < 1000; ++i) {
    EXPECT_EQ(by_index.NextIndex(),
              static_cast<std::size_t>(by_sample.NextUniform16() >> NormalStream::kIndexShift));
  }
}

TEST(NormalStream, SamplesAreUnitNormal) {
  Rng rng = MakeRng(9, "noise");
  NormalStream noise(rng);
  constexpr int kSamples = 1'000'000;
  double sum = 0.0, sum_sq = 0.0;
  for (int i = 0; i < kSamples; ++i) {
    const double z = noise.Next();
    sum += z;
    sum_sq += z * z;
  }
  const double mean = sum / kSamples;
  EXPECT_NEAR(mean, 0.0, 4.0 / std::sqrt(kSamples));
  EXPECT_NEAR(sum_sq / kSamples - mean * mean, 1.0, 0.01);
}

}  // namespace
}  // namespace fireswarm::sim2d
