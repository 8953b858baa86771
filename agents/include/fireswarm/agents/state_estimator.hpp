// The vehicle's own idea of where it is, from its sensors only: position from GPS
// fixes blended with the integrated GPS velocity (a complementary filter); altitude from the
// barometer, zeroed on the ground before take-off (the BMP280 reads pressure altitude, not height
// above the launch site); attitude and battery as measured.
#pragma once

#include <optional>

#include "fireswarm/agents/vehicle_io.hpp"
#include "fireswarm/common/local_frame.hpp"
#include "fireswarm/common/time.hpp"

namespace fireswarm::agents {

using common::Nanos;

struct Estimate {
  bool has_position = false;  ///< a GPS fix has arrived
  /// Dead-reckoned to the last Update, in frame(); StateEstimator::position()
  /// gives it as latitude and longitude.
  common::EastNorth position_local;
  double velocity_east_mps = 0.0;
  double velocity_north_mps = 0.0;
  bool has_altitude = false;
  double altitude_m = 0.0;  ///< above the ground where ZeroAltitude() was called
  double climb_rate_mps = 0.0;
  bool has_attitude = false;
  AttitudeInput attitude;
  double battery_v = 0.0;
  double battery_fraction = 1.0;
  double gps_age_s = 0.0;  ///< since the last fix
};

/// How long after its last GPS fix the estimate still moves the position with
/// that fix's velocity, s (ten fixes at the seed's 10 Hz).
inline constexpr double kMaxDeadReckoningS = 1.0;

class StateEstimator {
 public:
  /// Folds in this step's samples. The local frame is set on the first GPS fix
  /// (its origin there), so the vehicle needs no configured origin. Without fixes
  /// the position is carried on with the last fix's velocity for at most
  /// kMaxDeadReckoningS, then held (the velocity is no longer known).
  void Update(Nanos now, const SensorInputs& inputs);
  /// Takes the current barometric altitude as zero (on the ground, before take-off).
  void ZeroAltitude();
  /// The barometer reading altitudes are measured from, m; nullopt before the
  /// first reading.
  std::optional<double> altitude_zero_m() const {
    return baro_zeroed_ ? std::optional<double>(baro_zero_m_) : std::nullopt;
  }
  /// Measures altitudes from `baro_zero_m` (a restart in the air: the zero taken
  /// on the ground before take-off, kept in non-volatile storage).
  void RestoreAltitudeZero(double baro_zero_m);

  const Estimate& estimate() const { return estimate_; }
  /// estimate().position_local as WGS84 latitude and longitude (0, 0 before the
  /// first fix). Converted on demand and kept until the next Update: the
  /// projection costs more than the rest of an update, and the vehicle reads
  /// latitude and longitude only at its navigation and telemetry rates.
  common::LatLon position() const;
  /// Set after the first GPS fix; positions in Estimate are in this frame.
  const std::optional<common::LocalFrame>& frame() const { return frame_; }

 private:
  Estimate estimate_;
  mutable std::optional<common::LatLon> position_;  // position() since the last Update
  std::optional<common::LocalFrame> frame_;
  std::optional<Nanos> last_update_;
  std::optional<Nanos> last_fix_;
  std::optional<double> baro_raw_m_;
  std::optional<Nanos> baro_time_;
  double baro_zero_m_ = 0.0;
  bool baro_zeroed_ = false;
};

}  // namespace fireswarm::agents
