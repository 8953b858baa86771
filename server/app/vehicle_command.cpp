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
#include "link_flags.hpp"
#include "sim_link_loop.hpp"
#include "stop_signals.hpp"

namespace fireswarm::app {
namespace {

namespace po = boost::program_options;
using radio::Nanos;

constexpr const char* kName = "vehicle";
constexpr int kMinId = 1;
constexpr int kMaxId = 254;
constexpr double kMinSpeed = 1.0;
constexpr double kMaxSpeed = 1000.0;
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
  std::uint64_t seed = 1;
  std::optional<double> duration_s;
  double speed = 1.0;
};

[[noreturn]] void BadFlag(const std::string& flag, const std::string& requirement,
                          const std::string& got) {
  ThrowBadFlag(kName, flag, requirement, got);
}

// What a flag needs before it can become configuration; the ranges of the
// configurations themselves are checked by their Validate().
void CheckFlags(const Flags& f, const po::variables_map& values) {
  CheckLinkFlags(kName, f.link, values);
  if (f.id < kMinId || f.id > kMaxId) BadFlag("id", "in 1..254", std::to_string(f.id));
  if (common::FindCameraModel(f.camera) == nullptr) {
    BadFlag("camera", common::CameraModelNames(), f.camera);
  }
  if (f.lat_deg && !common::IsValidLatLon({*f.lat_deg, 0.0})) {
    BadFlag("lat", "in [-90, 90]", FlagText(*f.lat_deg));
  }
  if (f.lon_deg && !common::IsValidLatLon({0.0, *f.lon_deg})) {
    BadFlag("lon", "in [-180, 180]", FlagText(*f.lon_deg));
  }
  for (const auto& [flag, value] :
       {std::pair{"fire-east-m", f.fire_east_m}, std::pair{"fire-north-m", f.fire_north_m}}) {
    if (value && !(std::abs(*value) < kFireHalfWidthM)) {
      BadFlag(flag, "within (-1000, 1000) m of the launch point", FlagText(*value));
    }
  }
  if (f.duration_s && !(*f.duration_s > 0.0)) {
    BadFlag("duration-s", "> 0", FlagText(*f.duration_s));
  }
  if (!(f.speed >= kMinSpeed && f.speed <= kMaxSpeed)) {
    BadFlag("speed", "in [1, 1000]", FlagText(f.speed));
  }
}

// A 2 km square forest centred on the launch site (the world's origin) with the
// vehicle at its centre carrying its camera, and the optional ignition at t = 0.
sim2d::SimulationConfig WorldFor(const Flags& f) {
  sim2d::SimulationConfig config;
  config.world.seed = f.seed;
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

agents::VehicleConfig VehicleFor(const Flags& f) {
  agents::VehicleConfig config;
  config.id = static_cast<std::uint8_t>(f.id);
  config.radio.id = config.id;
  config.radio.mode = ModeOf(f.link);
  config.radio.checksum = ChecksumOf(f.link);
  config.radio.timing.baud = static_cast<int>(f.link.baud);
  config.param_file = f.param_file;
  config.camera = common::CameraModelByName(f.camera);
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
  add("seed", po::value(&f.seed)->default_value(f.seed), "simulation seed");
  add("duration-s", po::value<double>()->notifier([&f](double v) { f.duration_s = v; }),
      "stop after this much simulated time, s (default: run until SIGINT or SIGTERM)");
  add("speed", po::value(&f.speed)->default_value(f.speed),
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
  // Printed once the vehicle is built, so whoever reads it is answered at once.
  if (f.link.print_bound_port) std::cout << "bound_port=" << link.udp->local_port() << std::endl;
  fleet.Run(*link.link, f.speed,
            f.duration_s ? std::optional<Nanos>(radio::FromSeconds(*f.duration_s)) : std::nullopt);
  std::cout << fleet.VehicleSummary(*fleet.vehicles().front()).dump() << std::endl;
  return kExitOk;
}

}  // namespace fireswarm::app
