// Renders the example thermal image in docs/img/: a grass fire running into a
// forest edge, a lake and two sun-heated rocks, seen by the seed camera (96x64,
// 75x60 deg) looking straight down from 120 m, fixed range, white-hot.
//
//   render_thermal_example [out.pgm]      (default docs/img/fire_example.pgm)
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "fireswarm/common/camera_model.hpp"
#include "fireswarm/sim2d/fire_grid.hpp"
#include "fireswarm/sim2d/temperature_field.hpp"
#include "fireswarm/sim2d/thermal_camera.hpp"

namespace {

using fireswarm::sim2d::Vec2;
namespace sim2d = fireswarm::sim2d;

constexpr double kSceneTimeS = 300.0;  // five minutes after ignition
constexpr double kAltitudeM = 120.0;
constexpr std::uint64_t kSeed = 431;  // seed 4.3.1

int Run(const std::string& path) {
  sim2d::FireConfig config;
  config.width_m = 1000.0;
  config.height_m = 1000.0;
  config.wind_from_deg = 225.0;  // from the south-west: the head runs north-east
  sim2d::FireGrid fire(config, sim2d::MakeRng(kSeed, "fire"));
  // Grass south-west of the vehicle, forest elsewhere, a small lake to the east.
  fire.SetFuelRect(Vec2(0.0, 0.0), Vec2(500.0, 505.0), sim2d::Fuel::kOpen);
  const std::vector<Vec2> lake = {Vec2(540, 470), Vec2(575, 480), Vec2(585, 520), Vec2(550, 535)};
  fire.SetFuelPolygon(lake, sim2d::Fuel::kNone);
  fire.AddIgnition({Vec2(440.0, 450.0), 0.0});
  fire.AdvanceTo(kSceneTimeS);

  const sim2d::TemperatureField field(
      fire, {{Vec2(470.0, 540.0), 4.0, 65.0}, {Vec2(545.0, 445.0), 6.0, 48.0}});
  sim2d::ThermalCamera camera(fireswarm::common::CameraModelByName("seed"));
  sim2d::VehicleTruth vehicle;
  vehicle.position_m = Vec2(500.0, 500.0);
  vehicle.altitude_m = kAltitudeM;
  vehicle.phase = sim2d::FlightPhase::kFlying;
  sim2d::Rng noise = sim2d::MakeRng(kSeed, "camera", 1);
  const sim2d::ThermalImage image = camera.Render(vehicle, field, kSceneTimeS, noise);
  sim2d::WritePgm(path, image);
  std::printf("%s: %dx%d, %zu cells burning, %.0f m^2 burned\n", path.c_str(), image.width_px,
              image.height_px, fire.burning_count(), fire.BurnedAreaM2());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    return Run(argc > 1 ? argv[1] : "docs/img/fire_example.pgm");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "render_thermal_example: %s\n", e.what());
    return 2;
  }
}
