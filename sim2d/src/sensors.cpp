#include <array>
#include <cmath>

#include "multirotor_dynamics.hpp"
#include "sensor_suite.hpp"

namespace fireswarm::sim2d {
namespace {

// A 2D Gaussian with per-axis std sigma has its circular error probable (the
// median radial error) at sigma * sqrt(2 ln 2).
constexpr double kCepPerSigma = 1.1774100225154747;

// Slot stagger per vehicle: the fractional part of id * golden ratio spreads any
// number of IDs evenly over [0, 1); each sensor kind gets its own offset.
double PhaseFraction(int vehicle_id, int sensor_index) {
  constexpr double kGoldenFraction = 0.6180339887498949;
  const double x = static_cast<double>(vehicle_id) * kGoldenFraction + 0.25 * sensor_index;
  return x - std::floor(x);
}

// The sensor-fault logic shared by every sensor: a cut sensor says nothing; a
// frozen one repeats the value it had before the fault (with fresh timestamps);
// otherwise a fresh reading is made and remembered.
template <typename Reading, typename MakeReading>
void Deliver(double time_s, const SensorFaultState& fault, std::optional<Reading>& last,
             std::optional<Reading>& frozen, std::optional<Reading>& out, MakeReading make) {
  if (!fault.frozen) frozen.reset();
  if (fault.cut) return;
  if (fault.frozen) {
    if (!frozen) frozen = last ? *last : make();
    out = *frozen;
    out->time_s = time_s;
    return;
  }
  out = make();
  last = out;
}

}  // namespace

NoiseSource::NoiseSource(Rng seed_source) {
  // One 32-bit seed per taus88 component (Boost lifts any below its minimum).
  std::array<std::uint32_t, 3> seeds{};
  for (std::uint32_t& seed : seeds) seed = static_cast<std::uint32_t>(seed_source() >> 32U);
  auto first = seeds.begin();
  generator.seed(first, seeds.end());
}

RateAdapter::RateAdapter(double rate_hz, double phase_fraction)
    : period_s_(1.0 / rate_hz), phase_s_(phase_fraction / rate_hz) {}

bool RateAdapter::Due(double time_s) {
  // Tolerates the rounding of time_s = steps * step_s; slot times are computed
  // from the slot index, never accumulated.
  constexpr double kTimeToleranceS = 1e-9;
  const double slot_time_s = phase_s_ + static_cast<double>(next_slot_) * period_s_;
  if (time_s + kTimeToleranceS < slot_time_s) return false;
  next_slot_ =
      static_cast<std::int64_t>(std::floor((time_s + kTimeToleranceS - phase_s_) / period_s_)) + 1;
  return true;
}

GaussMarkov::GaussMarkov(double stationary_std, double time_constant_s, double period_s,
                         NoiseSource& noise)
    : decay_(std::exp(-period_s / time_constant_s)),
      drive_std_(stationary_std * std::sqrt(1.0 - decay_ * decay_)),
      value_(stationary_std * noise.Gaussian()) {}

double GaussMarkov::Advance(NoiseSource& noise) {
  value_ = value_ * decay_ + drive_std_ * noise.Gaussian();
  return value_;
}

SensorSuite::SensorSuite(const SensorParams& params, int vehicle_id, std::uint64_t seed)
    : params_(params),
      gps_noise_(MakeRng(seed, "sensor.gps", static_cast<std::uint64_t>(vehicle_id))),
      baro_noise_(MakeRng(seed, "sensor.baro", static_cast<std::uint64_t>(vehicle_id))),
      attitude_noise_(MakeRng(seed, "sensor.attitude", static_cast<std::uint64_t>(vehicle_id))),
      battery_noise_(MakeRng(seed, "sensor.battery", static_cast<std::uint64_t>(vehicle_id))),
      gps_rate_(params.gps.rate_hz, PhaseFraction(vehicle_id, 0)),
      baro_rate_(params.baro.rate_hz, PhaseFraction(vehicle_id, 1)),
      attitude_rate_(params.attitude.rate_hz, PhaseFraction(vehicle_id, 2)),
      battery_rate_(params.battery.rate_hz, PhaseFraction(vehicle_id, 3)) {
  const GpsParams& gps = params.gps;
  const double sigma_m = gps.horizontal_cep_m / kCepPerSigma;
  const double bias_share = gps.bias_variance_fraction;
  gps_white_std_m_ = sigma_m * std::sqrt(1.0 - bias_share);
  gps_vertical_white_std_m_ = gps.vertical_std_m * std::sqrt(1.0 - bias_share);
  const double period_s = gps_rate_.period_s();
  const double bias_std_m = sigma_m * std::sqrt(bias_share);
  const double vertical_bias_std_m = gps.vertical_std_m * std::sqrt(bias_share);
  gps_bias_east_ = GaussMarkov(bias_std_m, gps.bias_time_constant_s, period_s, gps_noise_);
  gps_bias_north_ = GaussMarkov(bias_std_m, gps.bias_time_constant_s, period_s, gps_noise_);
  gps_bias_up_ = GaussMarkov(vertical_bias_std_m, gps.bias_time_constant_s, period_s, gps_noise_);
  baro_bias_ = GaussMarkov(params.baro.bias_std_m, params.baro.bias_time_constant_s,
                           baro_rate_.period_s(), baro_noise_);
}

void SensorSuite::Sample(double time_s, const VehicleTruth& truth, const BatteryTruth& battery,
                         const FaultState& faults, const common::LocalFrame& frame,
                         SensorSample& out) {
  out = SensorSample{};
  if (faults.lost) return;
  if (gps_rate_.Due(time_s)) {
    // The biases wander whether or not the stream is cut.
    gps_bias_east_.Advance(gps_noise_);
    gps_bias_north_.Advance(gps_noise_);
    gps_bias_up_.Advance(gps_noise_);
    const SensorFaultState& fault = faults.sensor(SensorKind::kGps);
    Deliver(time_s, fault, last_gps_, frozen_gps_, out.gps,
            [&] { return MakeGps(time_s, truth, fault, frame); });
  }
  if (baro_rate_.Due(time_s)) {
    baro_bias_.Advance(baro_noise_);
    const SensorFaultState& fault = faults.sensor(SensorKind::kBaro);
    Deliver(time_s, fault, last_baro_, frozen_baro_, out.baro,
            [&] { return MakeBaro(time_s, truth, fault); });
  }
  if (attitude_rate_.Due(time_s)) {
    const SensorFaultState& fault = faults.sensor(SensorKind::kAttitude);
    Deliver(time_s, fault, last_attitude_, frozen_attitude_, out.attitude,
            [&] { return MakeAttitude(time_s, truth, fault); });
  }
  if (battery_rate_.Due(time_s)) {
    const SensorFaultState& fault = faults.sensor(SensorKind::kBattery);
    Deliver(time_s, fault, last_battery_, frozen_battery_, out.battery,
            [&] { return MakeBattery(time_s, battery, fault); });
  }
}

GpsReading SensorSuite::MakeGps(double time_s, const VehicleTruth& truth,
                                const SensorFaultState& fault, const common::LocalFrame& frame) {
  const double white_m = gps_white_std_m_ * fault.noise_factor;
  const double east_m = truth.position_m.x() + gps_bias_east_.value() +
                        white_m * gps_noise_.Gaussian() + fault.bias.x();
  const double north_m = truth.position_m.y() + gps_bias_north_.value() +
                         white_m * gps_noise_.Gaussian() + fault.bias.y();
  GpsReading reading;
  reading.time_s = time_s;
  reading.position = frame.ToGeodetic(common::EastNorth{east_m, north_m});
  reading.altitude_m = truth.altitude_m + gps_bias_up_.value() +
                       gps_vertical_white_std_m_ * fault.noise_factor * gps_noise_.Gaussian() +
                       fault.bias.z();
  const double velocity_std = params_.gps.velocity_std_mps * fault.noise_factor;
  reading.velocity_mps =
      truth.velocity_mps + velocity_std * Vec2(gps_noise_.Gaussian(), gps_noise_.Gaussian());
  return reading;
}

BaroReading SensorSuite::MakeBaro(double time_s, const VehicleTruth& truth,
                                  const SensorFaultState& fault) {
  const double noise_m = params_.baro.noise_std_m * fault.noise_factor * baro_noise_.Gaussian();
  return BaroReading{time_s, truth.altitude_m + baro_bias_.value() + noise_m + fault.bias.x()};
}

AttitudeReading SensorSuite::MakeAttitude(double time_s, const VehicleTruth& truth,
                                          const SensorFaultState& fault) {
  const AttitudeSensorParams& p = params_.attitude;
  const double angle_std = p.angle_noise_std_rad * fault.noise_factor;
  const double rate_std = p.rate_noise_std_radps * fault.noise_factor;
  NoiseSource& noise = attitude_noise_;
  AttitudeReading reading;
  reading.time_s = time_s;
  reading.roll_rad = truth.roll_rad + angle_std * noise.Gaussian() + fault.bias.x();
  reading.pitch_rad = truth.pitch_rad + angle_std * noise.Gaussian() + fault.bias.y();
  reading.heading_rad =
      WrapTwoPi(truth.heading_rad +
                p.heading_noise_std_rad * fault.noise_factor * noise.Gaussian() + fault.bias.z());
  reading.roll_rate_radps = truth.roll_rate_radps + rate_std * noise.Gaussian();
  reading.pitch_rate_radps = truth.pitch_rate_radps + rate_std * noise.Gaussian();
  reading.yaw_rate_radps = truth.yaw_rate_radps + rate_std * noise.Gaussian();
  return reading;
}

BatteryReading SensorSuite::MakeBattery(double time_s, const BatteryTruth& battery,
                                        const SensorFaultState& fault) {
  const BatterySensorParams& p = params_.battery;
  NoiseSource& noise = battery_noise_;
  BatteryReading reading;
  reading.time_s = time_s;
  reading.voltage_v = battery.voltage_v +
                      p.voltage_noise_std_v * fault.noise_factor * noise.Gaussian() +
                      fault.bias.x();
  reading.current_a =
      battery.current_a + p.current_noise_std_a * fault.noise_factor * noise.Gaussian();
  reading.fraction = battery.fraction;
  return reading;
}

void SensorSuite::HashInto(StateHasher& hasher) const {
  hasher.Add(gps_bias_east_.value());
  hasher.Add(gps_bias_north_.value());
  hasher.Add(gps_bias_up_.value());
  hasher.Add(baro_bias_.value());
  hasher.AddOptional(last_gps_, [](StateHasher& h, const GpsReading& r) {
    h.Add(r.time_s);
    h.Add(r.position.lat_deg);
    h.Add(r.position.lon_deg);
    h.Add(r.altitude_m);
    h.Add(r.velocity_mps);
  });
  hasher.AddOptional(last_baro_, [](StateHasher& h, const BaroReading& r) {
    h.Add(r.time_s);
    h.Add(r.altitude_m);
  });
  hasher.AddOptional(last_attitude_, [](StateHasher& h, const AttitudeReading& r) {
    h.Add(r.time_s);
    h.Add(r.roll_rad);
    h.Add(r.pitch_rad);
    h.Add(r.heading_rad);
  });
  hasher.AddOptional(last_battery_, [](StateHasher& h, const BatteryReading& r) {
    h.Add(r.time_s);
    h.Add(r.voltage_v);
    h.Add(r.current_a);
  });
}

}  // namespace fireswarm::sim2d
