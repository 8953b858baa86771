// A distribution of ages or delays (s) in fixed memory, however long a server
// runs: the scorer's telemetry ages, the server's fire-report latencies.
#pragma once

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace fireswarm::common {

/// Ages in 10 ms bins below 10 s, 1 s bins to 1,000 s, and one bin above.
/// Percentile() is the nearest-rank percentile's bin's upper edge, at most the
/// largest age added: within 10 ms of the exact value below 10 s, within 1 s
/// below 1,000 s. Ages <= 0 (and NaN) count in the first bin.
class AgeHistogram {
 public:
  /// Fine bins per second (10 ms each), from 0 to kFineLimitS.
  static constexpr std::size_t kFineBinsPerS = 100;
  static constexpr std::size_t kFineLimitS = 10;
  /// 1 s bins from kFineLimitS to kCoarseLimitS; one bin above.
  static constexpr std::size_t kCoarseLimitS = 1'000;
  static constexpr std::size_t kFineBins = kFineLimitS * kFineBinsPerS;
  static constexpr std::size_t kCoarseBins = kCoarseLimitS - kFineLimitS;
  static constexpr std::size_t kBins = kFineBins + kCoarseBins + 1;

  /// (bin index, count) of every bin holding an age, ascending by index: what a
  /// journal stores.
  using Bins = std::vector<std::pair<std::size_t, std::uint64_t>>;

  AgeHistogram() = default;
  /// The histogram NonEmptyBins() and max_s() describe. Throws
  /// std::invalid_argument naming the first bin whose index is >= kBins, not
  /// ascending, or whose count is 0, and a max_s that is negative or not finite.
  static AgeHistogram FromBins(const Bins& bins, double max_s);

  void Add(double age_s);
  bool empty() const { return count_ == 0; }
  std::uint64_t count() const { return count_; }
  /// The largest age added, s (0 when empty).
  double max_s() const { return max_s_; }
  /// p in (0, 1]; 0 when empty.
  double Percentile(double p) const;
  Bins NonEmptyBins() const;

  friend bool operator==(const AgeHistogram&, const AgeHistogram&) = default;

 private:
  static std::size_t BinOf(double age_s);
  static double UpperEdgeS(std::size_t bin);

  std::vector<std::uint64_t> bins_;  // kBins, allocated at the first Add
  std::uint64_t count_ = 0;
  double max_s_ = 0.0;
};

}  // namespace fireswarm::common
