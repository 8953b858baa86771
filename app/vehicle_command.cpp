// `fireswarm vehicle`: one simulated APOne vehicle (the sim2d plant flown by an
// agents::Vehicle through the HIL bridge) behind a real link, serial or UDP, paced
// by the wall clock. Run one per vehicle to spread a fleet over several machines.
// The run loop, its time model and its half-duplex care over UDP are
// SimulatedFleet's (sim_link_loop.hpp), shared with `fireswarm sim`.
#include <cmath>
#include <cstdint>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "cli.hpp"
#include "commands.hpp"
#include "fireswarm/common/camera_model.hpp"
#include "fireswarm/common/local_frame.hpp"
#include "fireswarm/server/vehicle_registry.hpp"
#include "key_store.hpp"
#include "link_flags.hpp"
#include "sim_link_flags.hpp"
#include "sim_link_loop.hpp"
#include "stop_signals.hpp"

namespace fireswarm::app {
namespace {

namespace po = boost::program_options;

constexpr const char* kName = "vehicle";
// The fire area: a square of this half-width around the launch point.
constexpr double kFireHalfWidthM = 1000.0;

struct Flags {
  int id = 1;
  LinkFlags link;
  std::optional<double> lat_deg;
  std::optional<double> lon_deg;
  std::optional<double> fire_east_m;
  std::optional<double> fire_north_m;
  std::string camera = "seed";
  std::string param_file;
  SimRunFlags run;
};

// What a flag needs before it can become configuration; the ranges of the
// configurations themselves are checked by their Validate().
void CheckFlags(const Flags& f, const po::variables_map& values) {
  CheckLinkFlags(kName, f.link, values);
  if (f.id < server::kFirstVehicleId || f.id > server::kLastVehicleId) {
    ThrowBadFlag(kName, "id", "in 1..254", std::to_string(f.id));
  }
  if (common::FindCameraModel(f.camera) == nullptr) {
    ThrowBadFlag(kName, "camera", common::CameraModelNames(), f.camera);
  }
  if (f.lat_deg && !common::IsValidLatLon({*f.lat_deg, 0.0})) {
    ThrowBadFlag(kName, "lat", "in [-90, 90]", FlagText(*f.lat_deg));
  }
  if (f.lon_deg && !common::IsValidLatLon({0.0, *f.lon_deg})) {
    ThrowBadFlag(kName, "lon", "in [-180, 180]", FlagText(*f.lon_deg));
  }
  for (const auto& [flag, value] :
       {std::pair{"fire-east-m", f.fire_east_m}, std::pair{"fire-north-m", f.fire_north_m}}) {
    if (value && !(std::abs(*value) < kFireHalfWidthM)) {
      ThrowBadFlag(kName, flag, "within (-1000, 1000) m of the launch point", FlagText(*value));
    }
  }
  CheckSimRunFlags(kName, f.run);
  if (IsSecure(f.link) && f.link.keys.empty() && f.param_file.empty()) {
    throw UsageError(
        "fireswarm vehicle: --checksum secure (the default) needs its keys: --param-file PATH "
        "with PATH.key and PATH.broadcast.key beside it (fireswarm keys provision), or --keys "
        "DIR; --checksum crc16 runs the link unsecured");
  }
}

// A 2 km square forest centred on the launch site (the world's origin) with the
// vehicle at its centre carrying its camera, and the optional ignition at t = 0.
sim2d::SimulationConfig WorldFor(const Flags& f) {
  sim2d::SimulationConfig config;
  config.world.seed = f.run.seed;
  if (f.lat_deg) config.world.origin.lat_deg = *f.lat_deg;
  if (f.lon_deg) config.world.origin.lon_deg = *f.lon_deg;
  sim2d::VehicleConfig vehicle;
  vehicle.id = f.id;
  config.world.vehicles.push_back(vehicle);
  config.fire.origin_m = sim2d::Vec2(-kFireHalfWidthM, -kFireHalfWidthM);
  config.fire.width_m = 2.0 * kFireHalfWidthM;
  config.fire.height_m = 2.0 * kFireHalfWidthM;
  if (f.fire_east_m || f.fire_north_m) {
    sim2d::Ignition ignition;
    ignition.position_m = sim2d::Vec2(f.fire_east_m.value_or(0.0), f.fire_north_m.value_or(0.0));
    config.ignitions.push_back(ignition);
  }
  sim2d::VehicleCamera camera;
  camera.vehicle_id = f.id;
  camera.model = f.camera;
  config.cameras.push_back(camera);
  return config;
}

// Secure mode: the keys provisioned next to the parameter file (the vehicle's own
// storage), its counter and replay floor persisted there too; or --keys.
agents::VehicleConfig VehicleFor(const Flags& f) {
  agents::VehicleConfig config = VehicleConfigFor(f.id, f.link, f.camera);
  config.param_file = f.param_file;
  if (IsSecure(f.link) && f.link.keys.empty()) {
    try {
      config.radio.security = VehicleSecurityFromParamFile(f.param_file, f.id);
    } catch (const std::runtime_error& e) {
      throw UsageError(std::string("fireswarm vehicle: ") + e.what() +
                       " (fireswarm keys provision DIR --id N --param-file PATH)");
    }
  }
  return config;
}

}  // namespace

int RunVehicle(const std::vector<std::string>& args) {
  Flags f;
  po::options_description options("vehicle options");
  auto add = options.add_options();
  add("id", po::value(&f.id)->default_value(f.id), "receiver ID, 1..254");
  add("lat", po::value<double>()->notifier([&f](double v) { f.lat_deg = v; }),
      "launch site latitude, deg (default: the simulator's origin)");
  add("lon", po::value<double>()->notifier([&f](double v) { f.lon_deg = v; }),
      "launch site longitude, deg (default: the simulator's origin)");
  add("fire-east-m", po::value<double>()->notifier([&f](double v) { f.fire_east_m = v; }),
      "ignite a fire at t = 0 this far east of the launch point, m");
  add("fire-north-m", po::value<double>()->notifier([&f](double v) { f.fire_north_m = v; }),
      "ignite a fire at t = 0 this far north of the launch point, m");
  const std::string camera_help = "thermal camera: " + common::CameraModelNames();
  add("camera", po::value(&f.camera)->default_value(f.camera), camera_help.c_str());
  add("param-file", po::value(&f.param_file)->value_name("PATH"),
      "the vehicle's parameter file (its EEPROM); default: parameters in memory only");
  add("seed", po::value(&f.run.seed)->default_value(f.run.seed), "simulation seed");
  add("duration-s", po::value<double>()->notifier([&f](double v) { f.run.duration_s = v; }),
      "stop after this much simulated time, s (default: run until SIGINT or SIGTERM)");
  add("speed", po::value(&f.run.speed)->default_value(f.run.speed),
      "run the simulation this many times faster than the wall clock, 1..1000");
  AddLinkOptions(options, f.link);
  po::variables_map values;
  if (!ParseCommandLine(kName, "(--udp LOCAL REMOTE | --serial DEVICE) [options]", options, {},
                        args, values)) {
    return kExitOk;
  }
  CheckFlags(f, values);

  // Handled from here on, so a signal right after the port is printed ends cleanly.
  const StopOnSignals stop_on_signals;
  const OpenedLink link = OpenLink(f.link);
  SimulatedFleet fleet(WorldFor(f), {VehicleFor(f)});
  RunFleet(fleet, link, f.link, f.run);
  std::cout << fleet.VehicleSummary(*fleet.vehicles().front()).dump() << std::endl;
  return kExitOk;
}

}  // namespace fireswarm::app
