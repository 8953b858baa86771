// Test scenes for the detector: a sim2d fire grid and temperature field, a
// geodetic frame over sim2d's local ENU, and the conversions from sim2d's
// camera images and vehicle truth to the vehicle's inputs (the job hil/ does
// in flight).
#pragma once

#include <utility>
#include <vector>

#include "fireswarm/agents/geolocation.hpp"
#include "fireswarm/agents/vehicle_io.hpp"
#include "fireswarm/common/angles.hpp"
#include "fireswarm/common/local_frame.hpp"
#include "fireswarm/hil/sim_bridge.hpp"
#include "fireswarm/sim2d/fire_grid.hpp"
#include "fireswarm/sim2d/temperature_field.hpp"
#include "fireswarm/sim2d/thermal_camera.hpp"

namespace fireswarm::agents::testing {

inline constexpr double kDeg = common::kRadPerDeg;

/// No wind and no jitter: a fire spreads as a (grid) disc about its ignition.
inline sim2d::FireConfig StillAirFire() {
  sim2d::FireConfig config;
  config.wind_speed_mps = 0.0;
  config.jitter_fraction = 0.0;
  return config;
}

/// A 1 km square of forest (origin at the south-west corner), its temperature
/// field, and the WGS84 frame the vehicle sees it through. Not movable: the
/// field refers to the grid.
struct ThermalScene {
  explicit ThermalScene(std::vector<sim2d::Distractor> distractors = {},
                        sim2d::FireConfig config = StillAirFire())
      : fire(config, sim2d::MakeRng(7, "fire")), field(fire, std::move(distractors)) {}
  ThermalScene(const ThermalScene&) = delete;
  ThermalScene& operator=(const ThermalScene&) = delete;

  sim2d::FireGrid fire;
  sim2d::TemperatureField field;
  common::LocalFrame geo{common::LatLon{45.0, 7.0}};

  sim2d::Vec2 Local(common::LatLon point) const {
    const common::EastNorth local = geo.ToLocal(point);
    return {local.east_m, local.north_m};
  }
};

/// Ignites the cell at (500, 500) and burns it for a second: one hot cell. Its centre.
inline sim2d::Vec2 LightOneCell(ThermalScene& scene) {
  scene.fire.AddIgnition({sim2d::Vec2(500.0, 500.0), 0.0});
  scene.fire.AdvanceTo(1.0);
  return scene.fire.CellCenter(*scene.fire.CellAt({500.0, 500.0}));
}

inline sim2d::VehicleTruth Flying(sim2d::Vec2 position_m, double altitude_m,
                                  double heading_deg = 0.0, double pitch_deg = 0.0,
                                  double roll_deg = 0.0) {
  sim2d::VehicleTruth v;
  v.position_m = position_m;
  v.altitude_m = altitude_m;
  v.heading_rad = heading_deg * kDeg;
  v.pitch_rad = pitch_deg * kDeg;
  v.roll_rad = roll_deg * kDeg;
  v.phase = sim2d::FlightPhase::kFlying;
  return v;
}

/// The vehicle's view of a sim2d image (valid while `image` lives), as the HIL
/// bridge converts it.
inline CameraFrame FrameOf(const sim2d::ThermalImage& image) {
  return hil::ToCameraFrame(image);
}

/// The pose a perfect estimator would give for `v` seen through `camera`.
inline ObserverPose PoseOf(const sim2d::VehicleTruth& v, const sim2d::ThermalCamera& camera,
                           const common::LocalFrame& geo) {
  ObserverPose pose;
  common::EastNorth local;
  local.east_m = v.position_m.x();
  local.north_m = v.position_m.y();
  pose.position = geo.ToGeodetic(local);
  pose.altitude_m = v.altitude_m;
  pose.roll_rad = v.roll_rad;
  pose.pitch_rad = v.pitch_rad;
  pose.heading_rad = v.heading_rad;
  pose.camera = GeometryOf(camera.model(), camera.mount().camera_pitch_deg);
  return pose;
}

inline sim2d::ThermalCameraOptions AutoGain() {
  sim2d::ThermalCameraOptions options;
  options.gain = sim2d::GainMode::kAuto;
  return options;
}

}  // namespace fireswarm::agents::testing
