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

namespace {

const char* ResolutionVerb(std::int8_t resolution) {
  switch (resolution) {
    case conflict_t::RESOLUTION_CLIMB:
      return "climb to";
    case conflict_t::RESOLUTION_DESCEND:
      return "descend to";
    case conflict_t::RESOLUTION_LEVEL:
      return "stay at";
    default:
      return "fly at";
  }
}

}  // namespace

void ConflictWatch::Update(const conflict_t& message, AlertLog& log) {
  const double time_s = static_cast<double>(message.utime) * 1e-6;
  char text[160];
  auto [it, added] = seen_.try_emplace(message.conflict_id);
  Seen& seen = it->second;
  if (added) {
    ++predicted_;
    std::snprintf(text, sizeof text, "drones %d and %d predicted %.1f m apart in %.0f s",
                  message.vehicle_a, message.vehicle_b, message.predicted_separation_m,
                  message.time_to_closest_s);
    log.Add(time_s, AlertLevel::kWarning, "conflict", message.vehicle_a, 0, text);
  }
  if (message.resolution != conflict_t::RESOLUTION_NONE && message.resolution != seen.resolution) {
    ++ordered_;
    std::snprintf(text, sizeof text, "drone %d ordered to %s %.0f m (conflict with drone %d)",
                  message.mover, ResolutionVerb(message.resolution), message.target_altitude_m,
                  message.mover == message.vehicle_a ? message.vehicle_b : message.vehicle_a);
    log.Add(time_s, AlertLevel::kInfo, "conflict_resolution", message.mover, 0, text);
  }
  if (message.outcome != conflict_t::OUTCOME_OPEN && seen.outcome == conflict_t::OUTCOME_OPEN) {
    const bool lost = message.outcome == conflict_t::OUTCOME_LOST_SEPARATION;
    ++(lost ? lost_separation_ : resolved_);
    std::snprintf(text, sizeof text, "drones %d and %d %s: closest %.1f m", message.vehicle_a,
                  message.vehicle_b, lost ? "lost separation" : "passed apart",
                  message.observed_min_separation_m);
    log.Add(time_s, lost ? AlertLevel::kCritical : AlertLevel::kInfo,
            lost ? "separation_lost" : "conflict_resolved", message.vehicle_a, 0, text);
  }
  seen.resolution = message.resolution;
  seen.outcome = message.outcome;
}

nlohmann::json ConflictWatch::Counts() const {
  return {{"predicted", predicted_},
          {"ordered", ordered_},
          {"resolved", resolved_},
          {"lost_separation", lost_separation_},
          {"open", predicted_ - resolved_ - lost_separation_}};
}

}  // namespace fireswarm::server::internal
