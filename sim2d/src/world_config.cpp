#include "fireswarm/sim2d/world_config.hpp"

#include <cmath>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>

#include "fireswarm/common/units.hpp"

namespace fireswarm::sim2d {
namespace {

// Checks fields and throws std::invalid_argument("<prefix><field> must be ..., got <value>").
class FieldChecker {
 public:
  explicit FieldChecker(std::string prefix) : prefix_(std::move(prefix)) {}

  void Positive(std::string_view field, double value) const {
    if (!(std::isfinite(value) && value > 0.0)) Fail(field, "must be > 0", value);
  }
  void NonNegative(std::string_view field, double value) const {
    if (!(std::isfinite(value) && value >= 0.0)) Fail(field, "must be >= 0", value);
  }
  void Finite(std::string_view field, double value) const {
    if (!std::isfinite(value)) Fail(field, "must be finite", value);
  }
  void InRange(std::string_view field, double value, double low, double high) const {
    if (!(value >= low && value <= high)) {
      Fail(field, "must be in [" + Format(low) + ", " + Format(high) + "]", value);
    }
  }
  void AtMost(std::string_view field, double value, double high, std::string_view why) const {
    if (!(value <= high)) {
      Fail(field, "must be <= " + Format(high) + " (" + std::string(why) + ")", value);
    }
  }
  [[noreturn]] void Fail(std::string_view field, std::string_view what, double value) const {
    throw std::invalid_argument(prefix_ + std::string(field) + " " + std::string(what) + ", got " +
                                Format(value));
  }

 private:
  static std::string Format(double value) {
    std::ostringstream out;
    out << value;
    return out.str();
  }
  std::string prefix_;
};

std::string VehiclePrefix(int id) {
  return "vehicle " + std::to_string(id) + ": ";
}

void CheckMultirotor(const FieldChecker& check, const MultirotorParams& p) {
  check.Positive("multirotor.mass_kg", p.mass_kg);
  check.Positive("multirotor.roll_pitch_inertia_kgm2", p.roll_pitch_inertia_kgm2);
  check.Positive("multirotor.radius_m", p.radius_m);
  check.Positive("multirotor.height_m", p.height_m);
  check.Positive("multirotor.max_thrust_n", p.max_thrust_n);
  if (p.max_thrust_n <= p.mass_kg * common::kGravityMps2) {
    check.Fail("multirotor.max_thrust_n", "must exceed the weight (mass_kg * g) to fly",
               p.max_thrust_n);
  }
  check.Positive("multirotor.thrust_time_constant_s", p.thrust_time_constant_s);
  check.Positive("multirotor.climb_gain_per_s", p.climb_gain_per_s);
  check.Positive("multirotor.max_climb_rate_mps", p.max_climb_rate_mps);
  check.Positive("multirotor.max_descent_rate_mps", p.max_descent_rate_mps);
  check.InRange("multirotor.max_tilt_rad", p.max_tilt_rad, 0.0, 1.4);
  check.Positive("multirotor.attitude_time_constant_s", p.attitude_time_constant_s);
  check.Positive("multirotor.max_attitude_rate_radps", p.max_attitude_rate_radps);
  check.Positive("multirotor.yaw_time_constant_s", p.yaw_time_constant_s);
  check.Positive("multirotor.max_yaw_rate_radps", p.max_yaw_rate_radps);
  check.NonNegative("multirotor.linear_drag_n_per_mps", p.linear_drag_n_per_mps);
  check.NonNegative("multirotor.quadratic_drag_n_per_mps2", p.quadratic_drag_n_per_mps2);
  check.Positive("multirotor.crash_vertical_speed_mps", p.crash_vertical_speed_mps);
  check.Positive("multirotor.crash_horizontal_speed_mps", p.crash_horizontal_speed_mps);
  const BatteryParams& b = p.battery;
  check.Positive("multirotor.battery.capacity_wh", b.capacity_wh);
  check.NonNegative("multirotor.battery.reference_power_w", b.reference_power_w);
  check.Positive("multirotor.battery.reference_thrust_n", b.reference_thrust_n);
  check.NonNegative("multirotor.battery.avionics_power_w", b.avionics_power_w);
  check.Positive("multirotor.battery.empty_voltage_v", b.empty_voltage_v);
  if (!(b.full_voltage_v > b.empty_voltage_v)) {
    check.Fail("multirotor.battery.full_voltage_v", "must exceed empty_voltage_v",
               b.full_voltage_v);
  }
  if (!(b.initial_fraction > 0.0 && b.initial_fraction <= 1.0)) {
    check.Fail("multirotor.battery.initial_fraction", "must be in (0, 1]", b.initial_fraction);
  }
}

void CheckRate(const FieldChecker& check, std::string_view field, double rate_hz, double step_s) {
  check.Positive(field, rate_hz);
  check.AtMost(field, rate_hz, 1.0 / step_s, "one sample per step at most: 1 / step_s");
}

void CheckSensors(const FieldChecker& check, const SensorParams& s, double step_s) {
  CheckRate(check, "sensors.gps.rate_hz", s.gps.rate_hz, step_s);
  check.NonNegative("sensors.gps.horizontal_cep_m", s.gps.horizontal_cep_m);
  check.NonNegative("sensors.gps.vertical_std_m", s.gps.vertical_std_m);
  check.InRange("sensors.gps.bias_variance_fraction", s.gps.bias_variance_fraction, 0.0, 1.0);
  check.Positive("sensors.gps.bias_time_constant_s", s.gps.bias_time_constant_s);
  check.NonNegative("sensors.gps.velocity_std_mps", s.gps.velocity_std_mps);
  CheckRate(check, "sensors.baro.rate_hz", s.baro.rate_hz, step_s);
  check.NonNegative("sensors.baro.noise_std_m", s.baro.noise_std_m);
  check.NonNegative("sensors.baro.bias_std_m", s.baro.bias_std_m);
  check.Positive("sensors.baro.bias_time_constant_s", s.baro.bias_time_constant_s);
  CheckRate(check, "sensors.attitude.rate_hz", s.attitude.rate_hz, step_s);
  check.NonNegative("sensors.attitude.angle_noise_std_rad", s.attitude.angle_noise_std_rad);
  check.NonNegative("sensors.attitude.heading_noise_std_rad", s.attitude.heading_noise_std_rad);
  check.NonNegative("sensors.attitude.rate_noise_std_radps", s.attitude.rate_noise_std_radps);
  CheckRate(check, "sensors.battery.rate_hz", s.battery.rate_hz, step_s);
  check.NonNegative("sensors.battery.voltage_noise_std_v", s.battery.voltage_noise_std_v);
  check.NonNegative("sensors.battery.current_noise_std_a", s.battery.current_noise_std_a);
}

}  // namespace

void ValidateFault(int vehicle_id, const FaultSpec& fault) {
  const FieldChecker check(VehiclePrefix(vehicle_id));
  check.NonNegative("fault.start_s", fault.start_s);
  if (fault.kind != FaultKind::kTotalLoss && !(fault.end_s > fault.start_s)) {
    check.Fail("fault.end_s", "must be > start_s", fault.end_s);
  }
  for (int axis = 0; axis < 3; ++axis) check.Finite("fault.bias", fault.bias[axis]);
  if (!(std::isfinite(fault.noise_factor) && fault.noise_factor >= 1.0)) {
    check.Fail("fault.noise_factor", "must be >= 1", fault.noise_factor);
  }
  check.Finite("fault.ballast_offset_m.x", fault.ballast_offset_m.x());
  check.Finite("fault.ballast_offset_m.y", fault.ballast_offset_m.y());
}

void ValidateVehicle(const VehicleConfig& vehicle, double step_s) {
  if (vehicle.id < 1) {
    throw std::invalid_argument("vehicle id must be >= 1, got " + std::to_string(vehicle.id));
  }
  const FieldChecker check(VehiclePrefix(vehicle.id));
  check.Finite("launch_position_m.x", vehicle.launch_position_m.x());
  check.Finite("launch_position_m.y", vehicle.launch_position_m.y());
  check.Finite("launch_heading_rad", vehicle.launch_heading_rad);
  CheckMultirotor(check, vehicle.multirotor);
  CheckSensors(check, vehicle.sensors, step_s);
  for (const FaultSpec& fault : vehicle.faults) ValidateFault(vehicle.id, fault);
}

void WorldConfig::Validate() const {
  if (!common::IsValidLatLon(origin)) {
    throw std::invalid_argument("origin must be a valid lat/lon, got " +
                                std::to_string(origin.lat_deg) + ", " +
                                std::to_string(origin.lon_deg));
  }
  const FieldChecker check("");
  check.Positive("step_s", step_s);
  if (substeps < 1) check.Fail("substeps", "must be >= 1", substeps);
  check.NonNegative("wind.speed_mps", wind.speed_mps);
  check.Finite("wind.from_deg", wind.from_deg);
  check.NonNegative("wind.gust_std_mps", wind.gust_std_mps);
  check.Positive("wind.gust_time_constant_s", wind.gust_time_constant_s);
  check.Positive("collision.near_miss_separation_m", collision.near_miss_separation_m);
  check.Positive("collision.crash_relative_speed_mps", collision.crash_relative_speed_mps);
  check.InRange("collision.restitution", collision.restitution, 0.0, 1.0);
  check.NonNegative("collision.friction", collision.friction);
  check.NonNegative("battery_swap_s", battery_swap_s);
  check.Finite("battery_swap_s", battery_swap_s);
  std::set<int> ids;
  for (const VehicleConfig& vehicle : vehicles) {
    ValidateVehicle(vehicle, step_s);
    if (!ids.insert(vehicle.id).second) {
      throw std::invalid_argument("vehicles: duplicate id " + std::to_string(vehicle.id));
    }
  }
}

}  // namespace fireswarm::sim2d
