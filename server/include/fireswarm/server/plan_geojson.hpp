// The mission's plan as the server holds it, as GeoJSON for displays and logs
// (plan_t on LCM, lcm_bridge.hpp). Pure.
#pragma once

#include <nlohmann/json.hpp>

#include "fireswarm/server/server.hpp"

namespace fireswarm::server {

/// An RFC 7946 FeatureCollection ([lon, lat] in WGS84 through the server's
/// frame; rings by the right-hand rule), every feature with property "kind":
///  * "area": ServerConfig::area, a Polygon (one part) or MultiPolygon, holes
///    kept; absent without an area;
///  * "no_fly": one Polygon per zone of ServerConfig::no_fly;
///  * "lanes": per drone of the loaded mission (ascending receiver ID) a
///    LineString of the waypoints it flies now (MissionManager::mission_of, so a
///    drone handed lanes of a lost one shows its new mission), properties
///    "vehicle" (receiver ID) and "mission_id"; a one-waypoint route repeats
///    its point (a LineString needs two), a drone without waypoints has none;
///  * "launch": a Point at ServerConfig::launch_en_m, when given.
/// The collection's member "camera" is {"model", "hfov_deg", "vfov_deg",
/// "pitch_deg"} of ServerConfig::camera, null without one.
nlohmann::ordered_json PlanGeoJson(const Server& server);

}  // namespace fireswarm::server
