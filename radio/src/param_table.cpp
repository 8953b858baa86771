// The parameter table: every parameter's wire ID, name, default, range and unit.
// Ranges catch typing errors at the config tab, not tuning mistakes: a gain may be
// anything from 0 to well past any sane value; clamps stay within what the plant
// can do (tilt up to limit.max_tilt_deg's 45 deg ceiling, climb up to 8 m/s, yaw
// rate up to 360 deg/s).
#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>

#include "fireswarm/radio/params.hpp"

namespace fireswarm::radio {
namespace {

constexpr float kMaxGain = 10.0F;
constexpr float kMaxAngleRad = 0.8F;      // ~45 deg: roll, pitch and tilt clamps
constexpr float kMaxYawRateRadps = 6.3F;  // ~360 deg/s
constexpr float kMaxClimbMps = 8.0F;

constexpr ParamSpec Writable(ParamId id, std::string_view name, float default_value, float min,
                             float max, std::string_view unit, std::string_view description) {
  ParamSpec spec;
  spec.id = id;
  spec.name = name;
  spec.default_value = default_value;
  spec.min = min;
  spec.max = max;
  spec.unit = unit;
  spec.description = description;
  return spec;
}

constexpr ParamSpec ReadOnly(ParamId id, std::string_view name, float value,
                             std::string_view description) {
  ParamSpec spec = Writable(id, name, value, value, value, "", description);
  spec.read_only = true;
  return spec;
}

using P = ParamId;

constexpr std::array kTable{
    // Roll: roll command (rad) per rad of roll error.
    Writable(P::kRollKp, "pid.roll.kp", 1.0F, 0.0F, kMaxGain, "rad per rad", "roll P gain"),
    Writable(P::kRollKi, "pid.roll.ki", 0.5F, 0.0F, kMaxGain, "rad per rad*s", "roll I gain"),
    Writable(P::kRollKd, "pid.roll.kd", 0.02F, 0.0F, kMaxGain, "rad per rad/s", "roll D gain"),
    Writable(P::kRollILimit, "pid.roll.i_limit", 0.1F, 0.0F, kMaxAngleRad, "rad",
             "roll I-term clamp, symmetric"),
    Writable(P::kRollDLimit, "pid.roll.d_limit", 0.1F, 0.0F, kMaxAngleRad, "rad",
             "roll D-term clamp, symmetric"),
    Writable(P::kRollOutLimit, "pid.roll.out_limit", 0.15F, 0.0F, kMaxAngleRad, "rad",
             "roll output clamp, symmetric"),
    // Pitch: pitch command (rad) per rad of pitch error.
    Writable(P::kPitchKp, "pid.pitch.kp", 1.0F, 0.0F, kMaxGain, "rad per rad", "pitch P gain"),
    Writable(P::kPitchKi, "pid.pitch.ki", 0.5F, 0.0F, kMaxGain, "rad per rad*s", "pitch I gain"),
    Writable(P::kPitchKd, "pid.pitch.kd", 0.02F, 0.0F, kMaxGain, "rad per rad/s", "pitch D gain"),
    Writable(P::kPitchILimit, "pid.pitch.i_limit", 0.1F, 0.0F, kMaxAngleRad, "rad",
             "pitch I-term clamp, symmetric"),
    Writable(P::kPitchDLimit, "pid.pitch.d_limit", 0.1F, 0.0F, kMaxAngleRad, "rad",
             "pitch D-term clamp, symmetric"),
    Writable(P::kPitchOutLimit, "pid.pitch.out_limit", 0.15F, 0.0F, kMaxAngleRad, "rad",
             "pitch output clamp, symmetric"),
    // Heading: yaw rate command (rad/s) per rad of heading error.
    Writable(P::kHeadingKp, "pid.heading.kp", 1.5F, 0.0F, kMaxGain, "rad/s per rad",
             "heading P gain"),
    Writable(P::kHeadingKi, "pid.heading.ki", 0.0F, 0.0F, kMaxGain, "rad/s per rad*s",
             "heading I gain"),
    Writable(P::kHeadingKd, "pid.heading.kd", 0.0F, 0.0F, kMaxGain, "rad/s per rad/s",
             "heading D gain"),
    Writable(P::kHeadingILimit, "pid.heading.i_limit", 0.2F, 0.0F, kMaxYawRateRadps, "rad/s",
             "heading I-term clamp, symmetric"),
    Writable(P::kHeadingDLimit, "pid.heading.d_limit", 0.5F, 0.0F, kMaxYawRateRadps, "rad/s",
             "heading D-term clamp, symmetric"),
    Writable(P::kHeadingOutLimit, "pid.heading.out_limit", 1.5F, 0.0F, kMaxYawRateRadps, "rad/s",
             "heading output clamp, symmetric"),
    // Altitude: climb rate command (m/s) per m of altitude error.
    Writable(P::kAltitudeKp, "pid.altitude.kp", 0.8F, 0.0F, kMaxGain, "m/s per m",
             "altitude P gain"),
    Writable(P::kAltitudeKi, "pid.altitude.ki", 0.05F, 0.0F, kMaxGain, "m/s per m*s",
             "altitude I gain"),
    Writable(P::kAltitudeKd, "pid.altitude.kd", 0.0F, 0.0F, kMaxGain, "m/s per m/s",
             "altitude D gain"),
    Writable(P::kAltitudeILimit, "pid.altitude.i_limit", 0.5F, 0.0F, kMaxClimbMps, "m/s",
             "altitude I-term clamp, symmetric"),
    Writable(P::kAltitudeDLimit, "pid.altitude.d_limit", 1.0F, 0.0F, kMaxClimbMps, "m/s",
             "altitude D-term clamp, symmetric"),
    Writable(P::kAltitudeOutLimit, "pid.altitude.out_limit", 3.0F, 0.0F, kMaxClimbMps, "m/s",
             "altitude output clamp, symmetric"),
    // Speed: pitch command (rad) per m/s of along-track speed error.
    Writable(P::kSpeedKp, "pid.speed.kp", 0.12F, 0.0F, kMaxGain, "rad per m/s", "speed P gain"),
    Writable(P::kSpeedKi, "pid.speed.ki", 0.02F, 0.0F, kMaxGain, "rad per m", "speed I gain"),
    Writable(P::kSpeedKd, "pid.speed.kd", 0.0F, 0.0F, kMaxGain, "rad per m/s^2", "speed D gain"),
    Writable(P::kSpeedILimit, "pid.speed.i_limit", 0.1F, 0.0F, kMaxAngleRad, "rad",
             "speed I-term clamp, symmetric"),
    Writable(P::kSpeedDLimit, "pid.speed.d_limit", 0.1F, 0.0F, kMaxAngleRad, "rad",
             "speed D-term clamp, symmetric"),
    Writable(P::kSpeedOutLimit, "pid.speed.out_limit", 0.35F, 0.0F, kMaxAngleRad, "rad",
             "speed output clamp, symmetric"),
    // Cross-track: roll command (rad) per m of cross-track error.
    Writable(P::kCrossTrackKp, "pid.cross_track.kp", 0.1F, 0.0F, kMaxGain, "rad per m",
             "cross-track P gain"),
    Writable(P::kCrossTrackKi, "pid.cross_track.ki", 0.02F, 0.0F, kMaxGain, "rad per m*s",
             "cross-track I gain"),
    Writable(P::kCrossTrackKd, "pid.cross_track.kd", 0.12F, 0.0F, kMaxGain, "rad per m/s",
             "cross-track D gain"),
    Writable(P::kCrossTrackILimit, "pid.cross_track.i_limit", 0.4F, 0.0F, kMaxAngleRad, "rad",
             "cross-track I-term clamp, symmetric"),
    Writable(P::kCrossTrackDLimit, "pid.cross_track.d_limit", 0.2F, 0.0F, kMaxAngleRad, "rad",
             "cross-track D-term clamp, symmetric"),
    Writable(P::kCrossTrackOutLimit, "pid.cross_track.out_limit", 0.35F, 0.0F, kMaxAngleRad, "rad",
             "cross-track output clamp, symmetric"),
    // Trims and limits.
    Writable(P::kRollTrimDeg, "trim.roll_deg", 0.0F, -10.0F, 10.0F, "deg",
             "added to every roll command"),
    Writable(P::kPitchTrimDeg, "trim.pitch_deg", 0.0F, -10.0F, 10.0F, "deg",
             "added to every pitch command"),
    Writable(P::kMaxTiltDeg, "limit.max_tilt_deg", 25.0F, 5.0F, 45.0F, "deg",
             "largest roll or pitch command"),
    Writable(P::kMaxClimbMps, "limit.max_climb_mps", 3.0F, 0.5F, 8.0F, "m/s",
             "largest climb or descent rate command"),
    Writable(P::kMaxYawRateDps, "limit.max_yaw_rate_dps", 90.0F, 10.0F, 360.0F, "deg/s",
             "largest yaw rate command"),
    // Navigation (seed chapter 6).
    Writable(P::kNavMode, "nav.mode", 1.0F, 0.0F, 1.0F, "",
             "0 = seed (turn, then pitch), 1 = track (hold cross-track error)"),
    Writable(P::kAcceptanceRadiusM, "nav.acceptance_radius_m", 10.0F, 1.0F, 100.0F, "m",
             "a waypoint this close counts as reached"),
    Writable(P::kSeedPitchDeg, "nav.seed_pitch_deg", 15.0F, 1.0F, 35.0F, "deg",
             "seed mode: forward pitch once the heading is on target"),
    Writable(P::kHeadingToleranceDeg, "nav.heading_tolerance_deg", 5.0F, 1.0F, 45.0F, "deg",
             "seed mode: heading error below which the vehicle pitches forward"),
    Writable(P::kCruiseSpeedMps, "nav.cruise_speed_mps", 8.0F, 1.0F, 20.0F, "m/s",
             "track mode: ground speed when a waypoint gives none"),
    Writable(P::kTakeoffAltitudeM, "nav.takeoff_altitude_m", 60.0F, 5.0F, 400.0F, "m",
             "climb to this altitude above launch before the mission"),
    // Camera.
    Writable(P::kCameraPitchDeg, "camera.pitch_deg", -90.0F, -90.0F, 0.0F, "deg",
             "camera mount pitch, -90 = nadir"),
    // Behaviour.
    Writable(P::kRtlBatteryFraction, "safety.rtl_battery_fraction", 0.25F, 0.05F, 0.9F, "1",
             "return to launch when the battery falls below this fraction"),
    Writable(P::kLinkLostTimeoutS, "safety.link_lost_timeout_s", 30.0F, 2.0F, 600.0F, "s",
             "return to launch after the server is not heard for this long"),
    Writable(P::kLoiterRadiusM, "investigate.radius_m", 20.0F, 5.0F, 500.0F, "m",
             "loiter radius around a fire when the command gives none"),
    Writable(P::kLandDescentMps, "safety.land_descent_mps", 1.0F, 0.2F, 3.0F, "m/s",
             "descent rate when landing"),
    // Read-only.
    ReadOnly(P::kFirmwareVersion, "sys.firmware_version", 1.0F, "parameter table version"),
};

constexpr bool SortedById() {
  for (std::size_t i = 1; i < kTable.size(); ++i) {
    if (kTable[i - 1].id >= kTable[i].id) return false;
  }
  return true;
}
static_assert(SortedById(), "FindParam(id) searches the table by ID");

}  // namespace

std::span<const ParamSpec> ParamTable() {
  return kTable;
}

const ParamSpec* FindParam(std::uint16_t id) {
  const auto it = std::lower_bound(kTable.begin(), kTable.end(), id,
                                   [](const ParamSpec& spec, std::uint16_t key) {
                                     return static_cast<std::uint16_t>(spec.id) < key;
                                   });
  return it != kTable.end() && static_cast<std::uint16_t>(it->id) == id ? &*it : nullptr;
}

const ParamSpec* FindParam(std::string_view name) {
  const auto it = std::find_if(kTable.begin(), kTable.end(),
                               [name](const ParamSpec& spec) { return spec.name == name; });
  return it != kTable.end() ? &*it : nullptr;
}

const ParamSpec& SpecOf(ParamId id) {
  const ParamSpec* spec = FindParam(static_cast<std::uint16_t>(id));
  if (spec == nullptr) {
    throw std::invalid_argument("no parameter has ID " +
                                std::to_string(static_cast<std::uint16_t>(id)));
  }
  return *spec;
}

}  // namespace fireswarm::radio
