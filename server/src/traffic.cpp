// The tactical watch over the fleet: closest approaches predicted from
// telemetry, avoid orders, outcomes. The rules are in traffic.hpp.
#include "fireswarm/server/traffic.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace fireswarm::server {

namespace {

void RequirePositive(double value, const char* field) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    throw std::invalid_argument(std::string("separation: ") + field + " must be a positive number");
  }
}

}  // namespace

void SeparationConfig::Validate() const {
  RequirePositive(separation_m, "separation_m");
  RequirePositive(layer_m, "layer_m");
  RequirePositive(transit_min_m, "transit_min_m");
  RequirePositive(horizon_s, "horizon_s");
  RequirePositive(max_altitude_m, "max_altitude_m");
  if (!(min_altitude_m >= 0.0) || !(min_altitude_m < max_altitude_m)) {
    throw std::invalid_argument("separation: min_altitude_m must be in [0, max_altitude_m)");
  }
  if (search_layers < 1 || search_layers > 10) {
    throw std::invalid_argument("separation: search_layers must be in 1..10");
  }
  if (transit_sectors < 1 || transit_sectors > 12) {
    throw std::invalid_argument("separation: transit_sectors must be in 1..12");
  }
}

const char* ToString(Resolution resolution) {
  switch (resolution) {
    case Resolution::kNone:
      return "none";
    case Resolution::kClimb:
      return "climb";
    case Resolution::kDescend:
      return "descend";
    case Resolution::kLevel:
      return "level";
  }
  return "unknown";
}

const char* ToString(ConflictOutcome outcome) {
  switch (outcome) {
    case ConflictOutcome::kOpen:
      return "open";
    case ConflictOutcome::kResolved:
      return "resolved";
    case ConflictOutcome::kLostSeparation:
      return "lost_separation";
  }
  return "unknown";
}

TrafficControl::TrafficControl(const SeparationConfig& config) : config_(config) {
  config_.Validate();
}

void TrafficControl::Observe(int vehicle, const TrafficSample& sample) {
  tracks_[vehicle] = sample;
}

void TrafficControl::Forget(int vehicle) {
  tracks_.erase(vehicle);
}

void TrafficControl::ExpectLost(int vehicle, const TrafficSample& last,
                                const Eigen::Vector2d& home_m, double altitude_m, double speed_mps,
                                double until_s) {
  tracks_.erase(vehicle);
  ghosts_[vehicle] = Ghost{last, home_m, altitude_m, speed_mps, until_s};
}

void TrafficControl::SetIntent(int vehicle, std::optional<double> altitude_m) {
  intents_[vehicle] = altitude_m;
}

std::vector<AvoidOrder> TrafficControl::Step(double /*now_s*/) {
  return {};  // TODO(traffic): predictions (next commit)
}

}  // namespace fireswarm::server
