// AgeHistogram: percentiles in fixed memory that agree with the exact
// nearest-rank ones within a bin, and a histogram saved as its non-empty bins
// comes back the same (the server's report latencies survive a journal).
#include "fireswarm/common/age_histogram.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <vector>

namespace fireswarm::common {
namespace {

double NearestRank(std::vector<double> values, double p) {
  std::sort(values.begin(), values.end());
  const auto rank =
      static_cast<std::size_t>(std::max(1.0, std::ceil(p * static_cast<double>(values.size()))));
  return values[rank - 1];
}

TEST(AgeHistogram, PercentilesAreTheExactOnesWithinABin) {
  std::mt19937_64 rng(7);
  std::exponential_distribution<double> ages(1.0 / 0.6);  // mean 0.6 s, a tail to seconds
  AgeHistogram histogram;
  std::vector<double> exact;
  for (int i = 0; i < 100'000; ++i) {
    const double age = ages(rng);
    histogram.Add(age);
    exact.push_back(age);
  }
  for (const double p : {0.01, 0.5, 0.9, 0.99, 0.999}) {
    const double want = NearestRank(exact, p);
    const double got = histogram.Percentile(p);
    EXPECT_GE(got, want) << "p" << p;  // the bin's upper edge
    EXPECT_LE(got, want + 0.0101) << "p" << p;
  }
  EXPECT_EQ(histogram.count(), 100'000U);
}

TEST(AgeHistogram, CoarseBinsAboveTenSecondsAndTheLargestAgeCaps) {
  AgeHistogram histogram;
  EXPECT_EQ(histogram.Percentile(0.5), 0.0) << "empty";
  histogram.Add(12.3);
  histogram.Add(0.25);
  histogram.Add(5'000.0);  // beyond the last bin
  EXPECT_DOUBLE_EQ(histogram.Percentile(0.3), 0.26);
  EXPECT_DOUBLE_EQ(histogram.Percentile(0.6), 13.0);
  EXPECT_DOUBLE_EQ(histogram.Percentile(1.0), 5'000.0);
  AgeHistogram one;
  one.Add(0.123);
  EXPECT_DOUBLE_EQ(one.Percentile(0.99), 0.123) << "never above the largest age";
}

TEST(AgeHistogram, SavedAsItsNonEmptyBinsItComesBackTheSame) {
  std::mt19937_64 rng(11);
  std::lognormal_distribution<double> delays(0.0, 2.0);  // from ms to hundreds of s
  AgeHistogram histogram;
  for (int i = 0; i < 10'000; ++i) histogram.Add(delays(rng));
  histogram.Add(-1.0);     // a clock step: counts in the first bin
  histogram.Add(4'000.0);  // beyond the last bin
  const AgeHistogram::Bins bins = histogram.NonEmptyBins();
  EXPECT_LT(bins.size(), AgeHistogram::kBins);
  const AgeHistogram back = AgeHistogram::FromBins(bins, histogram.max_s());
  EXPECT_EQ(back, histogram);
  EXPECT_EQ(back.count(), 10'002U);
  EXPECT_EQ(back.Percentile(0.99), histogram.Percentile(0.99));
  EXPECT_EQ(AgeHistogram::FromBins({}, 0.0), AgeHistogram{});
}

TEST(AgeHistogram, FromBinsNamesTheBadEntry) {
  const auto message = [](const AgeHistogram::Bins& bins, double max_s) -> std::string {
    try {
      AgeHistogram::FromBins(bins, max_s);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "accepted";
  };
  EXPECT_NE(message({{3, 1}, {AgeHistogram::kBins, 2}}, 1.0).find("bin entry 1"),
            std::string::npos);
  EXPECT_NE(message({{5, 1}, {5, 1}}, 1.0).find("ascend"), std::string::npos);
  EXPECT_NE(message({{5, 0}}, 1.0).find("count must be positive"), std::string::npos);
  EXPECT_NE(message({{5, 1}}, -1.0).find("max_s"), std::string::npos);
  EXPECT_NE(message({{5, 1}}, NAN).find("max_s"), std::string::npos);
}

}  // namespace
}  // namespace fireswarm::common
