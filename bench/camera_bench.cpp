// Thermal camera and fire costs: one frame per camera model with and without
// fire in view, and one 1 s fire step with a large burning front. Budget: 1,000
// seed cameras at 9 Hz at 10x real time is 90,000 frames per second of wall time.
#include <benchmark/benchmark.h>

#include <memory>

#include "fireswarm/common/camera_model.hpp"
#include "fireswarm/sim2d/fire_grid.hpp"
#include "fireswarm/sim2d/temperature_field.hpp"
#include "fireswarm/sim2d/thermal_camera.hpp"

namespace {

namespace sim2d = fireswarm::sim2d;
using sim2d::Vec2;

// A 2 km x 2 km forest with a grass fire burning for 20 min around (1000, 1000),
// and a few rocks. Built once.
struct Scene {
  sim2d::FireGrid fire{Config(), sim2d::MakeRng(1, "fire")};
  std::unique_ptr<sim2d::TemperatureField> field;
  Scene() {
    fire.SetFuelRect(Vec2(800.0, 800.0), Vec2(1300.0, 1300.0), sim2d::Fuel::kOpen);
    fire.AddIgnition({Vec2(1000.0, 1000.0), 0.0});
    fire.AdvanceTo(600.0);
    field = std::make_unique<sim2d::TemperatureField>(
        fire, std::vector<sim2d::Distractor>{{Vec2(1050.0, 980.0), 5.0, 60.0},
                                             {Vec2(300.0, 300.0), 5.0, 60.0}});
  }
  static sim2d::FireConfig Config() {
    sim2d::FireConfig config;
    config.width_m = 2000.0;
    config.height_m = 2000.0;
    return config;
  }
};

const Scene& TheScene() {
  static const Scene scene;
  return scene;
}

// Args: camera model index (0 seed, 1 amg8833, 2 lepton35), fire in view (0/1).
void BM_RenderFrame(benchmark::State& state) {
  const Scene& scene = TheScene();
  const auto& model = fireswarm::common::CameraModels()[static_cast<std::size_t>(state.range(0))];
  sim2d::ThermalCamera camera(model);
  sim2d::VehicleTruth vehicle;
  vehicle.altitude_m = 120.0;
  vehicle.position_m = state.range(1) != 0 ? Vec2(1000.0, 1000.0) : Vec2(1600.0, 1600.0);
  vehicle.heading_rad = 0.3;
  vehicle.pitch_rad = -0.1;
  sim2d::Rng rng = sim2d::MakeRng(1, "camera");
  sim2d::ThermalImage image;
  double t_s = 0.0;
  for (auto _ : state) {
    camera.Render(vehicle, *scene.field, t_s, rng, image);
    benchmark::DoNotOptimize(image.pixels.data());
    t_s += 0.1;
  }
  state.SetLabel(std::string(model.name) + (state.range(1) != 0 ? " fire in view" : " no fire"));
  state.counters["pixels/s"] =
      benchmark::Counter(static_cast<double>(state.iterations()) * model.width_px * model.height_px,
                         benchmark::Counter::kIsRate);
}
BENCHMARK(BM_RenderFrame)->ArgsProduct({{0, 1, 2}, {0, 1}});

// A seed camera tilted to `range(0)` deg (negative down): near the horizon the
// pixel footprints grow long and some rays see sky.
void BM_RenderTiltedFrame(benchmark::State& state) {
  const Scene& scene = TheScene();
  sim2d::ThermalCamera camera(fireswarm::common::CameraModelByName("seed"),
                              {static_cast<double>(state.range(0))});
  sim2d::VehicleTruth vehicle;
  vehicle.altitude_m = 120.0;
  vehicle.position_m = Vec2(900.0, 700.0);  // the fire lies ahead, to the north
  sim2d::Rng rng = sim2d::MakeRng(1, "camera");
  sim2d::ThermalImage image;
  for (auto _ : state) {
    camera.Render(vehicle, *scene.field, 0.0, rng, image);
    benchmark::DoNotOptimize(image.pixels.data());
  }
}
BENCHMARK(BM_RenderTiltedFrame)->Arg(-60)->Arg(-20)->Arg(0);

// One 1 s step of grass fires on a 25 km^2 grid (a million cells), 15 min after
// `range(0)` random ignitions: the cost follows the burning front, not the grid.
void BM_FireStep(benchmark::State& state) {
  sim2d::FireConfig config;
  config.width_m = 5000.0;
  config.height_m = 5000.0;
  sim2d::FireGrid fire(config, sim2d::MakeRng(1, "fire"));
  fire.SetFuelRect(Vec2(0.0, 0.0), Vec2(5000.0, 5000.0), sim2d::Fuel::kOpen);
  sim2d::Rng rng = sim2d::MakeRng(1, "ignitions");
  for (const sim2d::Ignition& ignition :
       sim2d::RandomIgnitions(fire, static_cast<int>(state.range(0)), 0.0, 0.0, rng)) {
    fire.AddIgnition(ignition);
  }
  double t_s = 900.0;
  fire.AdvanceTo(t_s);
  const std::size_t front = fire.burning_count();
  const std::uint64_t events = fire.events_processed();
  for (auto _ : state) {
    t_s += 1.0;
    fire.AdvanceTo(t_s);
  }
  state.counters["burning_cells"] = static_cast<double>(front);
  state.counters["events/step"] = static_cast<double>(fire.events_processed() - events) /
                                  static_cast<double>(state.iterations());
}
BENCHMARK(BM_FireStep)->Arg(1)->Arg(100)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
