// The GeoJSON export and the file writer every export goes through.

#include <cstdio>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

#include "fireswarm/common/atomic_file.hpp"
#include "fireswarm/planner/export.hpp"

namespace fireswarm::planner {
namespace {

using Json = nlohmann::ordered_json;

Json Position(const common::LatLon& p) {
  return Json::array({p.lon_deg, p.lat_deg});
}

// RFC 7946 3.1.6: exterior rings counter-clockwise, holes clockwise. Boost's rings
// (x east, y north) are the opposite, so each ring is written back to front.
template <typename Ring>
Json RingCoordinates(const Ring& ring, const common::LocalFrame& frame) {
  Json positions = Json::array();
  for (auto it = ring.rbegin(); it != ring.rend(); ++it) {
    positions.push_back(Position(frame.ToGeodetic({it->x(), it->y()})));
  }
  return positions;
}

Json PolygonFeature(const Polygon& polygon, const common::LocalFrame& frame, Json properties) {
  Json rings = Json::array({RingCoordinates(polygon.outer(), frame)});
  for (const auto& hole : polygon.inners()) rings.push_back(RingCoordinates(hole, frame));
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
            {"length_m", drone.length_m},
            {"time_s", drone.time_s},
            {"sorties", drone.sorties},
            {"waypoints", drone.waypoints.size()}}},
          {"geometry", {{"type", "LineString"}, {"coordinates", std::move(coordinates)}}}};
}

}  // namespace

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
  Json figures = {{"coverage", plan.coverage},
                  {"makespan_s", plan.makespan_s},
                  {"lower_bound_s", plan.lower_bound_s},
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
