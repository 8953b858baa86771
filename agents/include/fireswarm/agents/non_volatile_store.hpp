// What an autopilot keeps across a restart of its software (the seed's EEPROM, a
// flight controller's flash): its parameters, its missions, where it was in its
// flight, and its radio counters and unacknowledged fire reports. The vehicle
// writes each record when it changes and a restarted Vehicle reloads them all
// (docs/scenario.md, fault kind vehicle_reboot).
//
// Held in memory: the simulator's stand-in for the flash, owned by whoever owns
// the vehicle and handed to the next Vehicle after a reboot. ParamStore's JSON
// file remains the parameters' on-disk persistence for `fireswarm sim`.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>

#include "fireswarm/agents/mission_store.hpp"
#include "fireswarm/common/local_frame.hpp"
#include "fireswarm/radio/frame_security.hpp"
#include "fireswarm/radio/messages.hpp"
#include "fireswarm/radio/vehicle_endpoint.hpp"

namespace fireswarm::agents {

/// Where the vehicle is in its flight, as a restarted autopilot resumes it.
struct FlightRecord {
  radio::FlightMode mode = radio::FlightMode::kIdle;
  radio::FlightMode mode_before_hold = radio::FlightMode::kIdle;  ///< what a resume goes back to
  std::uint16_t active_mission = 0;                               ///< 0 = none
  /// The mission's waypoint it flies toward, or resumes at after a hold, an
  /// investigation or a return.
  std::size_t waypoint_index = 0;
  /// Where it left its route for a hold or an investigation (its way back).
  std::optional<common::LatLon> rejoin_at;
  std::optional<common::LatLon> home;  ///< where it took off
  /// The barometer's reading at take-off: altitudes are above it, m.
  std::optional<double> baro_zero_m;
  bool low_battery = false;  ///< a low battery sent it home: no new mission on this pack
  /// Every field equal (positions exactly).
  friend bool operator==(const FlightRecord& a, const FlightRecord& b);
};

/// The vehicle's non-volatile records. Each Write replaces its record whole (as a
/// flash page is rewritten); nothing is written that was not handed in.
class NonVolatileStore {
 public:
  /// A parameter accepted by ParamStore (wire ID, value held).
  void WriteParam(std::uint16_t id, float value);
  /// Every parameter written since the store was made, by wire ID.
  const std::map<std::uint16_t, float>& params() const { return params_; }

  /// The mission store after a chunk: its complete mission and the upload in
  /// progress (an autopilot writes each mission item as it arrives).
  void WriteMissions(const MissionStore& missions);
  const std::optional<MissionStore>& missions() const { return missions_; }

  void WriteFlight(const FlightRecord& flight);
  const FlightRecord& flight() const { return flight_; }

  /// The radio endpoint's counters, unacknowledged reports and last request.
  void WriteEndpoint(const radio::VehicleEndpointState& endpoint);
  const std::optional<radio::VehicleEndpointState>& endpoint() const { return endpoint_; }

  /// Secure mode: the frame counter's reserved range and the replay floors, as
  /// radio::PersistSecurityState hands them. Always succeeds (memory).
  bool WriteSecurity(const radio::SecurityState& security);
  const radio::SecurityState& security() const { return security_; }

  /// Writes since the store was made (every record).
  std::uint64_t writes() const { return writes_; }

 private:
  std::map<std::uint16_t, float> params_;
  std::optional<MissionStore> missions_;
  FlightRecord flight_;
  std::optional<radio::VehicleEndpointState> endpoint_;
  radio::SecurityState security_;
  std::uint64_t writes_ = 0;
};

}  // namespace fireswarm::agents
