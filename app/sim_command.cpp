// `fireswarm sim`: N simulated APOne vehicles in one sim2d world behind one real
// link, serial or UDP, paced by the wall clock: a fleet for `fireswarm serve` on
// the other end. The vehicles share the link as they would share one radio modem
// (sim_link_loop.hpp): each hears every byte, and the server's turns keep their
// replies apart.
#include <cmath>
#include <cstdint>
#include <iostream>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "cli.hpp"
#include "commands.hpp"
#include "fireswarm/agents/params.hpp"
#include "fireswarm/common/camera_model.hpp"
#include "fireswarm/common/local_frame.hpp"
#include "fireswarm/planner/plan.hpp"
#include "fireswarm/radio/params.hpp"
#include "fireswarm/server/vehicle_registry.hpp"
#include "link_flags.hpp"
#include "sim_link_flags.hpp"
#include "sim_link_loop.hpp"
#include "stop_signals.hpp"

namespace fireswarm::app {
namespace {

namespace po = boost::program_options;

constexpr const char* kName = "sim";
// The world's fire grid: a square of this half-width around the launch site.
constexpr double kWorldHalfWidthM = 2000.0;
constexpr double kFireCellM = 5.0;
// A fire starts as a burning disc of this radius, so a camera passing over sees
// more than one cell of it.
constexpr double kFireRadiusM = 8.0;
// Stands on the launch ring are at least this far apart (centre to centre), m.
constexpr double kMinStandSpacingM = 4.0;
constexpr double kMinStandRingM = 5.0;
constexpr double kMinLinkLostS = 2.0;
constexpr double kMaxLinkLostS = 600.0;
// The ground crew's battery swap after a landing, s (run's fleet.swap_s range).
constexpr double kDefaultSwapS = 300.0;

struct Flags {
  int count = 1;
  int first_id = 1;
  std::string launch;
  LinkFlags link;
  std::vector<std::string> fires;
  std::string camera = "seed";
  SimRunFlags run;
  std::optional<double> link_lost_timeout_s;
  double swap_s = kDefaultSwapS;
};

void CheckFlags(const Flags& f, const po::variables_map& values) {
  CheckLinkFlags(kName, f.link, values);
  if (f.count < 1 || f.count > server::kLastVehicleId) {
    ThrowBadFlag(kName, "count", "in 1..254", std::to_string(f.count));
  }
  if (f.first_id < server::kFirstVehicleId || f.first_id + f.count - 1 > server::kLastVehicleId) {
    ThrowBadFlag(kName, "first-id", "in 1..254 with every ID up to first-id + count - 1 <= 254",
                 std::to_string(f.first_id));
  }
  if (f.launch.empty()) ThrowBadFlag(kName, "launch", "given, as LAT,LON in degrees", "");
  if (!ParseLatLon(f.launch)) ThrowBadFlag(kName, "launch", "LAT,LON in degrees", f.launch);
  for (const std::string& fire : f.fires) {
    if (!ParseLatLon(fire)) ThrowBadFlag(kName, "fire", "LAT,LON in degrees", fire);
  }
  if (common::FindCameraModel(f.camera) == nullptr) {
    ThrowBadFlag(kName, "camera", common::CameraModelNames(), f.camera);
  }
  CheckSimRunFlags(kName, f.run);
  if (f.link_lost_timeout_s &&
      !(*f.link_lost_timeout_s >= kMinLinkLostS && *f.link_lost_timeout_s <= kMaxLinkLostS)) {
    ThrowBadFlag(kName, "link-lost-timeout-s", "in [2, 600]", FlagText(*f.link_lost_timeout_s));
  }
  CheckFlagRange(kName, "swap-s", f.swap_s, {0.0, planner::kMaxSwapS});
  RequireKeys(kName, f.link);  // last, so a flag above that is wrong is named first
}

// Stands on a ring around the launch site (the world's origin), a few metres
// apart, the first one north of the site and the others clockwise.
std::vector<sim2d::Vec2> Stands(int count) {
  if (count == 1) return {sim2d::Vec2::Zero()};
  const double n = count;
  const double ring_m =
      std::max(kMinStandRingM, kMinStandSpacingM / (2.0 * std::sin(std::numbers::pi / n)));
  std::vector<sim2d::Vec2> stands;
  for (int i = 0; i < count; ++i) {
    const double angle = 2.0 * std::numbers::pi * i / n;  // clockwise from north
    stands.emplace_back(ring_m * std::sin(angle), ring_m * std::cos(angle));
  }
  return stands;
}

sim2d::SimulationConfig WorldFor(const Flags& f) {
  const common::LatLon launch = *ParseLatLon(f.launch);
  const common::LocalFrame frame(launch);
  sim2d::SimulationConfig config;
  config.world.seed = f.run.seed;
  config.world.origin = launch;
  config.world.battery_swap_s = f.swap_s;
  config.fire.origin_m = sim2d::Vec2(-kWorldHalfWidthM, -kWorldHalfWidthM);
  config.fire.width_m = 2.0 * kWorldHalfWidthM;
  config.fire.height_m = 2.0 * kWorldHalfWidthM;
  config.fire.cell_size_m = kFireCellM;
  const std::vector<sim2d::Vec2> stands = Stands(f.count);
  for (int i = 0; i < f.count; ++i) {
    sim2d::VehicleConfig vehicle;
    vehicle.id = f.first_id + i;
    vehicle.launch_position_m = stands[static_cast<std::size_t>(i)];
    config.world.vehicles.push_back(vehicle);
    sim2d::VehicleCamera camera;
    camera.vehicle_id = vehicle.id;
    camera.model = f.camera;
    config.cameras.push_back(camera);
  }
  for (const std::string& text : f.fires) {
    const common::EastNorth at = frame.ToLocal(*ParseLatLon(text));
    const sim2d::Vec2 centre(at.east_m, at.north_m);
    if (std::abs(at.east_m) > kWorldHalfWidthM - kFireRadiusM ||
        std::abs(at.north_m) > kWorldHalfWidthM - kFireRadiusM) {
      ThrowBadFlag(kName, "fire", "within 2 km of the launch site", text);
    }
    // The centre and every cell centre of the disc, all at t = 0.
    const int reach = static_cast<int>(std::ceil(kFireRadiusM / kFireCellM));
    for (int i = -reach; i <= reach; ++i) {
      for (int j = -reach; j <= reach; ++j) {
        const sim2d::Vec2 offset(i * kFireCellM, j * kFireCellM);
        if (offset.norm() > kFireRadiusM) continue;
        sim2d::Ignition ignition;
        ignition.position_m = centre + offset;
        config.ignitions.push_back(ignition);
      }
    }
  }
  return config;
}

std::vector<agents::VehicleConfig> VehiclesFor(const Flags& f) {
  std::vector<agents::VehicleConfig> vehicles;
  for (int i = 0; i < f.count; ++i) {
    vehicles.push_back(VehicleConfigFor(f.first_id + i, f.link, f.camera));
  }
  return vehicles;
}

}  // namespace

int RunSim(const std::vector<std::string>& args) {
  Flags f;
  po::options_description options("sim options");
  auto add = options.add_options();
  add("count", po::value(&f.count)->default_value(f.count), "vehicles, 1..254");
  add("first-id", po::value(&f.first_id)->default_value(f.first_id),
      "receiver ID of the first vehicle; the others follow (first-id + 1, ...)");
  add("launch", po::value(&f.launch)->value_name("LAT,LON"),
      "launch site, deg: the vehicles stand a few metres apart around it");
  AddLinkOptions(options, f.link);
  add("fire", po::value(&f.fires)->composing()->value_name("LAT,LON"),
      "ignite a fire there at t = 0 (repeatable), within 2 km of the launch site");
  const std::string camera_help = "thermal camera of every vehicle: " + common::CameraModelNames();
  add("camera", po::value(&f.camera)->default_value(f.camera), camera_help.c_str());
  add("seed", po::value(&f.run.seed)->default_value(f.run.seed), "simulation seed");
  add("speed", po::value(&f.run.speed)->default_value(f.run.speed),
      "run the simulation this many times faster than the wall clock, 1..1000 (the vehicles' "
      "timers run that much faster than the server's)");
  add("duration-s", po::value<double>()->notifier([&f](double v) { f.run.duration_s = v; }),
      "stop after this much simulated time, s (default: run until SIGINT or SIGTERM)");
  add("link-lost-timeout-s",
      po::value<double>()->notifier([&f](double v) { f.link_lost_timeout_s = v; }),
      "set every vehicle's safety.link_lost_timeout_s parameter, simulated s, 2..600 (default: "
      "the parameter's default)");
  add("swap-s", po::value(&f.swap_s)->default_value(f.swap_s),
      "the ground crew puts a full pack in a vehicle this long after it landed, simulated s, "
      "0..3600 (0: never), so the server's next sortie can start");
  po::variables_map values;
  if (!ParseCommandLine(kName,
                        "--launch LAT,LON (--udp LOCAL REMOTE | --serial DEVICE) [--count N] "
                        "[options]",
                        options, {}, args, values)) {
    return kExitOk;
  }
  CheckFlags(f, values);
  const sim2d::SimulationConfig world = WorldFor(f);

  const StopOnSignals stop_on_signals;
  const OpenedLink link = OpenLink(f.link);
  SimulatedFleet fleet(world, VehiclesFor(f));
  if (f.link_lost_timeout_s) {
    for (const auto& vehicle : fleet.vehicles()) {
      radio::ParamWrite write;
      write.param_id = static_cast<std::uint16_t>(radio::ParamId::kLinkLostTimeoutS);
      write.value = static_cast<float>(*f.link_lost_timeout_s);
      vehicle->OnParamWrite(write);
    }
  }
  RunFleet(fleet, link, f.link, f.run);

  nlohmann::ordered_json summary;
  summary["sim_seconds"] = fleet.simulation().time_s();
  summary["wall_seconds"] = fleet.wall_seconds();
  summary["real_time_factor"] =
      fleet.wall_seconds() > 0.0 ? fleet.simulation().time_s() / fleet.wall_seconds() : 0.0;
  summary["vehicles"] = nlohmann::ordered_json::array();
  for (const auto& vehicle : fleet.vehicles()) {
    summary["vehicles"].push_back(fleet.VehicleSummary(*vehicle));
  }
  std::cout << summary.dump() << std::endl;
  return kExitOk;
}

}  // namespace fireswarm::app
