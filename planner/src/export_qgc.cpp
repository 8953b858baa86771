// QGroundControl .plan export (format: QGC dev guide, "Plan File Format"; the
// command and frame numbers are MAVLink's MAV_CMD and MAV_FRAME enums).
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "fireswarm/common/atomic_file.hpp"
#include "fireswarm/planner/export.hpp"

namespace fireswarm::planner {
namespace {

using Json = nlohmann::ordered_json;

constexpr int kPlanFileVersion = 1;
constexpr int kMissionVersion = 2;
constexpr int kGeoFenceVersion = 2;
constexpr int kRallyPointsVersion = 2;
constexpr int kFencePolygonVersion = 1;
constexpr int kFirmwarePx4 = 12;            // MAV_AUTOPILOT_PX4
constexpr int kVehicleQuadrotor = 2;        // MAV_TYPE_QUADROTOR (QGC's multirotor)
constexpr int kCmdNavWaypoint = 16;         // MAV_CMD_NAV_WAYPOINT
constexpr int kCmdNavReturnToLaunch = 20;   // MAV_CMD_NAV_RETURN_TO_LAUNCH
constexpr int kCmdNavTakeoff = 22;          // MAV_CMD_NAV_TAKEOFF
constexpr int kFrameMission = 2;            // MAV_FRAME_MISSION: no position (RTL)
constexpr int kFrameGlobalRelativeAlt = 3;  // MAV_FRAME_GLOBAL_RELATIVE_ALT
constexpr int kAltitudeModeRelative = 1;    // QGC: altitude relative to home

// A positioned item: params [p1, p2, p3, yaw (null = unchanged), lat, lon, alt].
Json PositionItem(int command, int jump_id, const common::LatLon& p, double altitude_m) {
  return {{"type", "SimpleItem"},
          {"command", command},
          {"frame", kFrameGlobalRelativeAlt},
          {"params", Json::array({0, 0, 0, nullptr, p.lat_deg, p.lon_deg, altitude_m})},
          {"autoContinue", true},
          {"doJumpId", jump_id},
          {"AMSLAltAboveTerrain", nullptr},
          {"Altitude", altitude_m},
          {"AltitudeMode", kAltitudeModeRelative}};
}

Json ReturnToLaunchItem(int jump_id) {
  return {{"type", "SimpleItem"},   {"command", kCmdNavReturnToLaunch},
          {"frame", kFrameMission}, {"params", Json::array({0, 0, 0, 0, 0, 0, 0})},
          {"autoContinue", true},   {"doJumpId", jump_id}};
}

// The no-fly zones as exclusion fences (outer rings; QGC polygons are not closed).
Json GeoFence(const SearchArea& area) {
  Json polygons = Json::array();
  for (const Polygon& zone : area.no_fly) {
    Json corners = Json::array();
    const auto& ring = zone.outer();
    for (std::size_t i = 0; i + 1 < ring.size(); ++i) {
      const common::LatLon p = area.frame.ToGeodetic({ring[i].x(), ring[i].y()});
      corners.push_back(Json::array({p.lat_deg, p.lon_deg}));
    }
    polygons.push_back(
        {{"polygon", std::move(corners)}, {"inclusion", false}, {"version", kFencePolygonVersion}});
  }
  return {
      {"version", kGeoFenceVersion}, {"polygons", std::move(polygons)}, {"circles", Json::array()}};
}

// One flight: waypoints [first, last] of the drone's list, first = where it takes off.
std::string SortieJson(const DronePlan& drone, std::size_t first, std::size_t last,
                       const FleetSpec& fleet, const Json& fence) {
  const common::LatLon home = drone.waypoints[first].geodetic;
  Json items = Json::array();
  int jump_id = 1;
  items.push_back(PositionItem(kCmdNavTakeoff, jump_id++, home, fleet.altitude_m));
  // The last point is back at launch: the RTL item flies it and lands.
  for (std::size_t i = first + 1; i < last; ++i) {
    items.push_back(
        PositionItem(kCmdNavWaypoint, jump_id++, drone.waypoints[i].geodetic, fleet.altitude_m));
  }
  items.push_back(ReturnToLaunchItem(jump_id));
  const Json mission = {{"version", kMissionVersion},
                        {"firmwareType", kFirmwarePx4},
                        {"vehicleType", kVehicleQuadrotor},
                        {"globalPlanAltitudeMode", kAltitudeModeRelative},
                        {"cruiseSpeed", fleet.speed_mps},
                        {"hoverSpeed", fleet.speed_mps},
                        {"plannedHomePosition", Json::array({home.lat_deg, home.lon_deg, 0.0})},
                        {"items", std::move(items)}};
  const Json plan = {
      {"fileType", "Plan"},
      {"version", kPlanFileVersion},
      {"groundStation", "QGroundControl"},
      {"mission", mission},
      {"geoFence", fence},
      {"rallyPoints", {{"version", kRallyPointsVersion}, {"points", Json::array()}}}};
  return plan.dump(4) + "\n";
}

}  // namespace

std::vector<QgcPlanFile> PlanToQgc(const Plan& plan, const SearchArea& area,
                                   const FleetSpec& fleet) {
  const Json fence = GeoFence(area);
  std::vector<QgcPlanFile> files;
  for (const DronePlan& drone : plan.drones) {
    if (drone.waypoints.size() < 2) continue;
    // Sorties end at is_return waypoints (and at the last waypoint).
    std::vector<std::size_t> ends;
    for (std::size_t i = 1; i + 1 < drone.waypoints.size(); ++i) {
      if (drone.waypoints[i].is_return) ends.push_back(i);
    }
    ends.push_back(drone.waypoints.size() - 1);
    const std::string stem = "drone_" + std::to_string(drone.receiver_id);
    std::size_t first = 0;
    for (std::size_t k = 0; k < ends.size(); ++k) {
      const std::string name =
          ends.size() == 1 ? stem + ".plan" : stem + "_sortie_" + std::to_string(k + 1) + ".plan";
      files.push_back({name, SortieJson(drone, first, ends[k], fleet, fence)});
      first = ends[k];
    }
  }
  return files;
}

std::vector<std::filesystem::path> WriteQgcPlans(const std::filesystem::path& directory,
                                                 const Plan& plan, const SearchArea& area,
                                                 const FleetSpec& fleet) {
  const std::vector<QgcPlanFile> files = PlanToQgc(plan, area, fleet);
  std::error_code error;
  std::filesystem::create_directories(directory, error);
  if (error) throw std::runtime_error(directory.string() + ": cannot create the directory");
  std::vector<std::filesystem::path> written;
  for (const QgcPlanFile& file : files) {
    written.push_back(directory / file.file_name);
    common::WriteFileAtomically(written.back(), file.json);
  }
  return written;
}

}  // namespace fireswarm::planner
