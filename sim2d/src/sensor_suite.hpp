// One vehicle's sensors (seed 4.3): refresh-rate adapters that let each sensor
// through only in its own time slots, Gaussian noise, Gauss-Markov biases, and
// the sensor faults (cut, frozen, bias, extra noise). Pure: the caller passes
// truth, time and the fault state; each sensor owns its seeded generator.
#pragma once

#include <boost/random/normal_distribution.hpp>
#include <boost/random/taus88.hpp>
#include <cstdint>
#include <optional>

#include "fault_state.hpp"
#include "fireswarm/common/local_frame.hpp"
#include "fireswarm/sim2d/random.hpp"
#include "fireswarm/sim2d/sensors.hpp"
#include "world_hash.hpp"

namespace fireswarm::sim2d {

/// The seed's refresh-rate adapter: of a fast stream of step times it lets one
/// through per period (slots at phase_s + k * period_s) and drops the rest.
class RateAdapter {
 public:
  /// Precondition: rate_hz > 0, phase_fraction in [0, 1).
  RateAdapter(double rate_hz, double phase_fraction);
  /// True when a slot has come up since the last sample (at most once per call).
  bool Due(double time_s);
  double period_s() const { return period_s_; }

 private:
  double period_s_;
  double phase_s_;
  std::int64_t next_slot_ = 0;
};

/// One sensor's noise: a generator seeded from the source's own Rng (MakeRng)
/// and a unit normal distribution.
///
/// Why not draw from the Rng itself: a fleet samples thousands of sensors per
/// step, each from its own generator, and mt19937_64's 2.5 KB state meant a cache
/// miss per sensor per step (a fifth of a 1,000-vehicle step). L'Ecuyer's taus88
/// keeps 12 bytes of state with good statistics for noise; Boost's ziggurat draws
/// a normal from about one word, a third of std::normal_distribution's cost.
struct NoiseSource {
  explicit NoiseSource(Rng seed_source);
  double Gaussian() { return unit(generator); }
  boost::random::taus88 generator;
  boost::random::normal_distribution<double> unit;
};

/// A first-order Gauss-Markov process sampled every period_s, started from its
/// stationary distribution: b' = b e^(-dt/tau) + std sqrt(1 - e^(-2 dt/tau)) w.
class GaussMarkov {
 public:
  GaussMarkov() = default;
  GaussMarkov(double stationary_std, double time_constant_s, double period_s, NoiseSource& noise);
  /// Advances one period and returns the new value.
  double Advance(NoiseSource& noise);
  double value() const { return value_; }

 private:
  double decay_ = 0.0;
  double drive_std_ = 0.0;
  double value_ = 0.0;
};

/// What the battery monitor measures this step.
struct BatteryTruth {
  double voltage_v = 0.0;
  double current_a = 0.0;
  double fraction = 0.0;
};

class SensorSuite {
 public:
  /// Seeds one generator per sensor from (seed, sensor name, vehicle_id), and
  /// staggers the sensors' slots by the vehicle's ID so a fleet's samples spread
  /// over the steps instead of all landing in one.
  SensorSuite(const SensorParams& params, int vehicle_id, std::uint64_t seed);

  /// Produces this step's sample: resets `out`, then sets each sensor that is due.
  void Sample(double time_s, const VehicleTruth& truth, const BatteryTruth& battery,
              const FaultState& faults, const common::LocalFrame& frame, SensorSample& out);

  void HashInto(StateHasher& hasher) const;

 private:
  GpsReading MakeGps(double time_s, const VehicleTruth& truth, const SensorFaultState& fault,
                     const common::LocalFrame& frame);
  BaroReading MakeBaro(double time_s, const VehicleTruth& truth, const SensorFaultState& fault);
  AttitudeReading MakeAttitude(double time_s, const VehicleTruth& truth,
                               const SensorFaultState& fault);
  BatteryReading MakeBattery(double time_s, const BatteryTruth& battery,
                             const SensorFaultState& fault);

  SensorParams params_;
  NoiseSource gps_noise_;
  NoiseSource baro_noise_;
  NoiseSource attitude_noise_;
  NoiseSource battery_noise_;
  RateAdapter gps_rate_;
  RateAdapter baro_rate_;
  RateAdapter attitude_rate_;
  RateAdapter battery_rate_;
  double gps_white_std_m_ = 0.0;
  double gps_vertical_white_std_m_ = 0.0;
  GaussMarkov gps_bias_east_;
  GaussMarkov gps_bias_north_;
  GaussMarkov gps_bias_up_;
  GaussMarkov baro_bias_;
  // The last value delivered (what a frozen sensor repeats) and the frozen copy.
  std::optional<GpsReading> last_gps_, frozen_gps_;
  std::optional<BaroReading> last_baro_, frozen_baro_;
  std::optional<AttitudeReading> last_attitude_, frozen_attitude_;
  std::optional<BatteryReading> last_battery_, frozen_battery_;
};

}  // namespace fireswarm::sim2d
