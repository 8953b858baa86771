// Strategic deconfliction: search layers by drone, transit layers by heading
// sector (airspace.hpp says why).
#include "fireswarm/server/airspace.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include "fireswarm/radio/mission_chunks.hpp"

namespace fireswarm::server {

namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

common::EastNorth Local(const common::LocalFrame& frame, const radio::Waypoint& waypoint) {
  return frame.ToLocal({waypoint.lat_deg, waypoint.lon_deg});
}

double HeadingRad(const common::EastNorth& from, const common::EastNorth& to) {
  return std::atan2(to.east_m - from.east_m, to.north_m - from.north_m);
}

double DistanceM(const common::EastNorth& a, const common::EastNorth& b) {
  return std::hypot(b.east_m - a.east_m, b.north_m - a.north_m);
}

std::string RuleOf(const SeparationConfig& config) {
  if (!config.layers) return "one layer: every drone at the fleet's altitude";
  char text[200];
  std::snprintf(text, sizeof text,
                "search layer by drone (k mod %d), transit layer by heading sector (%d sectors "
                "of %.0f deg above the search layers), layers %.0f m apart",
                config.search_layers, config.transit_sectors, 360.0 / config.transit_sectors,
                config.layer_m);
  return text;
}

// One sortie in its layers: transits climb over their start and descend over
// their end; the way home goes last.
std::vector<radio::Waypoint> Layered(const std::vector<radio::Waypoint>& route,
                                     const common::LocalFrame& frame,
                                     const common::EastNorth* site,
                                     double search_altitude_m, const AirspacePlan& plan,
                                     const SeparationConfig& config) {
  std::vector<radio::Waypoint> out;
  if (route.empty()) return out;
  // Room for the extra waypoints: two per transit, one for the way home.
  std::size_t room = radio::kMaxMissionWaypoints - std::min(radio::kMaxMissionWaypoints,
                                                            route.size() + 1);
  const auto transit = [&](const radio::Waypoint& at, double heading_rad) {
    radio::Waypoint high = at;
    high.altitude_m = TransitAltitudeM(plan, heading_rad);
    high.flags = 0;  // no lane starts up here
    return high;
  };
  const auto in_search_layer = [&](radio::Waypoint waypoint) {
    waypoint.altitude_m = search_altitude_m;
    return waypoint;
  };
  // The take-off's leg: the vehicle climbs over its stand to the first
  // waypoint's altitude, then flies there.
  const common::EastNorth first = Local(frame, route.front());
  if (config.layers && site != nullptr && DistanceM(*site, first) >= config.transit_min_m && room >= 1) {
    out.push_back(transit(route.front(), HeadingRad(*site, first)));
    --room;
  }
  for (std::size_t i = 0; i < route.size(); ++i) {
    out.push_back(in_search_layer(route[i]));
    if (i + 1 == route.size()) break;
    const bool lane = (route[i].flags & radio::Waypoint::kLaneStart) != 0;
    const common::EastNorth from = Local(frame, route[i]);
    const common::EastNorth to = Local(frame, route[i + 1]);
    if (!config.layers || lane || DistanceM(from, to) < config.transit_min_m || room < 2) continue;
    const double heading = HeadingRad(from, to);
    out.push_back(transit(route[i], heading));
    out.push_back(transit(route[i + 1], heading));
    room -= 2;
  }
  // The way home: over the last waypoint, at the layer of the heading home.
  const common::EastNorth last = Local(frame, route.back());
  radio::Waypoint home = route.back();
  home.flags = 0;
  home.altitude_m = search_altitude_m;
  if (config.layers && site != nullptr && DistanceM(last, *site) >= config.transit_min_m) {
    home.altitude_m = TransitAltitudeM(plan, HeadingRad(last, *site));
  }
  out.push_back(home);
  return out;
}

}  // namespace

int HeadingSector(const AirspacePlan& plan, double heading_rad) {
  double heading = std::fmod(heading_rad, kTwoPi);
  if (heading < 0.0) heading += kTwoPi;
  const int sector = static_cast<int>(heading / (kTwoPi / plan.transit_sectors));
  return std::min(sector, plan.transit_sectors - 1);
}

double TransitAltitudeM(const AirspacePlan& plan, double heading_rad) {
  return plan.base_altitude_m +
         plan.layer_m * static_cast<double>(plan.search_layers + HeadingSector(plan, heading_rad));
}

AirspacePlan AssignAirspace(std::vector<DroneMission>& missions, const common::LocalFrame& frame,
                            const std::map<std::uint8_t, common::EastNorth>& sites,
                            double base_altitude_m, const SeparationConfig& config) {
  config.Validate();
  AirspacePlan plan;
  plan.rule = RuleOf(config);
  plan.base_altitude_m = base_altitude_m;
  plan.layer_m = config.layer_m;
  plan.search_layers = config.layers ? config.search_layers : 1;
  plan.transit_sectors = config.transit_sectors;
  for (std::size_t k = 0; k < missions.size(); ++k) {
    DroneMission& mission = missions[k];
    DroneLayers layers;
    layers.vehicle = mission.vehicle;
    layers.search_layer = static_cast<int>(k % static_cast<std::size_t>(plan.search_layers));
    layers.search_altitude_m = base_altitude_m + config.layer_m * layers.search_layer;
    plan.drones.push_back(layers);
    const auto found = sites.find(mission.vehicle);
    const common::EastNorth* site = found == sites.end() ? nullptr : &found->second;
    std::vector<std::vector<radio::Waypoint>> sorties = SortiesOf(mission);
    for (std::vector<radio::Waypoint>& route : sorties) {
      route = Layered(route, frame, site, layers.search_altitude_m, plan, config);
    }
    SetSorties(mission, sorties);
  }
  return plan;
}

}  // namespace fireswarm::server
