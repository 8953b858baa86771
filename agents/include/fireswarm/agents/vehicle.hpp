// One APOne vehicle (seed chapters 6 and 7) as software: the state estimate, the
// control cascade and navigation, the mission store, the parameters (the seed's
// EEPROM), the fire detector and geolocation, and the behaviours (take-off,
// search, hold, investigate, return to launch, land). It talks to the server only
// through APOne frames: bytes in through OnRadio(), bursts out for its link. It
// knows nothing of the simulator: sensors and the camera come in as SensorInputs,
// commands go out as ActuatorOutputs (the seed's HIL FlightData idea), so the same
// class flies a simulated plant in-process or behind a serial or UDP link.
//
// A pure core: both calls take the time; no clock, no socket. The only I/O is the
// parameter file, written when a parameter changes.
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "fireswarm/agents/control_cascade.hpp"
#include "fireswarm/agents/fire_detector.hpp"
#include "fireswarm/agents/loiter.hpp"
#include "fireswarm/agents/mission_store.hpp"
#include "fireswarm/agents/navigation.hpp"
#include "fireswarm/agents/non_volatile_store.hpp"
#include "fireswarm/agents/params.hpp"
#include "fireswarm/agents/state_estimator.hpp"
#include "fireswarm/agents/vehicle_io.hpp"
#include "fireswarm/common/camera_model.hpp"
#include "fireswarm/common/time.hpp"
#include "fireswarm/radio/vehicle_endpoint.hpp"

namespace fireswarm::agents {

struct VehicleConfig {
  std::uint8_t id = 1;  ///< receiver ID, 1..254 (overrides radio.id)
  radio::VehicleEndpointConfig radio;
  /// The parameter file (the seed's EEPROM); empty keeps parameters in memory only.
  std::filesystem::path param_file;
  /// What survives a restart of the vehicle's software: parameters, missions,
  /// where it was in its flight, radio counters and unacknowledged reports. A
  /// Vehicle made with a store that holds records resumes from them (a reboot);
  /// null keeps nothing. Shared so the owner can hand it to the next Vehicle.
  /// In secure mode the owner also persists radio.security through it
  /// (NonVolatileStore::WriteSecurity).
  std::shared_ptr<NonVolatileStore> storage;
  /// The thermal camera carried; its mount pitch is the parameter camera.pitch_deg.
  common::CameraModel camera = common::CameraModelByName("seed");
  /// Detector tuning; nullopt takes FireDetectorConfigFor(camera).
  std::optional<FireDetectorConfig> detector;
  double navigation_hz = 10.0;  ///< the outer loop's rate (the GPS rate)
  double telemetry_hz = 10.0;   ///< how often the telemetry answer is refreshed
  /// Throws std::invalid_argument naming the field when a value is out of range.
  void Validate() const;
};

/// Counts of what the vehicle did, for tests and figures.
struct VehicleStats {
  std::uint64_t frames_processed = 0;
  std::uint64_t fires_detected = 0;  ///< reports queued for the server
  std::uint64_t commands_accepted = 0;
  std::uint64_t commands_rejected = 0;
  std::uint64_t link_lost_returns = 0;
  std::uint64_t low_battery_returns = 0;
  std::uint64_t avoid_orders = 0;       ///< the server's avoid orders taken
  std::uint64_t gps_lost_landings = 0;  ///< landed where it was: no GPS for kGpsLostLandAfterS
};

/// No GPS fix for this long and the vehicle has lost its GPS, s: it levels off
/// and holds its altitude (drifting with the wind), geolocates nothing and
/// reports no fix, until fixes come back (ten fixes at the seed's 10 Hz).
inline constexpr double kGpsLostAfterS = kMaxDeadReckoningS;
/// No GPS fix for this long in the air and the vehicle lands where it is, s.
inline constexpr double kGpsLostLandAfterS = 30.0;

class Vehicle final : public radio::VehicleRequestHandler {
 public:
  /// Loads the parameter file if it exists, then what config.storage holds (a
  /// reboot): parameters, missions, radio counters and unacknowledged reports at
  /// once; its flight (mode, mission, waypoint, home, altitude zero) at its first
  /// step with a position, an attitude and an altitude: until then, in the air,
  /// it flies level at zero climb rate. Throws std::invalid_argument for a bad
  /// configuration, std::runtime_error naming the file when it is corrupt.
  explicit Vehicle(const VehicleConfig& config);

  /// Bytes heard on the radio up to `now`; returns the replies to transmit. Hearing
  /// any valid frame for this vehicle or for all resets the link-lost timer.
  std::vector<radio::Burst> OnRadio(Nanos now, std::span<const std::uint8_t> bytes);

  /// One control step at `now` with this step's sensor samples (and camera frame).
  ActuatorOutputs Step(Nanos now, const SensorInputs& inputs);

  // VehicleRequestHandler: the server's requests, decoded by the endpoint.
  radio::CommandResult OnCommand(const radio::Command& command) override;
  radio::MissionAckStatus OnMissionChunk(const radio::MissionChunk& chunk) override;
  radio::ParamValue OnParamRead(const radio::ParamRead& read) override;
  radio::ParamValue OnParamWrite(const radio::ParamWrite& write) override;
  void CompleteTelemetry(radio::Telemetry& telemetry) const override;

  std::uint8_t id() const { return config_.id; }
  radio::FlightMode mode() const { return mode_; }
  const Estimate& estimate() const { return estimator_.estimate(); }
  /// Navigation, once the first GPS fix has set the local frame.
  const Navigator* navigator() const { return navigator_ ? &*navigator_ : nullptr; }
  const Loiter& loiter() const { return loiter_; }
  /// The outer loop's latest set-points (navigation or loiter).
  const NavigationSetpoint& navigation_setpoint() const { return navigation_setpoint_; }
  /// The latest commands to the plant.
  const ActuatorOutputs& outputs() const { return outputs_; }
  const ParamStore& params() const { return params_; }
  const MissionStore& missions() const { return missions_; }
  const FireDetector& detector() const { return detector_; }
  const radio::VehicleEndpoint& endpoint() const { return endpoint_; }
  const VehicleStats& stats() const { return stats_; }
  /// The mission being flown (0 = none).
  std::uint16_t active_mission() const { return active_mission_; }
  /// Home: where the vehicle took off (unset before the first take-off).
  const std::optional<common::LatLon>& home() const { return home_; }
  /// True while its GPS is lost (no fix for kGpsLostAfterS after a first one).
  bool gps_lost() const;
  /// True from a reboot until its stored flight is resumed.
  bool resuming() const { return resume_.has_value(); }
  /// Its flight as it would be stored now (what config.storage holds after a step).
  FlightRecord flight_record() const;

 private:
  void ApplyParams();
  void Reload(const NonVolatileStore& storage);
  /// Resumes the stored flight once the estimate allows; false while it waits.
  bool ResumeFlight(Nanos now);
  void SaveFlight();
  void SaveEndpoint();
  void EnterMode(radio::FlightMode mode, Nanos now);
  void StartRoute(std::vector<RoutePoint> route, std::size_t start_index);
  void HoldHere(double altitude_m);
  /// The take-off's target: the active mission's first waypoint altitude (its
  /// layer), or the take-off altitude parameter when it gives none, m.
  double ClimbOutAltitudeM() const;
  /// The way home's speed: the active mission's, at the waypoint it left it (the
  /// speed the search was planned and flown at), or 0 (the cruise speed
  /// parameter) without a mission or a speed in it, m/s.
  double ReturnSpeedMps() const;
  /// The way home's altitude: the active mission's last waypoint's (the sortie's
  /// way home, at the layer the server gave it: airspace.hpp), so a vehicle going
  /// home by itself (low battery, lost link) flies the layer the server predicts;
  /// without a mission, the altitude it was flying to. Never below the take-off
  /// altitude, m.
  double ReturnAltitudeM() const;
  /// Applies a standing avoid order (CommandType::kAvoid) to `setpoint`.
  void ApplyAvoid(Nanos now, CascadeSetpoint& setpoint);
  CascadeSetpoint Behave(Nanos now, std::optional<common::Micros> nav_dt);
  double Param(ParamId id) const { return static_cast<double>(params_.Get(id)); }
  void CheckSafety(Nanos now);
  void ProcessFrame(Nanos now, const CameraFrame& frame);
  void UpdateTelemetry(Nanos now);
  bool Airborne() const;
  NavigationInput NavInput() const;

  VehicleConfig config_;
  ParamStore params_;
  MissionStore missions_;
  radio::VehicleEndpoint endpoint_;
  StateEstimator estimator_;
  ControlCascade cascade_;
  std::optional<Navigator> navigator_;
  NavigationConfig navigation_config_;
  Loiter loiter_;
  FireDetector detector_;
  VehicleStats stats_;

  radio::FlightMode mode_ = radio::FlightMode::kIdle;
  radio::FlightMode mode_before_hold_ = radio::FlightMode::kIdle;
  Nanos now_{0};
  Nanos mode_since_{0};
  std::optional<Nanos> last_heard_;
  std::optional<Nanos> last_navigation_;
  std::optional<Nanos> last_telemetry_;
  /// The position of the latest telemetry update, in the estimator's frame (none
  /// before the first fix), and as latitude and longitude once a reply asked.
  std::optional<common::EastNorth> telemetry_local_;
  mutable std::optional<common::LatLon> telemetry_position_;
  std::optional<Nanos> investigate_until_;
  bool investigate_approach_ = false;  ///< investigating, still on the way to the circle
  NavigationSetpoint navigation_setpoint_;
  ActuatorOutputs outputs_;
  std::optional<common::LatLon> home_;
  std::uint16_t active_mission_ = 0;
  std::size_t resume_index_ = 0;  ///< search waypoint to go back to after hold/investigate
  /// Where it left the search route for a hold or an investigation: the search
  /// flies back there first (rejoining_) and then on toward resume_index_.
  std::optional<common::LatLon> rejoin_at_;
  bool rejoining_ = false;
  double land_low_altitude_m_ = 0.0;  ///< lowest altitude seen while landing
  Nanos land_progress_at_{0};         ///< when it last fell kLandProgressM lower
  bool link_lost_ = false;
  bool low_battery_ = false;
  /// The server's avoid order: fly at this altitude until avoid_until_, whatever
  /// the mode says (a landing waits level meanwhile).
  std::optional<double> avoid_altitude_m_;
  Nanos avoid_until_{0};
  /// After a reboot: the stored flight, resumed at the first step that can.
  std::optional<FlightRecord> resume_;
  std::uint64_t endpoint_saved_at_ = 0;  ///< endpoint_.state_changes() at the last save
};

}  // namespace fireswarm::agents
