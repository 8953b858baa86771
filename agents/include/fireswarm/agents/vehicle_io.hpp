// What a vehicle reads and writes each step: the seed's HIL "FlightData" idea.
// The simulator bridge (hil/) or real drivers fill SensorInputs; ActuatorOutputs
// go to the plant's attitude/climb interface. Angles follow FRD/NED: roll right
// positive, pitch nose-up positive (forward flight is negative pitch), heading
// clockwise from true north.
#pragma once

#include <cstdint>
#include <optional>
#include <span>

namespace fireswarm::agents {

struct GpsInput {
  double lat_deg = 0.0;
  double lon_deg = 0.0;
  double altitude_m = 0.0;  ///< above the (flat) launch ground
  double velocity_north_mps = 0.0;
  double velocity_east_mps = 0.0;
};

struct BaroInput {
  double altitude_m = 0.0;  ///< uncalibrated: the vehicle zeroes it on the ground
};

struct AttitudeInput {
  double roll_rad = 0.0;
  double pitch_rad = 0.0;
  double heading_rad = 0.0;  ///< clockwise from north, [0, 2 pi)
  double roll_rate_radps = 0.0;
  double pitch_rate_radps = 0.0;
  double yaw_rate_radps = 0.0;
};

struct BatteryInput {
  double voltage_v = 0.0;
  double fraction = 1.0;  ///< fuel gauge, 0..1
};

/// One white-hot thermal frame (row-major, row 0 at the top; for a nadir camera
/// the top is the vehicle's forward direction and columns grow to its right).
/// Grey g stands for range_min_c + g / 255 * (range_max_c - range_min_c): a
/// radiometric camera reports the range of its mapping with every frame.
struct CameraFrame {
  int width_px = 0;
  int height_px = 0;
  std::span<const std::uint8_t> pixels;
  double range_min_c = 0.0;
  double range_max_c = 0.0;
};

/// The sensor samples of one step: a field is set only when that sensor delivered.
struct SensorInputs {
  std::optional<GpsInput> gps;
  std::optional<BaroInput> baro;
  std::optional<AttitudeInput> attitude;
  std::optional<BatteryInput> battery;
  const CameraFrame* frame = nullptr;  ///< a new camera frame, valid during the call
};

/// Attitude and climb commands: the plant's stabilised interface.
struct ActuatorOutputs {
  double roll_rad = 0.0;
  double pitch_rad = 0.0;
  double yaw_rate_radps = 0.0;
  double climb_rate_mps = 0.0;  ///< positive up
  bool armed = false;
};

}  // namespace fireswarm::agents
