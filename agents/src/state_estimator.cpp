#include "fireswarm/agents/state_estimator.hpp"

#include "fireswarm/common/time.hpp"

namespace fireswarm::agents {

namespace {
// The climb rate is the barometer's altitude differenced and smoothed with this
// time constant: it is for telemetry, not for control.
constexpr double kClimbRateTimeConstantS = 1.0;
// A complementary filter: the position integrates the GPS velocity (0.05 m/s
// noise) and moves this fraction of the way to each fix. At 10 Hz fixes that is a
// 1 s time constant: the fixes' white noise shrinks to about a fifth, while their
// slowly wandering bias passes through (nothing on board can see it).
constexpr double kGpsBlend = 0.1;
}  // namespace

void StateEstimator::Update(Nanos now, const SensorInputs& inputs) {
  const double dt_s = last_update_ ? common::ToSeconds(now - *last_update_) : 0.0;
  last_update_ = now;

  // Carry the position forward with the velocity, then pull it toward a new fix.
  // The velocity is the last fix's: without fixes it goes stale, and the vehicle
  // (which levels off when its GPS is lost) soon stops moving that way.
  const bool velocity_known =
      last_fix_ && common::ToSeconds(now - *last_fix_) <= kMaxDeadReckoningS;
  if (estimate_.has_position && dt_s > 0.0 && velocity_known) {
    estimate_.position_local.east_m += estimate_.velocity_east_mps * dt_s;
    estimate_.position_local.north_m += estimate_.velocity_north_mps * dt_s;
  }
  if (inputs.gps) {
    const GpsInput& gps = *inputs.gps;
    if (!frame_) frame_.emplace(common::LatLon{gps.lat_deg, gps.lon_deg});
    const common::EastNorth fix = frame_->ToLocal({gps.lat_deg, gps.lon_deg});
    // The first fix, or the first after a loss: the estimate carried on without
    // fixes is worth less than the fix itself.
    if (!estimate_.has_position || !velocity_known) {
      estimate_.position_local = fix;
    } else {
      estimate_.position_local.east_m += kGpsBlend * (fix.east_m - estimate_.position_local.east_m);
      estimate_.position_local.north_m +=
          kGpsBlend * (fix.north_m - estimate_.position_local.north_m);
    }
    estimate_.has_position = true;
    estimate_.velocity_east_mps = gps.velocity_east_mps;
    estimate_.velocity_north_mps = gps.velocity_north_mps;
    last_fix_ = now;
  }
  position_.reset();
  estimate_.gps_age_s = last_fix_ ? common::ToSeconds(now - *last_fix_) : 0.0;

  if (inputs.baro) {
    const double raw = inputs.baro->altitude_m;
    if (!baro_zeroed_) {
      baro_zero_m_ = raw;  // until told, the first reading is the ground
      baro_zeroed_ = true;
    }
    const double altitude = raw - baro_zero_m_;
    if (baro_raw_m_ && baro_time_ && now > *baro_time_) {
      const double baro_dt_s = common::ToSeconds(now - *baro_time_);
      const double rate = (raw - *baro_raw_m_) / baro_dt_s;
      const double blend = baro_dt_s / (kClimbRateTimeConstantS + baro_dt_s);
      estimate_.climb_rate_mps += blend * (rate - estimate_.climb_rate_mps);
    }
    baro_raw_m_ = raw;
    baro_time_ = now;
    estimate_.has_altitude = true;
    estimate_.altitude_m = altitude;
  }
  if (inputs.attitude) {
    estimate_.has_attitude = true;
    estimate_.attitude = *inputs.attitude;
  }
  if (inputs.battery) {
    estimate_.battery_v = inputs.battery->voltage_v;
    estimate_.battery_fraction = inputs.battery->fraction;
  }
}

common::LatLon StateEstimator::position() const {
  if (!estimate_.has_position) return {};
  if (!position_) position_ = frame_->ToGeodetic(estimate_.position_local);
  return *position_;
}

void StateEstimator::RestoreAltitudeZero(double baro_zero_m) {
  baro_zero_m_ = baro_zero_m;
  baro_zeroed_ = true;
  if (baro_raw_m_) estimate_.altitude_m = *baro_raw_m_ - baro_zero_m_;
}

void StateEstimator::ZeroAltitude() {
  if (!baro_raw_m_) return;
  baro_zero_m_ = *baro_raw_m_;
  baro_zeroed_ = true;
  estimate_.altitude_m = 0.0;
}

}  // namespace fireswarm::agents
