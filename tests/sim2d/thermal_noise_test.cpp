// NormalStream: its bit-sliced indices are uniform, the plain-ground fill gives
// each pixel the grey level its index selects, and the samples are unit normal.
#include "thermal_noise.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

namespace fireswarm::sim2d {
namespace {

// The table index of lane `lane` in a block of bit planes.
std::uint16_t IndexOfLane(const std::array<std::uint64_t, NormalStream::kIndexBits>& planes,
                          int lane) {
  unsigned index = 0;
  for (int bit = 0; bit < NormalStream::kIndexBits; ++bit) {
    index |= static_cast<unsigned>((planes[static_cast<std::size_t>(bit)] >> lane) & 1U) << bit;
  }
  return static_cast<std::uint16_t>(index);
}

TEST(NormalStream, IndexPlanesGiveUniformIndices) {
  Rng rng = MakeRng(6, "noise");
  NormalStream noise(rng);
  // The top and the bottom four bits of 128,000 indices, in 16 bins each.
  constexpr int kBlocks = 2000;
  constexpr double kExpected = kBlocks * 64 / 16.0;
  std::array<double, 16> top{}, bottom{};
  std::array<std::uint64_t, NormalStream::kIndexBits> planes{};
  for (int block = 0; block < kBlocks; ++block) {
    noise.NextIndexPlanes(planes);
    for (int lane = 0; lane < 64; ++lane) {
      const std::size_t index = IndexOfLane(planes, lane);
      ASSERT_LT(index, NormalStream::kTableSize);
      top[index >> (NormalStream::kIndexBits - 4)] += 1.0;
      bottom[index & 0xFU] += 1.0;
    }
  }
  // Chi-squared with 15 degrees of freedom: above 50 one time in 10^5.
  for (const auto* bins : {&top, &bottom}) {
    double chi2 = 0.0;
    for (const double n : *bins) chi2 += (n - kExpected) * (n - kExpected) / kExpected;
    EXPECT_LT(chi2, 50.0);
  }
}

TEST(FillPlainGround, DrawsIndexBitsFromTheStepsLowestOneUp) {
  EXPECT_EQ(LowestIndexBitRead({}), NormalStream::kIndexBits);
  EXPECT_EQ(LowestIndexBitRead(std::vector<std::uint16_t>{2048}), 11);
  EXPECT_EQ(LowestIndexBitRead(std::vector<std::uint16_t>{1024, 3072}), 10);
  EXPECT_EQ(LowestIndexBitRead(std::vector<std::uint16_t>{1, 4095}), 0);
  EXPECT_EQ(LowestIndexBitRead(std::vector<std::uint16_t>{3000, 3500}), 2);
}

TEST(FillPlainGround, EveryPixelReadsBasePlusTheStepsItsIndexReaches) {
  const std::vector<std::vector<std::uint16_t>> step_sets = {
      {}, {2048}, {1, 4095}, {1024, 3072}, {100, 900, 2000, 2001, 3000, 3500, 3700, 4000}};
  for (const std::vector<std::uint16_t>& steps : step_sets) {
    // A whole number of blocks (every camera model's frame), and a part block.
    for (const std::size_t size : {std::size_t{6144}, std::size_t{100}}) {
      SCOPED_TRACE(::testing::Message() << steps.size() << " steps, " << size << " px");
      Rng a = MakeRng(5, "noise"), b = MakeRng(5, "noise");
      NormalStream filled_noise(a), reference_noise(b);
      std::vector<std::uint8_t> pixels(size);
      constexpr std::uint8_t kBase = 40;
      FillPlainGround(kBase, steps, filled_noise, pixels);
      // The reference draws the planes the fill needs: from the steps' lowest 1 up.
      const int from_bit = LowestIndexBitRead(steps);
      std::array<std::uint64_t, NormalStream::kIndexBits> planes{};
      for (std::size_t i = 0; i < size; ++i) {
        if (i % 64 == 0) reference_noise.NextIndexPlanes(planes, from_bit);
        const std::uint16_t index = IndexOfLane(planes, static_cast<int>(i % 64));
        const auto reached = std::ranges::count_if(steps, [&](auto s) { return s <= index; });
        ASSERT_EQ(pixels[i], kBase + reached) << "pixel " << i << ", index " << index;
      }
    }
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
