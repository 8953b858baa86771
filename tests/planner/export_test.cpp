// Exports read back: the GeoJSON FeatureCollection (RFC 7946) and the
// QGroundControl .plan files against the fields QGC's file-format guide documents.
#include "fireswarm/planner/export.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>

#include "fireswarm/common/atomic_file.hpp"
#include "fireswarm/planner/area_io.hpp"

namespace fireswarm::planner {
namespace {

using Json = nlohmann::json;

constexpr double kAltitudeM = 60.0;
constexpr double kSpeedMps = 10.0;

// A 0.02 deg square near Mont-Tremblant with a no-fly zone in its north-east corner.
SearchArea TestArea() {
  const std::string area = R"({"type":"Polygon","coordinates":[[[-74.61,46.19],[-74.59,46.19],
      [-74.59,46.21],[-74.61,46.21],[-74.61,46.19]]]})";
  const std::string zone = R"({"type":"Polygon","coordinates":[[[-74.595,46.205],[-74.585,46.205],
      [-74.585,46.215],[-74.595,46.215],[-74.595,46.205]]]})";
  return ParseSearchArea({area, "area.geojson"}, GeoJsonText{zone, "nofly.geojson"});
}

Waypoint At(const SearchArea& area, double east_m, double north_m, bool is_return = false) {
  return {Point(east_m, north_m), area.frame.ToGeodetic({east_m, north_m}), is_return};
}

// Drone 3 flies one sortie; drone 5 two (a return to launch in the middle).
Plan TestPlan(const SearchArea& area) {
  Plan plan;
  DronePlan one;
  one.receiver_id = 3;
  one.region = area.area;
  one.waypoints = {At(area, 0, 0), At(area, -500, -500), At(area, -500, 500), At(area, 0, 0)};
  one.length_m = 2'414.0;
  one.time_s = 260.0;
  DronePlan two = one;
  two.receiver_id = 5;
  two.sorties = 2;
  two.waypoints = {At(area, 0, 0), At(area, 300, -300), At(area, 0, 0, true), At(area, 300, 300),
                   At(area, 0, 0)};
  plan.drones = {one, two};
  plan.coverage = 0.997;
  plan.makespan_s = 260.0;
  plan.lower_bound_s = 250.0;
  plan.sweep_width_m = 80.0;
  return plan;
}

FleetSpec TestFleet() {
  FleetSpec fleet;
  fleet.receiver_ids = {3, 5};
  fleet.altitude_m = kAltitudeM;
  fleet.speed_mps = kSpeedMps;
  fleet.camera = &common::CameraModelByName("seed");
  return fleet;
}

// Twice the signed area of a [lon, lat] ring: positive when counter-clockwise.
double SignedArea(const Json& ring) {
  double sum = 0.0;
  for (std::size_t i = 0; i + 1 < ring.size(); ++i) {
    sum += ring[i][0].get<double>() * ring[i + 1][1].get<double>() -
           ring[i + 1][0].get<double>() * ring[i][1].get<double>();
  }
  return sum;
}

TEST(PlanToGeoJson, ReadsBackAsAFeatureCollection) {
  const SearchArea area = TestArea();
  const Plan plan = TestPlan(area);
  const Json doc = Json::parse(PlanToGeoJson(plan, area, TestFleet()));
  EXPECT_EQ(doc["type"], "FeatureCollection");
  EXPECT_DOUBLE_EQ(doc["fireswarm"]["coverage"].get<double>(), 0.997);
  int paths = 0, regions = 0, zones = 0, areas = 0;
  for (const Json& feature : doc["features"]) {
    EXPECT_EQ(feature["type"], "Feature");
    const std::string kind = feature["properties"]["kind"];
    const Json& geometry = feature["geometry"];
    if (kind == "path") {
      const DronePlan& drone = plan.drones[static_cast<std::size_t>(paths++)];
      EXPECT_EQ(geometry["type"], "LineString");
      EXPECT_EQ(feature["properties"]["receiver_id"], drone.receiver_id);
      EXPECT_DOUBLE_EQ(feature["properties"]["length_m"].get<double>(), drone.length_m);
      EXPECT_DOUBLE_EQ(feature["properties"]["time_s"].get<double>(), drone.time_s);
      ASSERT_EQ(geometry["coordinates"].size(), drone.waypoints.size());
      for (std::size_t i = 0; i < drone.waypoints.size(); ++i) {
        EXPECT_DOUBLE_EQ(geometry["coordinates"][i][0].get<double>(),
                         drone.waypoints[i].geodetic.lon_deg);
        EXPECT_DOUBLE_EQ(geometry["coordinates"][i][1].get<double>(),
                         drone.waypoints[i].geodetic.lat_deg);
      }
      continue;
    }
    EXPECT_EQ(geometry["type"], "Polygon");
    // Right-hand rule (RFC 7946 3.1.6): outer ring counter-clockwise, closed.
    const Json& outer = geometry["coordinates"][0];
    EXPECT_GT(SignedArea(outer), 0.0) << kind;
    EXPECT_EQ(outer.front(), outer.back());
    if (kind == "region") ++regions;
    if (kind == "no_fly") ++zones;
    if (kind == "area") ++areas;
  }
  EXPECT_EQ(paths, 2);
  EXPECT_EQ(regions, 2);
  EXPECT_EQ(zones, 1);
  EXPECT_EQ(areas, 1);
}

TEST(PlanToQgc, HasTheFieldsQgcDocuments) {
  const SearchArea area = TestArea();
  const Plan plan = TestPlan(area);
  const auto files = PlanToQgc(plan, area, TestFleet());
  ASSERT_EQ(files.size(), 3U);  // drone 3 once, drone 5 per sortie
  EXPECT_EQ(files[0].file_name, "drone_3.plan");
  EXPECT_EQ(files[1].file_name, "drone_5_sortie_1.plan");
  EXPECT_EQ(files[2].file_name, "drone_5_sortie_2.plan");

  const Json doc = Json::parse(files[0].json);
  EXPECT_EQ(doc["fileType"], "Plan");
  EXPECT_EQ(doc["version"], 1);
  EXPECT_EQ(doc["groundStation"], "QGroundControl");
  const Json& mission = doc["mission"];
  EXPECT_EQ(mission["version"], 2);
  EXPECT_EQ(mission["firmwareType"], 12);
  EXPECT_EQ(mission["vehicleType"], 2);
  EXPECT_DOUBLE_EQ(mission["cruiseSpeed"].get<double>(), kSpeedMps);
  EXPECT_TRUE(mission.contains("hoverSpeed"));
  const DronePlan& drone = plan.drones[0];
  ASSERT_EQ(mission["plannedHomePosition"].size(), 3U);
  EXPECT_DOUBLE_EQ(mission["plannedHomePosition"][0].get<double>(),
                   drone.waypoints[0].geodetic.lat_deg);
  EXPECT_DOUBLE_EQ(mission["plannedHomePosition"][1].get<double>(),
                   drone.waypoints[0].geodetic.lon_deg);

  // Takeoff, one waypoint per inner point, return to launch.
  const Json& items = mission["items"];
  ASSERT_EQ(items.size(), drone.waypoints.size());
  for (std::size_t i = 0; i < items.size(); ++i) {
    const Json& item = items[i];
    EXPECT_EQ(item["type"], "SimpleItem");
    EXPECT_EQ(item["doJumpId"], i + 1);
    EXPECT_EQ(item["autoContinue"], true);
    ASSERT_EQ(item["params"].size(), 7U);
    if (i + 1 == items.size()) {
      EXPECT_EQ(item["command"], 20);
      continue;
    }
    EXPECT_EQ(item["command"], i == 0 ? 22 : 16);
    EXPECT_EQ(item["frame"], 3);
    EXPECT_TRUE(item["params"][3].is_null());
    EXPECT_DOUBLE_EQ(item["params"][4].get<double>(), drone.waypoints[i].geodetic.lat_deg);
    EXPECT_DOUBLE_EQ(item["params"][5].get<double>(), drone.waypoints[i].geodetic.lon_deg);
    EXPECT_DOUBLE_EQ(item["params"][6].get<double>(), kAltitudeM);
    EXPECT_DOUBLE_EQ(item["Altitude"].get<double>(), kAltitudeM);
    EXPECT_EQ(item["AltitudeMode"], 1);
    EXPECT_TRUE(item["AMSLAltAboveTerrain"].is_null());
  }

  // The no-fly zone as one exclusion polygon of [lat, lon] corners; no circles.
  const Json& fence = doc["geoFence"];
  EXPECT_EQ(fence["version"], 2);
  ASSERT_EQ(fence["polygons"].size(), 1U);
  EXPECT_EQ(fence["polygons"][0]["inclusion"], false);
  EXPECT_EQ(fence["polygons"][0]["version"], 1);
  EXPECT_EQ(fence["polygons"][0]["polygon"].size(), 4U);
  for (const Json& corner : fence["polygons"][0]["polygon"]) {
    EXPECT_NEAR(corner[0].get<double>(), 46.21, 0.006);
    EXPECT_NEAR(corner[1].get<double>(), -74.59, 0.006);
  }
  EXPECT_TRUE(fence["circles"].empty());
  EXPECT_EQ(doc["rallyPoints"]["version"], 2);
  EXPECT_TRUE(doc["rallyPoints"]["points"].empty());

  // The second sortie takes off where the first returned.
  const Json second = Json::parse(files[2].json);
  EXPECT_EQ(second["mission"]["items"].size(), 3U);
  EXPECT_DOUBLE_EQ(second["mission"]["items"][1]["params"][4].get<double>(),
                   plan.drones[1].waypoints[3].geodetic.lat_deg);
}

TEST(WriteExports, WritesWholeFilesAndNoTemporaries) {
  const SearchArea area = TestArea();
  const Plan plan = TestPlan(area);
  const auto dir =
      std::filesystem::temp_directory_path() / ("fireswarm_export_" + std::to_string(getpid()));
  WritePlanGeoJson(dir.string() + "_plan.geojson", plan, area, TestFleet());
  const auto written = WriteQgcPlans(dir / "qgc", plan, area, TestFleet());
  EXPECT_EQ(written.size(), 3U);
  for (const auto& path : written) {
    std::ifstream in(path);
    const Json doc = Json::parse(in);
    EXPECT_EQ(doc["fileType"], "Plan");
  }
  std::size_t entries = 0;
  for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir / "qgc")) {
    ++entries;
  }
  EXPECT_EQ(entries, 3U);
  std::ifstream in(dir.string() + "_plan.geojson");
  EXPECT_EQ(Json::parse(in)["type"], "FeatureCollection");
  std::filesystem::remove_all(dir);
  std::filesystem::remove(dir.string() + "_plan.geojson");
  EXPECT_THROW(common::WriteFileAtomically("/nonexistent-dir/x.geojson", "{}"), std::runtime_error);
}

}  // namespace
}  // namespace fireswarm::planner
