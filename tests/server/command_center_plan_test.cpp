// The plan (GET /api/plan) and the coverage raster over its area (GET /api/coverage).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "command_center_messages.hpp"
#include "fireswarm/server/command_center.hpp"

namespace fireswarm::server {
namespace {

using ::testing::HasSubstr;

// A 200 m (east) x 100 m (north) rectangle at kOrigin, a drone's lanes, a
// downward camera.
nlohmann::json PlanJson() {
  const common::LocalFrame frame(test::kOrigin);
  nlohmann::json ring = nlohmann::json::array();
  for (const auto& [e, n] : {std::pair{0.0, 0.0}, std::pair{200.0, 0.0}, std::pair{200.0, 100.0},
                             std::pair{0.0, 100.0}, std::pair{0.0, 0.0}}) {
    const common::LatLon p = frame.ToGeodetic({e, n});
    ring.push_back({p.lon_deg, p.lat_deg});
  }
  return {{"type", "FeatureCollection"},
          {"camera", {{"hfov_deg", 60.0}, {"vfov_deg", 45.0}, {"pitch_deg", -90.0}}},
          {"features",
           {{{"type", "Feature"},
             {"properties", {{"kind", "area"}}},
             {"geometry", {{"type", "Polygon"}, {"coordinates", {ring}}}}},
            {{"type", "Feature"},
             {"properties", {{"kind", "lanes"}, {"vehicle", 1}}},
             {"geometry", {{"type", "LineString"}, {"coordinates", {ring[0], ring[1]}}}}}}}};
}

plan_t PlanMessage(const std::string& geojson, std::int64_t utime) {
  plan_t plan{};
  plan.utime = utime;
  plan.mission_id = 1;
  plan.geojson = geojson;
  return plan;
}

TEST(CommandCenterPlan, ServesTheLatestPlanAndSaysWhenItChanged) {
  CommandCenter center({});
  const nlohmann::json plan = PlanJson();
  center.OnPlan(PlanMessage(plan.dump(), 1'000'000));
  EXPECT_EQ(center.Plan(), plan);
  EXPECT_EQ(center.State()["plan"], (nlohmann::json{{"mission_id", 1}, {"version", 1}}));
  std::optional<nlohmann::json> delta = center.TakeDelta();
  ASSERT_TRUE(delta);
  EXPECT_EQ((*delta)["plan"]["version"], 1);
  // Re-published unchanged: nothing new but the time.
  center.OnPlan(PlanMessage(plan.dump(), 5'000'000));
  delta = center.TakeDelta();
  ASSERT_TRUE(delta);
  EXPECT_FALSE(delta->contains("plan"));
}

TEST(CommandCenterPlan, AMalformedPlanKeepsThePreviousOneAndSaysWhy) {
  CommandCenter center({});
  const nlohmann::json plan = PlanJson();
  center.OnPlan(PlanMessage(plan.dump(), 1));
  center.OnPlan(PlanMessage("{\"type\": \"Feature", 2));
  EXPECT_EQ(center.Plan(), plan);
  const nlohmann::json info = center.State()["plan"];
  EXPECT_EQ(info["version"], 1);
  EXPECT_THAT(info["error"].get<std::string>(), HasSubstr("not a GeoJSON FeatureCollection"));
  // A "type" that is not a string (a replayed log can hold anything): the same.
  center.OnPlan(PlanMessage(R"({"type": {"type": "FeatureCollection"}})", 3));
  EXPECT_EQ(center.Plan(), plan);
  EXPECT_THAT(center.State()["plan"]["error"].get<std::string>(),
              HasSubstr("not a GeoJSON FeatureCollection"));
}

TEST(CommandCenterPlan, APlanWithoutACameraIsShownButHasNoCoverage) {
  CommandCenter center({});
  nlohmann::json plan = PlanJson();
  plan.erase("camera");
  center.OnPlan(PlanMessage(plan.dump(), 1));
  EXPECT_EQ(center.Plan(), plan);
  EXPECT_THAT(center.State()["plan"]["error"].get<std::string>(), HasSubstr("camera"));
  EXPECT_EQ(center.Coverage()["rows"], 0);
}

TEST(CommandCenterPlan, CoverageIsARasterOverTheArea) {
  CommandCenter center({});
  center.OnPlan(PlanMessage(PlanJson().dump(), 1));
  const nlohmann::json coverage = center.Coverage();
  const double cell_m = coverage["cell_m"].get<double>();
  EXPECT_DOUBLE_EQ(cell_m, 5.0);
  const int rows = coverage["rows"].get<int>();
  const int cols = coverage["cols"].get<int>();
  // planner::CoverageGrid's raster: whole 5 m cells covering the area's bounds
  // (a side projection made a hair longer than 200 m gets one more column).
  EXPECT_GE(rows * cell_m, 100.0 - 0.05);
  EXPECT_LT(rows * cell_m, 100.0 + cell_m + 0.05);
  EXPECT_GE(cols * cell_m, 200.0 - 0.05);
  EXPECT_LT(cols * cell_m, 200.0 + cell_m + 0.05);
  ASSERT_EQ(coverage["corners"].size(), 4U);
  // SW, SE, NE, NW of the raster, from the rectangle's SW corner, to within a few centimetres.
  const common::LocalFrame frame(test::kOrigin);
  const double east_m = cols * cell_m;
  const double north_m = rows * cell_m;
  const std::pair<double, double> expected[] = {
      {0, 0}, {east_m, 0}, {east_m, north_m}, {0, north_m}};
  for (std::size_t i = 0; i < 4; ++i) {
    const common::EastNorth corner = frame.ToLocal(
        {coverage["corners"][i][0].get<double>(), coverage["corners"][i][1].get<double>()});
    EXPECT_NEAR(corner.east_m, expected[i].first, 0.05) << i;
    EXPECT_NEAR(corner.north_m, expected[i].second, 0.05) << i;
  }
  const std::size_t bytes = (static_cast<std::size_t>(rows * cols) + 7) / 8;
  EXPECT_EQ(coverage["seen"].get<std::string>().size(), (bytes + 2) / 3 * 4);
}

// A drone over the area marks the cells under its camera, as the server's
// coverage_fraction does (the same planner::CoverageGrid); one not heard yet or
// without a fix marks nothing.
TEST(CommandCenterPlan, ADroneOverTheAreaMarksTheCellsItsCameraSees) {
  CommandCenter center({});
  center.OnPlan(PlanMessage(PlanJson().dump(), 1));
  const auto seen_bits = [&] {
    std::size_t count = 0;
    const std::string seen = center.Coverage()["seen"].get<std::string>();
    for (const char c : seen) count += c != 'A' && c != '=' ? 1 : 0;  // base64 of a zero byte
    return count;
  };
  vehicle_state_t drone = test::Flying(1, {100.0, 50.0}, 60.0, 1'000'000);
  drone.has_position = false;
  const std::uint64_t version_of_plan = center.coverage_version();
  center.OnVehicleState(drone);
  EXPECT_EQ(seen_bits(), 0U);
  EXPECT_EQ(center.coverage_version(), version_of_plan) << "nothing seen: the raster is the same";
  drone.has_position = true;
  center.OnVehicleState(drone);
  const std::size_t first = seen_bits();
  EXPECT_GT(first, 0U);
  const std::uint64_t version_of_first = center.coverage_version();
  EXPECT_NE(version_of_first, version_of_plan);
  // The same telemetry sample published again (states go at 5 Hz, telemetry at
  // 1-2 Hz) is not marked again, even were its position another.
  vehicle_state_t again = test::Flying(1, {150.0, 50.0}, 60.0, 1'200'000);
  again.vehicle_time_ms = drone.vehicle_time_ms;
  center.OnVehicleState(again);
  EXPECT_EQ(seen_bits(), first);
  EXPECT_EQ(center.coverage_version(), version_of_first);
  again.vehicle_time_ms += 1000;  // a new sample there
  center.OnVehicleState(again);
  EXPECT_GT(seen_bits(), first);
  EXPECT_NE(center.coverage_version(), version_of_first);
}

// The plan changes with the lanes (a handover, an investigation): the cells seen
// stay while the area, no-fly zones and camera are the same; a new area starts
// a new raster.
TEST(CommandCenterPlan, NewLanesKeepTheCoverageANewAreaStartsAfresh) {
  CommandCenter center({});
  nlohmann::json plan = PlanJson();
  center.OnPlan(PlanMessage(plan.dump(), 1'000'000));
  center.OnVehicleState(test::Flying(1, {100.0, 50.0}, 60.0, 1'000'000));
  const std::string seen = center.Coverage()["seen"].get<std::string>();
  ASSERT_NE(seen.find_first_not_of("A="), std::string::npos) << "some cell seen";
  plan["features"][1]["geometry"]["coordinates"][1] =
      plan["features"][1]["geometry"]["coordinates"][0];
  const std::uint64_t version_before_lanes = center.coverage_version();
  center.OnPlan(PlanMessage(plan.dump(), 6'000'000));
  EXPECT_EQ(center.State()["plan"]["version"], 2) << "the plan did change";
  EXPECT_EQ(center.Coverage()["seen"].get<std::string>(), seen);
  EXPECT_EQ(center.coverage_version(), version_before_lanes) << "the raster did not";
  plan["features"][0]["geometry"]["coordinates"][0][2][0] =
      plan["features"][0]["geometry"]["coordinates"][0][2][0].get<double>() + 0.001;
  center.OnPlan(PlanMessage(plan.dump(), 11'000'000));
  EXPECT_NE(center.coverage_version(), version_before_lanes);
  EXPECT_EQ(center.Coverage()["seen"].get<std::string>().find_first_not_of("A="), std::string::npos)
      << "nothing seen yet over the new area";
}

}  // namespace
}  // namespace fireswarm::server
