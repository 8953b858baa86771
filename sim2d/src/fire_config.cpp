#include "fireswarm/sim2d/fire_config.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string_view>

namespace fireswarm::sim2d {
namespace {

[[noreturn]] void Reject(std::string_view field, double value, std::string_view rule) {
  std::ostringstream message;
  message << "fire config: " << field << " = " << value << " " << rule;
  throw std::invalid_argument(message.str());
}

void RequirePositive(std::string_view field, double value) {
  if (!std::isfinite(value) || value <= 0.0) Reject(field, value, "must be a finite number > 0");
}

void RequireNonNegative(std::string_view field, double value) {
  if (!std::isfinite(value) || value < 0.0) Reject(field, value, "must be a finite number >= 0");
}

void ValidateFuel(std::string_view name, const FuelBehaviour& fuel) {
  const std::string prefix(name);
  RequireNonNegative(prefix + ".no_wind_ros_mpm", fuel.no_wind_ros_mpm);
  RequirePositive(prefix + ".head_ros_ref_mpm", fuel.head_ros_ref_mpm);
  if (fuel.no_wind_ros_mpm > fuel.head_ros_ref_mpm) {
    Reject(prefix + ".no_wind_ros_mpm", fuel.no_wind_ros_mpm,
           "must not exceed head_ros_ref_mpm (wind cannot slow a head fire)");
  }
  RequirePositive(prefix + ".burn_duration_s", fuel.burn_duration_s);
}

// A grid larger than this many cells would need gigabytes of per-cell state.
constexpr double kMaxCells = 1.0e8;

}  // namespace

void FireConfig::Validate() const {
  if (!origin_m.allFinite()) Reject("origin_m", origin_m.norm(), "must be finite");
  RequirePositive("width_m", width_m);
  RequirePositive("height_m", height_m);
  RequirePositive("cell_size_m", cell_size_m);
  if ((width_m / cell_size_m) * (height_m / cell_size_m) > kMaxCells) {
    Reject("cell_size_m", cell_size_m, "makes more than 1e8 cells for this area");
  }
  RequireNonNegative("wind_speed_mps", wind_speed_mps);
  if (!std::isfinite(wind_from_deg)) Reject("wind_from_deg", wind_from_deg, "must be finite");
  RequireNonNegative("wind_exponent", wind_exponent);
  if (!std::isfinite(jitter_fraction) || jitter_fraction < 0.0 || jitter_fraction >= 1.0) {
    Reject("jitter_fraction", jitter_fraction, "must be in [0, 1)");
  }
  ValidateFuel("forest", forest);
  ValidateFuel("open", open);
  if (!std::isfinite(ambient_c) || ambient_c < -60.0 || ambient_c > 60.0) {
    Reject("ambient_c", ambient_c, "must be in [-60, 60] C");
  }
  if (!std::isfinite(flame_c) || flame_c <= ambient_c) {
    Reject("flame_c", flame_c, "must be finite and hotter than ambient_c");
  }
  if (!std::isfinite(ember_c) || ember_c <= ambient_c || ember_c > flame_c) {
    Reject("ember_c", ember_c, "must be hotter than ambient_c and not hotter than flame_c");
  }
  RequirePositive("cooling_tau_s", cooling_tau_s);
  RequirePositive("cooled_threshold_k", cooled_threshold_k);
}

const FuelBehaviour& FireConfig::Behaviour(Fuel fuel) const {
  static const FuelBehaviour kNoFuel{};
  switch (fuel) {
    case Fuel::kForest:
      return forest;
    case Fuel::kOpen:
      return open;
    case Fuel::kNone:
      break;
  }
  return kNoFuel;
}

}  // namespace fireswarm::sim2d
