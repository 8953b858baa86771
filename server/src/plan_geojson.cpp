// The server's plan as GeoJSON (plan_geojson.hpp).
#include "fireswarm/server/plan_geojson.hpp"

#include <string>
#include <utility>
#include <vector>

#include "fireswarm/planner/export.hpp"
#include "fireswarm/server/lcm_bridge.hpp"

namespace fireswarm::server {
namespace {

using Json = nlohmann::ordered_json;

Json Position(const common::LatLon& p) {
  return Json::array({p.lon_deg, p.lat_deg});
}

// One polygon's GeoJSON coordinates: its rings, exterior first.
Json PolygonCoordinates(const planner::Polygon& polygon, const common::LocalFrame& frame) {
  Json rings = Json::array();
  for (const std::vector<common::LatLon>& ring : planner::GeoJsonRings(polygon, frame)) {
    Json positions = Json::array();
    for (const common::LatLon& p : ring) positions.push_back(Position(p));
    rings.push_back(std::move(positions));
  }
  return rings;
}

Json Feature(Json properties, const char* type, Json coordinates) {
  return {{"type", "Feature"},
          {"properties", std::move(properties)},
          {"geometry", {{"type", type}, {"coordinates", std::move(coordinates)}}}};
}

Json AreaFeature(const planner::MultiPolygon& area, const common::LocalFrame& frame) {
  if (area.size() == 1) {
    return Feature({{"kind", "area"}}, "Polygon", PolygonCoordinates(area.front(), frame));
  }
  Json polygons = Json::array();
  for (const planner::Polygon& polygon : area) {
    polygons.push_back(PolygonCoordinates(polygon, frame));
  }
  return Feature({{"kind", "area"}}, "MultiPolygon", std::move(polygons));
}

Json LanesFeature(const DroneMission& mission) {
  Json coordinates = Json::array();
  for (const radio::Waypoint& w : mission.waypoints) {
    coordinates.push_back(Position({w.lat_deg, w.lon_deg}));
  }
  // RFC 7946 3.1.4: a LineString has two or more positions.
  if (coordinates.size() == 1) coordinates.push_back(coordinates.front());
  return Feature(
      {{"kind", "lanes"}, {"vehicle", mission.vehicle}, {"mission_id", mission.mission_id}},
      "LineString", std::move(coordinates));
}

Json CameraMember(const ServerConfig& config) {
  if (!config.camera) return nullptr;
  return {{"model", std::string(config.camera->name)},
          {"hfov_deg", config.camera->hfov_deg},
          {"vfov_deg", config.camera->vfov_deg},
          {"pitch_deg", config.camera_pitch_deg}};
}

}  // namespace

Json PlanGeoJson(const Server& server) {
  const ServerConfig& config = server.config();
  const common::LocalFrame& frame = server.frame();
  Json features = Json::array();
  if (!config.area.empty()) features.push_back(AreaFeature(config.area, frame));
  for (const planner::Polygon& zone : config.no_fly) {
    features.push_back(Feature({{"kind", "no_fly"}}, "Polygon", PolygonCoordinates(zone, frame)));
  }
  if (const MissionManager* mission = server.mission()) {
    for (const std::uint8_t id : mission->vehicles()) {
      if (mission->mission_of(id).waypoints.empty()) continue;
      features.push_back(LanesFeature(mission->mission_of(id)));
    }
  }
  if (config.launch_en_m) {
    features.push_back(
        Feature({{"kind", "launch"}}, "Point", Position(frame.ToGeodetic(*config.launch_en_m))));
  }
  return {{"type", "FeatureCollection"},
          {"camera", CameraMember(config)},
          {"features", std::move(features)}};
}

plan_t ToPlan(const Server& server, std::int64_t utime) {
  plan_t m{};
  m.utime = utime;
  // As mission_status_t: the server flies one mission, ID 1, once it is loaded.
  const MissionManager* mission = server.mission();
  m.mission_id = mission != nullptr && !mission->vehicles().empty() ? 1 : 0;
  m.geojson = PlanGeoJson(server).dump();
  return m;
}

}  // namespace fireswarm::server
