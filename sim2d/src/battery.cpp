#include <algorithm>
#include <cmath>

#include "battery_model.hpp"

namespace fireswarm::sim2d {

double BatteryPowerW(const BatteryParams& params, double thrust_n) {
  const double ratio = std::max(0.0, thrust_n) / params.reference_thrust_n;
  return params.avionics_power_w + params.reference_power_w * ratio * std::sqrt(ratio);
}

double BatteryCapacityJ(const BatteryParams& params) {
  constexpr double kJoulesPerWh = 3600.0;
  return params.capacity_wh * kJoulesPerWh;
}

double DrainBatteryJ(double energy_j, double power_w, double dt_s) {
  return std::max(0.0, energy_j - power_w * dt_s);
}

double BatteryVoltageV(const BatteryParams& params, double fraction) {
  const double clamped = std::clamp(fraction, 0.0, 1.0);
  return params.empty_voltage_v + (params.full_voltage_v - params.empty_voltage_v) * clamped;
}

}  // namespace fireswarm::sim2d
