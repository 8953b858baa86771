// Separation between airborne drones, from their reported positions.
#include <cmath>
#include <cstdio>
#include <string>

#include "command_center_alerts.hpp"

namespace fireswarm::server::internal {

void SeparationWatch::Update(int vehicle, const std::optional<Eigen::Vector3d>& position_enu_m,
                             double time_s, AlertLog& log) {
  if (!position_enu_m) {
    airborne_.erase(vehicle);
    std::erase_if(close_, [vehicle](const auto& pair) {
      return pair.first == vehicle || pair.second == vehicle;
    });
    return;
  }
  airborne_[vehicle] = *position_enu_m;
  const double clear_m = kSeparationClearFactor * separation_m_;
  for (const auto& [other, other_position] : airborne_) {
    if (other == vehicle) continue;
    // Squared distances: this runs for every pair at the telemetry rate.
    const double distance2_m2 = (*position_enu_m - other_position).squaredNorm();
    if (distance2_m2 > clear_m * clear_m) {
      if (!close_.empty()) close_.erase(std::minmax(vehicle, other));
      continue;
    }
    const std::pair<int, int> pair = std::minmax(vehicle, other);
    const double distance_m = std::sqrt(distance2_m2);
    if (distance_m < separation_m_ && close_.insert(pair).second) {
      char text[96];
      std::snprintf(text, sizeof text, "drones %d and %d: %.1f m apart", pair.first, pair.second,
                    distance_m);
      log.Add(time_s, AlertLevel::kCritical, "separation", pair.first, 0, text);
    }
  }
}

}  // namespace fireswarm::server::internal
