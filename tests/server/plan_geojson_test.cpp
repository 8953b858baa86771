// The published plan: PlanGeoJson's shape (holes kept, [lon, lat], RFC 7946 ring
// order, one lanes feature per drone), ToPlan, and plan_t on FIRESWARM_PLAN
// through real LCM (memq://) and the log, at a mission's load and every 5 s.
#include "fireswarm/server/plan_geojson.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <boost/geometry/algorithms/correct.hpp>
#include <filesystem>
#include <lcm/lcm-cpp.hpp>
#include <map>
#include <string>
#include <vector>

#include "fireswarm/server/lcm_bridge.hpp"
#include "server/server_fixture.hpp"

namespace fireswarm::server {
namespace {

using Json = nlohmann::ordered_json;

using testing::kFrame;

planner::Polygon Rect(double x0, double y0, double x1, double y1) {
  planner::Polygon p{{{x0, y0}, {x0, y1}, {x1, y1}, {x1, y0}, {x0, y0}}};
  boost::geometry::correct(p);
  return p;
}

// Two parts, the first with a lake in it; a no-fly zone; the seed camera tilted.
ServerConfig PlanConfig() {
  ServerConfig config;
  planner::Polygon forest = Rect(0, 0, 400, 300);
  forest.inners().push_back(Rect(100, 100, 200, 200).outer());
  boost::geometry::correct(forest);
  config.area = {forest, Rect(600, 0, 800, 300)};
  config.no_fly = {Rect(450, 0, 550, 100)};
  config.camera = common::CameraModelByName("seed");
  config.camera_pitch_deg = -60.0;
  config.launch_en_m = common::EastNorth{-50.0, -50.0};
  return config;
}

// Four waypoints 100 m apart on a line per drone, drones 40 m apart.
std::vector<DroneMission> LineMissions(const std::vector<std::uint8_t>& ids) {
  return testing::Missions(ids, 4, 40.0);
}

struct PlannedServer {
  explicit PlannedServer(const ServerConfig& config = PlanConfig()) : server(config, kFrame) {
    server.AddVehicle(1);
    server.AddVehicle(2);
    server.LoadMission(LineMissions({1, 2}));
  }
  Server server;
};

common::EastNorth Local(const Json& position) {
  return kFrame.ToLocal({position.at(1).get<double>(), position.at(0).get<double>()});
}

// Twice the ring's signed area in degrees^2 (x = lon, y = lat): > 0 counter-clockwise.
double SignedArea(const Json& ring) {
  double sum = 0.0;
  for (std::size_t i = 0; i + 1 < ring.size(); ++i) {
    sum += ring[i][0].get<double>() * ring[i + 1][1].get<double>() -
           ring[i + 1][0].get<double>() * ring[i][1].get<double>();
  }
  return sum;
}

std::vector<Json> OfKind(const Json& collection, const std::string& kind) {
  std::vector<Json> out;
  for (const Json& feature : collection.at("features")) {
    if (feature.at("properties").at("kind") == kind) out.push_back(feature);
  }
  return out;
}

TEST(PlanGeoJson, TheAreaKeepsItsPartsAndHolesInLonLat) {
  PlannedServer planned;
  const Json plan = PlanGeoJson(planned.server);
  EXPECT_EQ(plan.at("type"), "FeatureCollection");
  const std::vector<Json> areas = OfKind(plan, "area");
  ASSERT_EQ(areas.size(), 1U);
  const Json& geometry = areas[0].at("geometry");
  EXPECT_EQ(geometry.at("type"), "MultiPolygon");
  const Json& polygons = geometry.at("coordinates");
  ASSERT_EQ(polygons.size(), 2U);
  ASSERT_EQ(polygons[0].size(), 2U) << "the forest's exterior and its lake";
  EXPECT_EQ(polygons[1].size(), 1U);
  const Json& exterior = polygons[0][0];
  const Json& lake = polygons[0][1];
  // [lon, lat]: near -74.5, 46 and back on the local corners.
  EXPECT_NEAR(exterior[0][0].get<double>(), -74.5, 0.01);
  EXPECT_NEAR(exterior[0][1].get<double>(), 46.0, 0.01);
  EXPECT_EQ(exterior.front(), exterior.back()) << "rings are closed";
  for (const Json& position : lake) {
    const common::EastNorth p = Local(position);
    EXPECT_TRUE(std::abs(p.east_m - 100.0) < 0.01 || std::abs(p.east_m - 200.0) < 0.01);
    EXPECT_TRUE(std::abs(p.north_m - 100.0) < 0.01 || std::abs(p.north_m - 200.0) < 0.01);
  }
  // RFC 7946: exterior counter-clockwise, holes clockwise.
  EXPECT_GT(SignedArea(exterior), 0.0);
  EXPECT_LT(SignedArea(lake), 0.0);
}

TEST(PlanGeoJson, OnePartIsAPolygon) {
  ServerConfig config = PlanConfig();
  config.area.resize(1);
  PlannedServer planned(config);
  const std::vector<Json> areas = OfKind(PlanGeoJson(planned.server), "area");
  ASSERT_EQ(areas.size(), 1U);
  EXPECT_EQ(areas[0].at("geometry").at("type"), "Polygon");
  EXPECT_EQ(areas[0].at("geometry").at("coordinates").size(), 2U);
}

TEST(PlanGeoJson, LanesPerDroneNoFlyLaunchAndCamera) {
  PlannedServer planned;
  const Json plan = PlanGeoJson(planned.server);
  const std::vector<Json> lanes = OfKind(plan, "lanes");
  ASSERT_EQ(lanes.size(), 2U) << "one per drone";
  for (std::size_t i = 0; i < lanes.size(); ++i) {
    const int vehicle = lanes[i].at("properties").at("vehicle").get<int>();
    EXPECT_EQ(vehicle, static_cast<int>(i) + 1);
    EXPECT_EQ(lanes[i].at("geometry").at("type"), "LineString");
    const Json& line = lanes[i].at("geometry").at("coordinates");
    ASSERT_EQ(line.size(), 4U);
    const common::EastNorth last = Local(line.back());
    EXPECT_NEAR(last.east_m, 300.0, 0.05);
    EXPECT_NEAR(last.north_m, 40.0 * vehicle, 0.05);
  }
  const std::vector<Json> zones = OfKind(plan, "no_fly");
  ASSERT_EQ(zones.size(), 1U);
  EXPECT_EQ(zones[0].at("geometry").at("type"), "Polygon");
  const std::vector<Json> launch = OfKind(plan, "launch");
  ASSERT_EQ(launch.size(), 1U);
  EXPECT_EQ(launch[0].at("geometry").at("type"), "Point");
  const common::EastNorth at = Local(launch[0].at("geometry").at("coordinates"));
  EXPECT_NEAR(at.east_m, -50.0, 0.01);
  EXPECT_NEAR(at.north_m, -50.0, 0.01);
  const Json& camera = plan.at("camera");
  EXPECT_DOUBLE_EQ(camera.at("hfov_deg").get<double>(), 75.0);
  EXPECT_DOUBLE_EQ(camera.at("vfov_deg").get<double>(), 60.0);
  EXPECT_DOUBLE_EQ(camera.at("pitch_deg").get<double>(), -60.0);
}

TEST(PlanGeoJson, WithoutAreaCameraOrMissionOnlyWhatIsKnown) {
  const Server server(ServerConfig{}, kFrame);
  const Json plan = PlanGeoJson(server);
  EXPECT_TRUE(plan.at("features").empty());
  EXPECT_TRUE(plan.at("camera").is_null());
  const plan_t m = ToPlan(server, 7);
  EXPECT_EQ(m.utime, 7);
  EXPECT_EQ(m.mission_id, 0);
}

TEST(PlanGeoJson, ToPlanCarriesTheCollectionAndTheMissionId) {
  PlannedServer planned;
  const plan_t m = ToPlan(planned.server, 42);
  EXPECT_EQ(m.utime, 42);
  EXPECT_EQ(m.mission_id, 1);
  EXPECT_EQ(Json::parse(m.geojson), PlanGeoJson(planned.server));
}

struct PlanInbox {
  void OnPlan(const lcm::ReceiveBuffer*, const std::string&, const plan_t* m) {
    utimes.push_back(m->utime);
    last = *m;
  }
  std::vector<std::int64_t> utimes;
  plan_t last{};
};

// No plan before a mission is loaded; one at once when it is, then every 5 s.
TEST(LcmBridgePlan, PublishedOnMemqWhenAMissionIsLoadedAndEveryFiveSeconds) {
  Server server(PlanConfig(), kFrame);
  server.AddVehicle(1);
  server.AddVehicle(2);
  LcmBridgeConfig config;
  config.url = "memq://";
  LcmBridge bridge(config);
  ASSERT_NE(bridge.lcm(), nullptr);
  PlanInbox inbox;
  bridge.lcm()->subscribe(kPlanChannel, &PlanInbox::OnPlan, &inbox);
  const auto publish_until = [&](double from_s, double to_s) {
    for (double t = from_s; t < to_s - 1e-9; t += 0.5) {
      bridge.Publish(server, t, std::llround(t * 1e6), 0);
      while (bridge.lcm()->handleTimeout(0) > 0) {
      }
    }
  };
  publish_until(0.0, 3.0);
  EXPECT_TRUE(inbox.utimes.empty()) << "no plan before a mission";
  EXPECT_EQ(bridge.NextPublishS(), 3.0) << "no plan due yet either";
  server.LoadMission(LineMissions({1, 2}));
  publish_until(3.0, 14.0);
  EXPECT_EQ(inbox.utimes, (std::vector<std::int64_t>{3'000'000, 8'000'000, 13'000'000}));
  EXPECT_EQ(inbox.last.mission_id, 1);
  EXPECT_EQ(OfKind(Json::parse(inbox.last.geojson), "lanes").size(), 2U);
}

// The log has the plan (lcm-logplayer replays it); the CSV directory does not:
// one GeoJSON string is no table.
TEST(LcmBridgePlan, LoggedButNotInCsv) {
  PlannedServer planned;
  const std::filesystem::path dir =
      std::filesystem::path(::testing::TempDir()) / ("plan_log_" + std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  LcmBridgeConfig config;
  config.log_path = dir / "run.lcmlog";
  config.csv_dir = dir / "csv";
  std::filesystem::create_directories(dir);
  {
    LcmBridge bridge(config);
    for (int step = 0; step < 100; ++step) {
      const double t = 0.1 * step;
      bridge.Publish(planned.server, t, std::llround(t * 1e6), 0);
    }
  }
  std::map<std::string, int> events;
  lcm::LogFile log(config.log_path->string(), "r");
  ASSERT_TRUE(log.good());
  while (const lcm::LogEvent* event = log.readNextEvent()) {
    ++events[event->channel];
    if (event->channel != kPlanChannel) continue;
    plan_t m;
    ASSERT_EQ(m.decode(event->data, 0, event->datalen), event->datalen);
    EXPECT_EQ(Json::parse(m.geojson).at("type"), "FeatureCollection");
  }
  EXPECT_EQ(events[kPlanChannel], 2) << "at 0 s and 5 s of 10";
  EXPECT_TRUE(std::filesystem::exists(*config.csv_dir / "fireswarm_mission_status.csv"));
  EXPECT_FALSE(std::filesystem::exists(*config.csv_dir / "fireswarm_plan.csv"));
  std::filesystem::remove_all(dir);
}

}  // namespace
}  // namespace fireswarm::server
