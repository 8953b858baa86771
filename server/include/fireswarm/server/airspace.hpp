// Strategic deconfliction: the altitude layers every drone flies before any
// conflict is predicted (the tactical half is traffic.hpp).
//
// The rule ("search layers by drone, transit layers by heading sector"):
// * Searching, drone k (in mission order) flies layer k % search_layers above the
//   fleet's altitude: neighbours whose lanes meet at a cut, or whose regions touch,
//   are a layer apart.
// * Every transit (to the first lane, between the pieces of a region, to an
//   investigation, home) flies in a transit layer above all search layers, one
//   layer per heading sector of 360 / transit_sectors degrees: two drones in one
//   transit layer fly within one sector of the same heading, so head-on traffic
//   never shares a layer and crossings are shallow. A drone climbs to it over the
//   leg's start and descends from it over the leg's end, inside its own region.
// * Home: each sortie ends with a "way home" waypoint over its last one, at the
//   transit layer of the heading home; the vehicle returns to launch at its
//   mission's last altitude (agents), also when its link is lost, and comes down
//   over its own stand.
// Layers are separation.layer_m apart. The plan records the rule and each drone's
// layers, and the journal keeps them with the mission (MissionLoaded), so a
// restarted server flies the same assignments.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "fireswarm/common/local_frame.hpp"
#include "fireswarm/server/mission_manager.hpp"
#include "fireswarm/server/traffic.hpp"

namespace fireswarm::server {

/// One drone's layers.
struct DroneLayers {
  std::uint8_t vehicle = 0;
  int search_layer = 0;           ///< 0 .. search_layers - 1
  double search_altitude_m = 0.0;
  bool operator==(const DroneLayers&) const = default;
};

/// The assignment a mission was given.
struct AirspacePlan {
  std::string rule;              ///< in words, for the plan and the journal
  double base_altitude_m = 0.0;  ///< the fleet's altitude (layer 0)
  double layer_m = 0.0;
  int search_layers = 1;
  int transit_sectors = 1;
  std::vector<DroneLayers> drones;
  bool operator==(const AirspacePlan&) const = default;
};

/// The transit layer of a leg flown at `heading_rad` (clockwise from north), m.
double TransitAltitudeM(const AirspacePlan& plan, double heading_rad);
/// Heading sector 0 .. transit_sectors - 1 of `heading_rad`.
int HeadingSector(const AirspacePlan& plan, double heading_rad);

/// Gives `missions` (as WithoutLaunchSite leaves them: every waypoint at the
/// fleet's altitude `base_altitude_m`) their layers as the rule above says and
/// returns the assignment. `sites`: each drone's launch site in `frame` (a drone
/// not listed gets no take-off transit and flies home at its search layer).
/// With config.layers false every drone keeps base_altitude_m and only the way
/// home is added. A sortie whose extra waypoints would not fit a radio mission
/// flies the transits beyond that in its search layer.
AirspacePlan AssignAirspace(std::vector<DroneMission>& missions, const common::LocalFrame& frame,
                            const std::map<std::uint8_t, common::EastNorth>& sites,
                            double base_altitude_m, const SeparationConfig& config);

}  // namespace fireswarm::server
