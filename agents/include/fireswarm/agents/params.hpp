// The vehicle's parameters: PID gains, trims, limits and behaviour settings that the
// operator reads and writes over the radio and the vehicle keeps across restarts
// (seed 3.3: the GCS config tab, the autopilot's EEPROM). radio::ParamTable()
// describes them; ParamStore holds the values and persists them to a JSON file.
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
#include "fireswarm/radio/params.hpp"

namespace fireswarm::agents {

// The catalogue is the protocol's (radio/params.hpp); the vehicle names it unqualified.
using radio::FindParam;
using radio::ParamId;
using radio::ParamSpec;
using radio::ParamTable;
using radio::SpecOf;

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
