// The vehicle's construction, parameters and radio side. Behaviours and the
// control step are in vehicle_behaviour.cpp.
#include "fireswarm/agents/vehicle.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "fireswarm/common/angles.hpp"
#include "fireswarm/common/time.hpp"

namespace fireswarm::agents {

namespace {

// Below this the camera sees the launch pad, not the forest.
constexpr double kMinDetectionAltitudeM = 5.0;

radio::VehicleEndpointConfig EndpointConfig(const VehicleConfig& config) {
  radio::VehicleEndpointConfig endpoint = config.radio;
  endpoint.id = config.id;
  return endpoint;
}

ParamStore MakeParamStore(const VehicleConfig& config) {
  if (config.param_file.empty()) return ParamStore();
  return ParamStore(config.param_file, config.id);
}

PidGains GainsOf(const ParamStore& params, ParamId kp) {
  // Each PID's six parameters have consecutive IDs: kp, ki, kd, i, d, out limits.
  const auto base = static_cast<std::uint16_t>(kp);
  const auto get = [&](int offset) {
    return static_cast<double>(params.Get(static_cast<ParamId>(base + offset)));
  };
  PidGains gains;
  gains.kp = get(0);
  gains.ki = get(1);
  gains.kd = get(2);
  gains.i_limit = get(3);
  gains.d_limit = get(4);
  gains.out_limit = get(5);
  return gains;
}

}  // namespace

void VehicleConfig::Validate() const {
  if (id == 0 || id == 255) {
    throw std::invalid_argument("vehicle id: " + std::to_string(id) +
                                " is reserved (0 = server, 255 = broadcast); use 1..254");
  }
  if (!(navigation_hz > 0.0) || !std::isfinite(navigation_hz)) {
    throw std::invalid_argument("vehicle navigation_hz: must be a finite rate > 0");
  }
  if (!(telemetry_hz > 0.0) || !std::isfinite(telemetry_hz)) {
    throw std::invalid_argument("vehicle telemetry_hz: must be a finite rate > 0");
  }
}

Vehicle::Vehicle(const VehicleConfig& config)
    : config_((config.Validate(), config)),
      params_(MakeParamStore(config)),
      endpoint_(EndpointConfig(config), *this),
      detector_(config.detector.value_or(FireDetectorConfigFor(config.camera))) {
  if (config_.storage) Reload(*config_.storage);
  ApplyParams();
}

bool Vehicle::gps_lost() const {
  const Estimate& state = estimator_.estimate();
  return state.has_position && state.gps_age_s > kGpsLostAfterS;
}

void Vehicle::ApplyParams() {
  CascadeConfig cascade;
  cascade.roll = GainsOf(params_, ParamId::kRollKp);
  cascade.pitch = GainsOf(params_, ParamId::kPitchKp);
  cascade.heading = GainsOf(params_, ParamId::kHeadingKp);
  cascade.altitude = GainsOf(params_, ParamId::kAltitudeKp);
  cascade.roll_trim_rad = Param(ParamId::kRollTrimDeg) * common::kRadPerDeg;
  cascade.pitch_trim_rad = Param(ParamId::kPitchTrimDeg) * common::kRadPerDeg;
  cascade.max_tilt_rad = Param(ParamId::kMaxTiltDeg) * common::kRadPerDeg;
  cascade.max_climb_mps = Param(ParamId::kMaxClimbMps);
  cascade.max_yaw_rate_radps = Param(ParamId::kMaxYawRateDps) * common::kRadPerDeg;
  cascade_.Configure(cascade);

  NavigationConfig& nav = navigation_config_;
  nav.mode = Param(ParamId::kNavMode) < 0.5 ? NavigationMode::kSeed : NavigationMode::kTrack;
  nav.acceptance_radius_m = Param(ParamId::kAcceptanceRadiusM);
  nav.seed_pitch_deg = Param(ParamId::kSeedPitchDeg);
  nav.heading_tolerance_deg = Param(ParamId::kHeadingToleranceDeg);
  nav.cruise_speed_mps = Param(ParamId::kCruiseSpeedMps);
  nav.max_tilt_rad = cascade.max_tilt_rad;
  nav.speed = GainsOf(params_, ParamId::kSpeedKp);
  nav.cross_track = GainsOf(params_, ParamId::kCrossTrackKp);
  if (navigator_) navigator_->Configure(nav);

  LoiterConfig loiter;
  loiter.radial = nav.cross_track;
  loiter.speed = nav.speed;
  loiter.max_tilt_rad = cascade.max_tilt_rad;
  loiter_.Configure(loiter);
}

std::vector<radio::Burst> Vehicle::OnRadio(Nanos now, std::span<const std::uint8_t> bytes) {
  now_ = std::max(now_, now);
  const radio::VehicleEndpointStats before = endpoint_.stats();
  std::vector<radio::Burst> replies = endpoint_.OnReceive(now, bytes);
  const radio::VehicleEndpointStats& after = endpoint_.stats();
  // Bytes of frames for other vehicles only (most of a shared channel's) change
  // nothing a record keeps: only a frame for this one or for all is handled.
  if (after.frames_for_me == before.frames_for_me &&
      after.broadcast_frames == before.broadcast_frames) {
    return replies;
  }
  last_heard_ = now;
  link_lost_ = false;
  // Before the replies go out: what they carry (sequence numbers, reports) and
  // what the requests changed is stored by then.
  SaveEndpoint();
  SaveFlight();
  return replies;
}

radio::MissionAckStatus Vehicle::OnMissionChunk(const radio::MissionChunk& chunk) {
  const radio::MissionAckStatus status = missions_.OnChunk(chunk);
  // Each chunk is stored before it is acknowledged: a reboot mid-upload keeps
  // the chunks the server will not send again.
  if (config_.storage && status != radio::MissionAckStatus::kRejected) {
    config_.storage->WriteMissions(missions_);
  }
  return status;
}

radio::ParamValue Vehicle::OnParamRead(const radio::ParamRead& read) {
  return params_.Read(read.param_id);
}

radio::ParamValue Vehicle::OnParamWrite(const radio::ParamWrite& write) {
  radio::ParamValue value = params_.Write(write.param_id, write.value);
  if (value.status == radio::ParamStatus::kOk) {
    ApplyParams();
    if (config_.storage) config_.storage->WriteParam(write.param_id, value.value);
  }
  return value;
}

void Vehicle::ProcessFrame(Nanos now, const CameraFrame& frame) {
  const Estimate& state = estimator_.estimate();
  // Frames from the ground or without a position and attitude locate nothing;
  // nor do frames while the GPS is lost (the position is only a guess then).
  if (!Airborne() || !state.has_position || !state.has_attitude || gps_lost() ||
      state.altitude_m < kMinDetectionAltitudeM) {
    return;
  }
  // The pose only for frames that need one (most are plain ground).
  const auto pose_at_frame = [&] {
    ObserverPose pose;
    pose.position = estimator_.position();
    pose.altitude_m = state.altitude_m;
    pose.roll_rad = state.attitude.roll_rad;
    pose.pitch_rad = state.attitude.pitch_rad;
    pose.heading_rad = state.attitude.heading_rad;
    pose.camera = GeometryOf(config_.camera, Param(ParamId::kCameraPitchDeg));
    return pose;
  };
  ++stats_.frames_processed;
  for (const FireDetection& detection :
       detector_.Process(common::ToSeconds(now), frame, pose_at_frame)) {
    radio::FireReport report;
    report.time_ms = static_cast<std::uint32_t>(std::lround(detection.time_s * 1000.0));
    report.lat_deg = detection.position.lat_deg;
    report.lon_deg = detection.position.lon_deg;
    report.sigma_north_m = detection.sigma_north_m;
    report.sigma_east_m = detection.sigma_east_m;
    report.correlation = detection.correlation_ne;
    report.observer_lat_deg = detection.observer.lat_deg;
    report.observer_lon_deg = detection.observer.lon_deg;
    report.observer_altitude_m = detection.observer_altitude_m;
    report.pixel_count = static_cast<std::uint16_t>(std::min(detection.pixel_count, 65535));
    report.peak_temperature_c = detection.peak_temperature_c;
    report.confidence = detection.confidence;
    endpoint_.QueueFireReport(report);
    ++stats_.fires_detected;
  }
  SaveEndpoint();  // a queued report survives a reboot until it is acknowledged
}

void Vehicle::UpdateTelemetry(Nanos now) {
  const Estimate& state = estimator_.estimate();
  radio::Telemetry telemetry;
  telemetry.time_ms = static_cast<std::uint32_t>(
      std::chrono::duration_cast<std::chrono::milliseconds>(now).count());
  // Latitude and longitude wait for a reply that needs them (CompleteTelemetry).
  telemetry_local_.reset();
  if (state.has_position) telemetry_local_ = state.position_local;
  telemetry_position_.reset();
  telemetry.altitude_m = state.altitude_m;
  telemetry.velocity_north_mps = state.velocity_north_mps;
  telemetry.velocity_east_mps = state.velocity_east_mps;
  telemetry.climb_rate_mps = state.climb_rate_mps;
  telemetry.roll_deg = state.attitude.roll_rad / common::kRadPerDeg;
  telemetry.pitch_deg = state.attitude.pitch_rad / common::kRadPerDeg;
  telemetry.heading_deg = std::fmod(state.attitude.heading_rad / common::kRadPerDeg + 360.0, 360.0);
  telemetry.battery_v = state.battery_v;
  telemetry.battery_percent =
      static_cast<std::uint8_t>(std::lround(std::clamp(state.battery_fraction, 0.0, 1.0) * 100.0));
  telemetry.mode = mode_;
  std::uint8_t flags = 0;
  if (missions_.complete() != nullptr) flags |= radio::telemetry_flags::kMissionValid;
  if (low_battery_) flags |= radio::telemetry_flags::kLowBattery;
  if (link_lost_) flags |= radio::telemetry_flags::kLinkLost;
  if (state.has_position && !gps_lost()) flags |= radio::telemetry_flags::kGpsFix;
  telemetry.flags = flags;
  telemetry.mission_id = active_mission_;
  // The mission's waypoint, also while the navigator flies a hold, a circle or
  // the way back to the route.
  const bool on_route = mode_ == radio::FlightMode::kSearch && !rejoining_ && navigator_;
  telemetry.waypoint_index =
      static_cast<std::uint16_t>(on_route ? navigator_->waypoint_index() : resume_index_);
  endpoint_.SetTelemetry(telemetry);
}

void Vehicle::CompleteTelemetry(radio::Telemetry& telemetry) const {
  if (!telemetry_local_) return;  // no fix yet: 0, 0 as set
  if (!telemetry_position_) telemetry_position_ = estimator_.frame()->ToGeodetic(*telemetry_local_);
  telemetry.lat_deg = telemetry_position_->lat_deg;
  telemetry.lon_deg = telemetry_position_->lon_deg;
}

}  // namespace fireswarm::agents
