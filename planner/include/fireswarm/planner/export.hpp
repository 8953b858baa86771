// A search plan as files other tools read: one GeoJSON FeatureCollection for the
// fleet (maps, GIS, the web page) and QGroundControl .plan missions per drone (so
// PX4 / ArduPilot vehicles can fly the same plan). Pure text builders plus
// writers that replace files atomically.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "fireswarm/planner/plan.hpp"

namespace fireswarm::planner {

/// A polygon's rings in WGS84 through `frame` as RFC 7946 3.1.6 orders them: the
/// exterior ring first, counter-clockwise, then each hole, clockwise; each closed.
/// The one place a local polygon becomes GeoJSON rings (this export, the server's
/// published plan).
std::vector<std::vector<common::LatLon>> GeoJsonRings(const Polygon& polygon,
                                                      const common::LocalFrame& frame);

/// The plan as an RFC 7946 FeatureCollection ([lon, lat], right-hand rule rings):
/// per drone a LineString (properties: kind "path", receiver_id, site, length_m,
/// time_s, sorties, ground_s, longest_sortie_s, waypoints; its landings between
/// sorties are the launch site) and its region as Polygons (kind "region",
/// receiver_id); the area (kind "area") and no-fly zones (kind "no_fly") as
/// Polygons; each launch site as a Point (kind "launch_site", site, drones); the
/// fleet figures (coverage, makespan_s, lower_bound_s and its basis, ...) in the
/// collection's "fireswarm" member.
std::string PlanToGeoJson(const Plan& plan, const SearchArea& area, const FleetSpec& fleet);

/// One QGroundControl .plan file: the name to give it and its JSON text.
struct QgcPlanFile {
  std::string file_name;  ///< drone_<id>.plan, or drone_<id>_sortie_<k>.plan (k from 1)
  std::string json;
};

/// QGroundControl plan files (fileType "Plan", version 1; mission version 2, PX4
/// firmware, multirotor): per drone and sortie, a takeoff (MAV_CMD 22) at the
/// sortie's first waypoint, one waypoint (MAV_CMD 16) per point at
/// `fleet.altitude_m` relative to home (frame 3), and a return to launch
/// (MAV_CMD 20) at the end. A drone with several sorties (split at its
/// is_return waypoints) gets one file per sortie, since each is a separate flight.
/// The no-fly zones go into the geoFence as exclusion polygons.
std::vector<QgcPlanFile> PlanToQgc(const Plan& plan, const SearchArea& area,
                                   const FleetSpec& fleet);

/// PlanToGeoJson written atomically to `path`.
void WritePlanGeoJson(const std::filesystem::path& path, const Plan& plan, const SearchArea& area,
                      const FleetSpec& fleet);

/// PlanToQgc written atomically into `directory` (created when missing); returns
/// the paths written.
std::vector<std::filesystem::path> WriteQgcPlans(const std::filesystem::path& directory,
                                                 const Plan& plan, const SearchArea& area,
                                                 const FleetSpec& fleet);

}  // namespace fireswarm::planner
