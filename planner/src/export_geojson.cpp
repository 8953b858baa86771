// The GeoJSON export and the file writer every export goes through.

#include <cstdio>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "fireswarm/common/atomic_file.hpp"
#include "fireswarm/planner/export.hpp"

namespace fireswarm::planner {
namespace {

using Json = nlohmann::ordered_json;

Json Position(const common::LatLon& p) {
  return Json::array({p.lon_deg, p.lat_deg});
}

Json PolygonFeature(const Polygon& polygon, const common::LocalFrame& frame, Json properties) {
  Json rings = Json::array();
  for (const std::vector<common::LatLon>& ring : GeoJsonRings(polygon, frame)) {
    Json positions = Json::array();
    for (const common::LatLon& p : ring) positions.push_back(Position(p));
    rings.push_back(std::move(positions));
  }
  return {{"type", "Feature"},
          {"properties", std::move(properties)},
          {"geometry", {{"type", "Polygon"}, {"coordinates", std::move(rings)}}}};
}

Json PathFeature(const DronePlan& drone) {
  Json coordinates = Json::array();
  for (const Waypoint& w : drone.waypoints) coordinates.push_back(Position(w.geodetic));
  return {{"type", "Feature"},
          {"properties",
           {{"kind", "path"},
            {"receiver_id", drone.receiver_id},
            {"site", drone.site},
            {"length_m", drone.length_m},
            {"time_s", drone.time_s},
            {"sorties", drone.sorties},
            {"ground_s", drone.ground_s},
            {"vertical_s", drone.vertical_s},
            {"longest_sortie_s", drone.longest_sortie_s},
            {"waypoints", drone.waypoints.size()}}},
          {"geometry", {{"type", "LineString"}, {"coordinates", std::move(coordinates)}}}};
}

}  // namespace

std::vector<std::vector<common::LatLon>> GeoJsonRings(const Polygon& polygon,
                                                      const common::LocalFrame& frame) {
  // Boost's rings (x east, y north) turn the other way round than RFC 7946's, so
  // each ring is read back to front.
  const auto reversed = [&](const auto& ring) {
    std::vector<common::LatLon> out;
    out.reserve(ring.size());
    for (auto it = ring.rbegin(); it != ring.rend(); ++it) {
      out.push_back(frame.ToGeodetic({it->x(), it->y()}));
    }
    return out;
  };
  std::vector<std::vector<common::LatLon>> rings{reversed(polygon.outer())};
  for (const auto& hole : polygon.inners()) rings.push_back(reversed(hole));
  return rings;
}

std::string PlanToGeoJson(const Plan& plan, const SearchArea& area, const FleetSpec& fleet) {
  Json features = Json::array();
  for (const DronePlan& drone : plan.drones) features.push_back(PathFeature(drone));
  for (const DronePlan& drone : plan.drones) {
    for (const Polygon& polygon : drone.region) {
      features.push_back(PolygonFeature(polygon, area.frame,
                                        {{"kind", "region"}, {"receiver_id", drone.receiver_id}}));
    }
  }
  for (const Polygon& polygon : area.area) {
    features.push_back(PolygonFeature(polygon, area.frame, {{"kind", "area"}}));
  }
  for (const Polygon& polygon : area.no_fly) {
    features.push_back(PolygonFeature(polygon, area.frame, {{"kind", "no_fly"}}));
  }
  for (std::size_t site = 0; site < fleet.launch_points.size(); ++site) {
    const Point& p = fleet.launch_points[site];
    int drones = 0;
    for (const DronePlan& drone : plan.drones) drones += drone.site == site ? 1 : 0;
    features.push_back(
        {{"type", "Feature"},
         {"properties", {{"kind", "launch_site"}, {"site", site}, {"drones", drones}}},
         {"geometry",
          {{"type", "Point"}, {"coordinates", Position(area.frame.ToGeodetic({p.x(), p.y()}))}}}});
  }
  Json figures = {{"coverage", plan.coverage},
                  {"makespan_s", plan.makespan_s},
                  {"lower_bound_s", plan.lower_bound_s},
                  {"lower_bound_basis", plan.lower_bound_basis},
                  {"endurance_s", fleet.endurance_s},
                  {"swap_s", fleet.swap_s},
                  {"climb_mps", fleet.climb_mps},
                  {"descent_mps", fleet.descent_mps},
                  {"nofly_violation_m", plan.nofly_violation_m},
                  {"sweep_width_m", plan.sweep_width_m},
                  {"altitude_m", fleet.altitude_m},
                  {"speed_mps", fleet.speed_mps},
                  {"camera", fleet.camera ? std::string(fleet.camera->name) : std::string()}};
  const Json collection = {{"type", "FeatureCollection"},
                           {"fireswarm", std::move(figures)},
                           {"features", std::move(features)}};
  return collection.dump(1) + "\n";
}

void WritePlanGeoJson(const std::filesystem::path& path, const Plan& plan, const SearchArea& area,
                      const FleetSpec& fleet) {
  common::WriteFileAtomically(path, PlanToGeoJson(plan, area, fleet));
}

}  // namespace fireswarm::planner
