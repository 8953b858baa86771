#include "fireswarm/common/age_histogram.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace fireswarm::common {

std::size_t AgeHistogram::BinOf(double age_s) {
  constexpr auto kFineLimit = static_cast<double>(kFineLimitS);
  if (!(age_s > 0.0)) return 0;
  if (age_s < kFineLimit) {
    return std::min(kFineBins - 1,
                    static_cast<std::size_t>(age_s * static_cast<double>(kFineBinsPerS)));
  }
  if (age_s < static_cast<double>(kCoarseLimitS)) {
    return kFineBins + std::min(kCoarseBins - 1, static_cast<std::size_t>(age_s - kFineLimit));
  }
  return kFineBins + kCoarseBins;
}

double AgeHistogram::UpperEdgeS(std::size_t bin) {
  if (bin < kFineBins) {
    return static_cast<double>(bin + 1) / static_cast<double>(kFineBinsPerS);
  }
  if (bin < kFineBins + kCoarseBins) return static_cast<double>(kFineLimitS + bin - kFineBins + 1);
  return std::numeric_limits<double>::infinity();
}

AgeHistogram AgeHistogram::FromBins(const Bins& bins, double max_s) {
  if (!std::isfinite(max_s) || max_s < 0.0) {
    throw std::invalid_argument("age histogram: max_s must be finite and >= 0, got " +
                                std::to_string(max_s));
  }
  AgeHistogram histogram;
  for (std::size_t i = 0; i < bins.size(); ++i) {
    const auto [bin, count] = bins[i];
    const std::string where =
        "age histogram: bin entry " + std::to_string(i) + " (index " + std::to_string(bin) + ")";
    if (bin >= kBins) {
      throw std::invalid_argument(where + ": index must be below " + std::to_string(kBins));
    }
    if (i > 0 && bin <= bins[i - 1].first) {
      throw std::invalid_argument(where + ": indices must ascend");
    }
    if (count == 0) throw std::invalid_argument(where + ": count must be positive");
    if (histogram.bins_.empty()) histogram.bins_.assign(kBins, 0);
    histogram.bins_[bin] = count;
    histogram.count_ += count;
  }
  histogram.max_s_ = histogram.count_ > 0 ? max_s : 0.0;
  return histogram;
}

void AgeHistogram::Add(double age_s) {
  if (bins_.empty()) bins_.assign(kBins, 0);
  ++bins_[BinOf(age_s)];
  ++count_;
  if (age_s > max_s_) max_s_ = age_s;
}

double AgeHistogram::Percentile(double p) const {
  if (count_ == 0) return 0.0;
  const double rank = std::max(1.0, std::ceil(p * static_cast<double>(count_)));
  std::uint64_t seen = 0;
  for (std::size_t bin = 0; bin < bins_.size(); ++bin) {
    seen += bins_[bin];
    if (static_cast<double>(seen) >= rank) return std::min(UpperEdgeS(bin), max_s_);
  }
  return max_s_;
}

AgeHistogram::Bins AgeHistogram::NonEmptyBins() const {
  Bins out;
  for (std::size_t bin = 0; bin < bins_.size(); ++bin) {
    if (bins_[bin] > 0) out.emplace_back(bin, bins_[bin]);
  }
  return out;
}

}  // namespace fireswarm::common
