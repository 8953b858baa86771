// The vehicle's parameters: PID gains, trims, limits and behaviour settings that the
// operator reads and writes over the radio and the vehicle keeps across restarts
// (seed 3.3: the GCS config tab, the autopilot's EEPROM). ParamTable() describes
// them; ParamStore holds the values and persists them to a JSON file.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "fireswarm/radio/messages.hpp"

namespace fireswarm::agents {

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

/// The vehicle's parameter values (wire type float), checked against the table and,
/// when a file is given, persisted to it after every accepted write.
///
/// File format (JSON, keyed by name so renumbering IDs never scrambles a file):
///   {"format": "fireswarm-params", "version": 1, "vehicle": 7,
///    "params": {"pid.roll.kp": 1.0, ...}}
/// Every writable parameter is written; read-only ones belong to the firmware and
/// are neither written nor read. Names the firmware does not know (a file from a
/// newer or older firmware) are kept and written back unchanged, so going back and
/// forth between firmware versions loses no setting; names missing from the file
/// take their defaults.
///
/// Persistence is atomic: a temporary file in the same directory is written, flushed
/// to disk and renamed over the file, so a crash leaves the old or the new file,
/// never a mix. A failed persist (directory gone, disk full) is not thrown from
/// Write(), which serves radio callbacks: the value is held and used, Write()
/// returns kOk, and persist_errors() / last_persist_error() report it; the next
/// accepted write tries again with the whole table.
class ParamStore {
 public:
  /// Loads `file` when it exists (a missing file means defaults; it is created, with
  /// its parent directory required to exist, at the first accepted write). An empty
  /// path keeps the parameters in memory only. `vehicle` is this vehicle's receiver
  /// ID, written to the file; when it is not 0 a file written for another vehicle is
  /// refused (0 accepts any and keeps the file's). Throws std::runtime_error naming
  /// the file and the key when the file cannot be read or is corrupt (not JSON, wrong
  /// format tag or version, another vehicle's, a value not a number or outside its
  /// range); the file is left untouched.
  explicit ParamStore(std::filesystem::path file = {}, std::uint8_t vehicle = 0);

  /// The value held for `id`. Throws std::invalid_argument for a value outside the enum.
  float Get(ParamId id) const;

  /// The value held for wire ID `id`: status kOk, or kUnknownParam (value 0).
  /// param_id is set; the header is left default. Never throws.
  radio::ParamValue Read(std::uint16_t id) const;

  /// Sets wire ID `id` to `value` and persists it. Status: kUnknownParam (value 0),
  /// kReadOnly, kOutOfRange (NaN, infinite or outside [min, max]; the value held is
  /// unchanged), or kOk. The returned value is the one held afterwards; param_id is
  /// set, the header left default. Never throws.
  radio::ParamValue Write(std::uint16_t id, float value);

  const std::filesystem::path& file() const { return file_; }
  /// Persists that failed since construction.
  std::uint64_t persist_errors() const { return persist_errors_; }
  /// What the latest failed persist reported; empty when none failed.
  const std::string& last_persist_error() const { return last_persist_error_; }
  /// Names in the loaded file that no parameter has, kept for writing back.
  std::size_t unknown_names() const { return unknown_.size(); }

 private:
  void Load();
  void Persist();

  std::filesystem::path file_;
  std::uint8_t vehicle_ = 0;
  std::vector<float> values_;                   // by position in ParamTable()
  std::map<std::string, std::string> unknown_;  // name -> JSON text, not in the table
  std::uint64_t persist_errors_ = 0;
  std::string last_persist_error_;
};

}  // namespace fireswarm::agents
