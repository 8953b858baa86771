// The parameter catalogue: every vehicle parameter's wire ID, name, default,
// range and unit (seed 3.3: the GCS config tab). It is part of the protocol: the
// vehicle (agents::ParamStore) holds the values, the ground station reads and
// writes them by these IDs (ParamRead/ParamWrite) and knows their defaults.
#pragma once

#include <cstdint>
#include <span>
#include <string_view>

namespace fireswarm::radio {

/// Wire IDs of the parameters (ParamRead/ParamWrite param_id). Stable: an ID is
/// never reused for another meaning. Persisted files key values by name instead.
enum class ParamId : std::uint16_t {
  // PID sets: gains, symmetric I-term, D-term and output clamps (units in the table).
  kRollKp = 1,
  kRollKi = 2,
  kRollKd = 3,
  kRollILimit = 4,
  kRollDLimit = 5,
  kRollOutLimit = 6,
  kPitchKp = 11,
  kPitchKi = 12,
  kPitchKd = 13,
  kPitchILimit = 14,
  kPitchDLimit = 15,
  kPitchOutLimit = 16,
  kHeadingKp = 21,
  kHeadingKi = 22,
  kHeadingKd = 23,
  kHeadingILimit = 24,
  kHeadingDLimit = 25,
  kHeadingOutLimit = 26,
  kAltitudeKp = 31,
  kAltitudeKi = 32,
  kAltitudeKd = 33,
  kAltitudeILimit = 34,
  kAltitudeDLimit = 35,
  kAltitudeOutLimit = 36,
  kSpeedKp = 41,
  kSpeedKi = 42,
  kSpeedKd = 43,
  kSpeedILimit = 44,
  kSpeedDLimit = 45,
  kSpeedOutLimit = 46,
  kCrossTrackKp = 51,
  kCrossTrackKi = 52,
  kCrossTrackKd = 53,
  kCrossTrackILimit = 54,
  kCrossTrackDLimit = 55,
  kCrossTrackOutLimit = 56,
  // Trims and limits.
  kRollTrimDeg = 60,
  kPitchTrimDeg = 61,
  kMaxTiltDeg = 62,
  kMaxClimbMps = 63,
  kMaxYawRateDps = 64,
  // Navigation.
  kNavMode = 70,  ///< 0 = seed (turn, then pitch), 1 = track (cross-track hold)
  kAcceptanceRadiusM = 71,
  kSeedPitchDeg = 72,
  kHeadingToleranceDeg = 73,
  kCruiseSpeedMps = 74,
  kTakeoffAltitudeM = 75,
  // Camera.
  kCameraPitchDeg = 80,
  // Behaviour.
  kRtlBatteryFraction = 90,
  kLinkLostTimeoutS = 91,
  kLoiterRadiusM = 92,
  kLandDescentMps = 93,
  // Read-only.
  kFirmwareVersion = 100,
};

/// One parameter: its ID, dotted name ("pid.roll.kp"), default and inclusive range.
struct ParamSpec {
  ParamId id = ParamId::kRollKp;
  std::string_view name;
  float default_value = 0.0F;
  float min = 0.0F;
  float max = 0.0F;
  std::string_view unit;
  bool read_only = false;
  std::string_view description;  ///< one line
};

/// Every parameter, in ascending ID order.
std::span<const ParamSpec> ParamTable();
/// The spec of a wire ID; nullptr when no parameter has it.
const ParamSpec* FindParam(std::uint16_t id);
/// The spec of a dotted name; nullptr when no parameter has it.
const ParamSpec* FindParam(std::string_view name);
/// The spec of `id`. Throws std::invalid_argument for a value outside the enum.
const ParamSpec& SpecOf(ParamId id);

}  // namespace fireswarm::radio
