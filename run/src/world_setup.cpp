#include "world_setup.hpp"

#include <algorithm>
#include <boost/geometry.hpp>
#include <cmath>
#include <numbers>
#include <random>
#include <string>

#include "fireswarm/radio/mission_chunks.hpp"

namespace fireswarm::run::internal {
namespace {

namespace bg = boost::geometry;

/// The fire grid reaches this far beyond the area's bounding box, m: fires near
/// the edge spread and cameras look a little past it.
constexpr double kFireGridMarginM = 200.0;
constexpr double kFireCellM = 5.0;
constexpr double kMinStandRingM = 8.0;
constexpr int kMaxDrawsPerFire = 100'000;
/// Forward flight draws about this much more than hovering (measured: a 1.2 kg
/// quadcopter at 10 m/s in sim2d averages ~180 W against 164 W hovering).
constexpr double kCruisePowerFactor = 1.1;
/// The battery left when a sortie of endurance_s ends: the vehicles' default
/// return-to-launch threshold (agents safety.rtl_battery_fraction, 0.25) plus a
/// reserve for the way home and the landing.
constexpr double kBatteryLeftAfterSortie = 0.3;
constexpr double kSecondsPerHour = 3'600.0;
/// The scenario's wind is the open wind the vehicles fly in (taken as the 10 m
/// wind); the fire spreads with the midflame wind under the canopy. Wind
/// adjustment factor for forest under a closed canopy: 0.1-0.2
/// (docs/thermal_camera.md); the upper end, the grid being all forest.
constexpr double kMidflameWindFactor = 0.2;

sim2d::Vec2 Local(const planner::SearchArea& area, common::LatLon point) {
  const common::EastNorth local = area.frame.ToLocal(point);
  return {local.east_m, local.north_m};
}

sim2d::Vec2 LaunchSite(const Scenario& scenario) {
  return Local(scenario.area, scenario.fleet.launch);
}

bool Searchable(const planner::SearchArea& area, const planner::Point& point) {
  return bg::covered_by(point, area.area) && !bg::within(point, area.no_fly);
}

sim2d::SensorKind ToSim(FaultSensor sensor) {
  switch (sensor) {
    case FaultSensor::kGps:
      return sim2d::SensorKind::kGps;
    case FaultSensor::kBaro:
      return sim2d::SensorKind::kBaro;
    case FaultSensor::kAttitude:
      return sim2d::SensorKind::kAttitude;
    case FaultSensor::kBattery:
      return sim2d::SensorKind::kBattery;
  }
  return sim2d::SensorKind::kGps;
}

sim2d::FaultKind ToSim(FaultKind kind) {
  switch (kind) {
    case FaultKind::kStreamCut:
    case FaultKind::kGpsLoss:  // a stream cut of the GPS (ToSim(FaultSpec) sets the sensor)
      return sim2d::FaultKind::kStreamCut;
    case FaultKind::kFrozen:
      return sim2d::FaultKind::kFrozen;
    case FaultKind::kBias:
      return sim2d::FaultKind::kBias;
    case FaultKind::kExtraNoise:
      return sim2d::FaultKind::kExtraNoise;
    case FaultKind::kBallast:
      return sim2d::FaultKind::kBallast;
    case FaultKind::kTotalLoss:
    case FaultKind::kRadioSilent:
    case FaultKind::kServerRestart:  // the runner's, like kRadioSilent: never passed on
    case FaultKind::kVehicleReboot:
    case FaultKind::kRadioBurst:
      return sim2d::FaultKind::kTotalLoss;
  }
  return sim2d::FaultKind::kStreamCut;
}

// The faults sim2d applies; the runner applies the others (the radio's, the
// server's, a vehicle's software reboot).
bool IsSimulatorFault(FaultKind kind) {
  return kind != FaultKind::kRadioSilent && kind != FaultKind::kServerRestart &&
         kind != FaultKind::kVehicleReboot && kind != FaultKind::kRadioBurst;
}

sim2d::FaultSpec ToSim(const FaultSpec& fault) {
  sim2d::FaultSpec out;
  out.kind = ToSim(fault.kind);
  out.sensor = ToSim(fault.kind == FaultKind::kGpsLoss ? FaultSensor::kGps : fault.sensor);
  out.start_s = fault.at_s;
  out.end_s = fault.at_s + fault.duration_s;
  out.bias = Eigen::Vector3d(fault.bias[0], fault.bias[1], fault.bias[2]);
  out.noise_factor = fault.noise_factor;
  out.ballast_offset_m = sim2d::Vec2(fault.ballast_offset_m[0], fault.ballast_offset_m[1]);
  return out;
}

// Ignitions at the centre and at every fire cell centre within the radius, so a
// fire starts as a burning disc of that radius.
void AddFire(const sim2d::Vec2& centre_m, const FireSpec& fire, double cell_m,
             std::vector<sim2d::Ignition>& out) {
  out.push_back({centre_m, fire.start_s});
  const int reach = static_cast<int>(std::ceil(fire.radius_m / cell_m));
  for (int i = -reach; i <= reach; ++i) {
    for (int j = -reach; j <= reach; ++j) {
      if (i == 0 && j == 0) continue;
      const sim2d::Vec2 offset(i * cell_m, j * cell_m);
      if (offset.norm() <= fire.radius_m) out.push_back({centre_m + offset, fire.start_s});
    }
  }
}

double BearingOf(const sim2d::Vec2& from, const sim2d::Vec2& to) {
  return std::atan2(to.x() - from.x(), to.y() - from.y());  // clockwise from north
}

}  // namespace

std::vector<FireSpec> ExpandFires(const Scenario& scenario) {
  std::vector<FireSpec> fires = scenario.fires;
  if (!scenario.random_fires) return fires;
  const RandomFiresSpec& random = *scenario.random_fires;
  planner::Box box;
  bg::envelope(scenario.area.area, box);
  std::mt19937_64 rng(random.seed);
  std::uniform_real_distribution<double> east(box.min_corner().x(), box.max_corner().x());
  std::uniform_real_distribution<double> north(box.min_corner().y(), box.max_corner().y());
  std::vector<sim2d::Vec2> placed_m;
  for (const FireSpec& fire : fires) placed_m.push_back(Local(scenario.area, fire.position));
  const auto spaced = [&](const sim2d::Vec2& p) {
    return std::all_of(placed_m.begin(), placed_m.end(), [&](const sim2d::Vec2& other) {
      return (p - other).norm() >= random.min_spacing_m;
    });
  };
  for (int i = 0; i < random.count; ++i) {
    bool placed = false;
    for (int draw = 0; draw < kMaxDrawsPerFire && !placed; ++draw) {
      const double e = east(rng);
      const double n = north(rng);
      if (!Searchable(scenario.area, planner::Point(e, n)) || !spaced(sim2d::Vec2(e, n))) continue;
      placed_m.emplace_back(e, n);
      FireSpec fire;
      fire.position = scenario.area.frame.ToGeodetic({e, n});
      fire.radius_m = random.radius_m;
      fires.push_back(fire);
      placed = true;
    }
    if (!placed) {
      throw ScenarioError(scenario.source + ": random_fires: cannot place fire " +
                          std::to_string(i + 1) + " inside the search area at least " +
                          std::to_string(random.min_spacing_m) +
                          " m (min_spacing_m) from the others; lower count or min_spacing_m");
    }
  }
  return fires;
}

namespace {

// The stands of the drones `ids` of one launch site, as StandPositions says.
void RingStands(const Scenario& scenario, const sim2d::Vec2& launch, const std::vector<int>& ids,
                const std::vector<server::DroneMission>& missions,
                std::map<int, sim2d::Vec2>& stands) {
  const auto n = static_cast<double>(ids.size());
  if (ids.size() == 1) {
    stands[ids.front()] = launch;
    return;
  }
  // Ring radius: with evenly spaced stands, neighbours (chord 2 r sin(pi / n))
  // are at least the spacing apart (fleet.stand_spacing_m, kDefaultStandSpacingM
  // says why 10 m by default).
  const double spacing_m = scenario.fleet.stand_spacing_m;
  const double ring_m =
      std::max(kMinStandRingM, spacing_m / (2.0 * std::sin(std::numbers::pi / n)));
  // Each drone stands on the ring in the direction of its first waypoint, so that
  // climb-outs run radially outward and never cross; stands closer than the
  // spacing are pushed apart along the ring (evenly spaced when they do not fit).
  std::vector<std::pair<double, int>> bearings;
  for (const int id : ids) {
    double bearing = 0.0;
    for (const server::DroneMission& mission : missions) {
      if (mission.vehicle == id && !mission.waypoints.empty()) {
        const radio::Waypoint& first = mission.waypoints.front();
        bearing = BearingOf(launch, Local(scenario.area, {first.lat_deg, first.lon_deg}));
      }
    }
    bearings.emplace_back(bearing, id);
  }
  std::sort(bearings.begin(), bearings.end());
  const double full = 2.0 * std::numbers::pi;
  const double gap = 2.0 * std::asin(std::min(1.0, spacing_m / (2.0 * ring_m)));
  std::vector<double> angles;
  for (const auto& [bearing, id] : bearings) {
    angles.push_back(angles.empty() ? bearing : std::max(bearing, angles.back() + gap));
  }
  if (angles.back() - angles.front() > full - gap) {
    for (std::size_t i = 0; i < angles.size(); ++i) {
      angles[i] = angles.front() + static_cast<double>(i) * full / n;
    }
  }
  for (std::size_t i = 0; i < bearings.size(); ++i) {
    stands[bearings[i].second] =
        launch + ring_m * sim2d::Vec2(std::sin(angles[i]), std::cos(angles[i]));
  }
}

}  // namespace

std::map<int, sim2d::Vec2> StandPositions(const Scenario& scenario,
                                          const std::vector<server::DroneMission>& missions,
                                          const std::map<std::uint8_t, common::EastNorth>& sites) {
  // The drones of each site (the fleet's first site for one the plan has not).
  std::map<std::pair<double, double>, std::vector<int>> by_site;
  const sim2d::Vec2 first_site = LaunchSite(scenario);
  for (const int id : scenario.fleet.ReceiverIds()) {
    const auto site = sites.find(static_cast<std::uint8_t>(id));
    const sim2d::Vec2 at =
        site == sites.end() ? first_site : sim2d::Vec2(site->second.east_m, site->second.north_m);
    by_site[{at.x(), at.y()}].push_back(id);
  }
  std::map<int, sim2d::Vec2> stands;
  for (const auto& [at, ids] : by_site) {
    RingStands(scenario, sim2d::Vec2(at.first, at.second), ids, missions, stands);
  }
  return stands;
}

sim2d::SimulationConfig MakeSimulationConfig(const Scenario& scenario,
                                             const std::vector<FireSpec>& fires,
                                             const std::map<int, sim2d::Vec2>& stands) {
  sim2d::SimulationConfig config;
  sim2d::WorldConfig& world = config.world;
  world.origin = scenario.area.frame.origin();
  world.seed = scenario.seed;
  world.wind.speed_mps = scenario.wind.speed_mps;
  world.wind.from_deg = scenario.wind.from_deg;
  // The ground crew swaps a landed vehicle's pack in the time the plan gives it.
  world.battery_swap_s = scenario.fleet.swap_s;

  planner::Box box;
  bg::envelope(scenario.area.area, box);
  // The grid covers the area and the launch sites.
  for (const LaunchSiteConfig& site : scenario.fleet.launch_sites) {
    const sim2d::Vec2 launch = Local(scenario.area, site.position);
    bg::expand(box, planner::Point(launch.x(), launch.y()));
  }
  const double min_e = box.min_corner().x() - kFireGridMarginM;
  const double min_n = box.min_corner().y() - kFireGridMarginM;
  const double max_e = box.max_corner().x() + kFireGridMarginM;
  const double max_n = box.max_corner().y() + kFireGridMarginM;
  config.fire.origin_m = sim2d::Vec2(min_e, min_n);
  config.fire.width_m = std::ceil((max_e - min_e) / kFireCellM) * kFireCellM;
  config.fire.height_m = std::ceil((max_n - min_n) / kFireCellM) * kFireCellM;
  config.fire.cell_size_m = kFireCellM;
  config.fire.wind_speed_mps = scenario.wind.speed_mps * kMidflameWindFactor;
  config.fire.wind_from_deg = scenario.wind.from_deg;

  for (const FireSpec& fire : fires) {
    AddFire(Local(scenario.area, fire.position), fire, kFireCellM, config.ignitions);
  }
  for (const DistractorSpec& spec : scenario.distractors) {
    sim2d::Distractor distractor;
    distractor.center_m = Local(scenario.area, spec.position);
    distractor.radius_m = spec.radius_m;
    distractor.temperature_c = spec.temp_c;
    config.distractors.push_back(distractor);
  }
  for (const auto& [id, stand] : stands) {
    sim2d::VehicleConfig vehicle;
    vehicle.id = id;
    vehicle.launch_position_m = stand;
    vehicle.launch_heading_rad = 0.0;
    // The pack is sized for the fleet's endurance: the planner plans sorties of
    // endurance_s, so the simulated vehicle must be able to fly them before its
    // return-to-launch threshold (never smaller than sim2d's default pack).
    sim2d::BatteryParams& battery = vehicle.multirotor.battery;
    const double cruise_w =
        (battery.reference_power_w + battery.avionics_power_w) * kCruisePowerFactor;
    battery.capacity_wh =
        std::max(battery.capacity_wh, cruise_w * scenario.fleet.endurance_s / kSecondsPerHour /
                                          (1.0 - kBatteryLeftAfterSortie));
    for (const FaultSpec& fault : scenario.faults) {
      if (fault.vehicle == id && IsSimulatorFault(fault.kind)) {
        vehicle.faults.push_back(ToSim(fault));
      }
    }
    world.vehicles.push_back(vehicle);
    sim2d::VehicleCamera camera;
    camera.vehicle_id = id;
    camera.model = std::string(scenario.fleet.camera->name);
    camera.mount.camera_pitch_deg = scenario.fleet.camera_pitch_deg;
    config.cameras.push_back(camera);
  }
  return config;
}

}  // namespace fireswarm::run::internal
