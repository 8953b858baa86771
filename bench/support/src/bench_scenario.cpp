#include "fireswarm/bench/bench_scenario.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "fireswarm/common/camera_model.hpp"

namespace fireswarm::bench {
namespace {

constexpr int kMaxDrones = 1'000;
constexpr double kMaxAreaKm2 = 100.0;
constexpr int kAltitudeLayers = 4;
constexpr double kLayerSpacingM = 5.0;
constexpr double kLaneOverlap = 0.1;
constexpr double kMetresPerKm = 1'000.0;
constexpr double kNadirPitchDeg = -90.0;

[[noreturn]] void Bad(const std::string& field, const std::string& problem) {
  throw std::invalid_argument("bench scenario: " + field + " " + problem);
}

// Across-track width a nadir camera sees at `altitude_m` ("none": the altitude).
double FootprintWidthM(const std::string& camera, double altitude_m) {
  if (camera == "none") return altitude_m;
  return common::FootprintWidthM(common::CameraModelByName(camera), altitude_m, kNadirPitchDeg);
}

}  // namespace

void BenchScenarioSpec::Validate() const {
  if (drones < 1 || drones > kMaxDrones) {
    Bad("drones",
        "must be in [1, " + std::to_string(kMaxDrones) + "], got " + std::to_string(drones));
  }
  if (camera != "none" && common::FindCameraModel(camera) == nullptr) {
    Bad("camera", "must be none|" + common::CameraModelNames() + ", got '" + camera + "'");
  }
  if (!(area_km2 > 0.0 && area_km2 <= kMaxAreaKm2)) {
    Bad("area_km2", "must be in (0, 100], got " + std::to_string(area_km2));
  }
  // At most as many as a scenario's random fires (docs/limits.md).
  constexpr int kMaxIgnitions = 1'000;
  if (fires < 0 || fires > kMaxIgnitions) {
    Bad("fires", "must be in [0, 1000], got " + std::to_string(fires));
  }
  if (distractors < 0 || distractors > kMaxIgnitions) {
    Bad("distractors", "must be in [0, 1000], got " + std::to_string(distractors));
  }
  if (!(altitude_m > 0.0 && altitude_m <= 500.0)) {
    Bad("altitude_m", "must be in (0, 500], got " + std::to_string(altitude_m));
  }
  if (!(speed_mps > 0.0 && speed_mps <= 30.0)) {
    Bad("speed_mps", "must be in (0, 30], got " + std::to_string(speed_mps));
  }
}

BenchScenario MakeBenchScenario(const BenchScenarioSpec& spec) {
  spec.Validate();
  const double side_m = std::sqrt(spec.area_km2) * kMetresPerKm;
  const sim2d::Vec2 min_m(-side_m / 2.0, -side_m / 2.0);
  const double strip_m = side_m / spec.drones;

  BenchScenario scenario;
  sim2d::SimulationConfig& config = scenario.config;
  config.world.seed = spec.seed;
  config.fire.origin_m = min_m;
  config.fire.width_m = side_m;
  config.fire.height_m = side_m;
  config.random_ignitions = spec.fires;
  config.random_distractors = spec.distractors;
  for (int i = 0; i < spec.drones; ++i) {
    const int id = i + 1;
    const double strip_x = min_m.x() + i * strip_m;
    sim2d::VehicleConfig vehicle;
    vehicle.id = id;
    vehicle.launch_position_m = sim2d::Vec2(strip_x + strip_m / 2.0, min_m.y());
    config.world.vehicles.push_back(vehicle);
    if (spec.camera != "none") config.cameras.push_back({id, spec.camera, {}, {}});

    sim2d::LanePilotParams pilot;
    pilot.altitude_m = spec.altitude_m + (i % kAltitudeLayers) * kLayerSpacingM;
    pilot.speed_mps = spec.speed_mps;
    const double spacing_m = FootprintWidthM(spec.camera, pilot.altitude_m) * (1.0 - kLaneOverlap);
    scenario.pilots.emplace_back(
        sim2d::LawnmowerLanes(sim2d::Vec2(strip_x, min_m.y()),
                              sim2d::Vec2(strip_x + strip_m, min_m.y() + side_m), spacing_m),
        pilot);
  }
  return scenario;
}

}  // namespace fireswarm::bench
