#include "fireswarm/server/investigations.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <boost/geometry/algorithms/correct.hpp>
#include <chrono>
#include <string>
#include <vector>

#include "fireswarm/common/time.hpp"
#include "server/server_fixture.hpp"

namespace fireswarm::server {
namespace {

using common::Nanos;
using ::testing::HasSubstr;

using testing::kFrame;

// A vehicle at `east_m, north_m` of the frame's origin in `mode`.
radio::Telemetry At(std::uint8_t id, double east_m, double north_m,
                    radio::FlightMode mode = radio::FlightMode::kSearch) {
  const common::LatLon where = kFrame.ToGeodetic({east_m, north_m});
  radio::Telemetry telemetry;
  telemetry.header.sender = id;
  telemetry.lat_deg = where.lat_deg;
  telemetry.lon_deg = where.lon_deg;
  telemetry.altitude_m = 60.0;
  telemetry.mode = mode;
  telemetry.flags = radio::telemetry_flags::kGpsFix | radio::telemetry_flags::kMissionValid;
  telemetry.battery_percent = 90;
  return telemetry;
}

Eigen::Vector2d Local(double east_m, double north_m) {
  return {east_m, north_m};
}

// The square [west, east] x [south, north] of local metres as a no-fly zone.
planner::MultiPolygon Zone(double west_m, double south_m, double east_m, double north_m) {
  planner::Polygon square;
  square.outer() = {{west_m, south_m},
                    {west_m, north_m},
                    {east_m, north_m},
                    {east_m, south_m},
                    {west_m, south_m}};
  boost::geometry::correct(square);
  return {square};
}

// Investigations over three registered vehicles (1 at the origin, 2 at 300 m
// east, 3 at 2 km east, all searching), optionally with one no-fly zone.
struct Fixture {
  explicit Fixture(planner::MultiPolygon no_fly = {}) {
    config.no_fly = no_fly;
    if (!no_fly.empty()) {
      transit = std::make_unique<planner::TransitPlanner>(
          no_fly, planner::Box{{-5'000.0, -5'000.0}, {5'000.0, 5'000.0}}, 1U);
    }
    investigations.emplace(config, kFrame, transit.get());
    const double east_m[] = {0.0, 300.0, 2'000.0};
    for (std::uint8_t id = 1; id <= 3; ++id) {
      registry.Register(id);
      registry.OnTelemetry(At(id, east_m[id - 1], 0.0), 1.0);
    }
  }
  InvestigationsConfig config;
  std::unique_ptr<planner::TransitPlanner> transit;
  VehicleRegistry registry;
  std::optional<Investigations> investigations;
};

// A tentative track at `east_m, north_m` reported by `vehicle` at `time_s`.
std::int32_t TrackAt(FireFusion& fusion, double east_m, double north_m, std::uint8_t vehicle,
                     double time_s, std::uint16_t report_id = 1) {
  FireObservation o;
  o.vehicle_id = vehicle;
  o.report_id = report_id;
  o.detection_time_s = time_s;
  o.position_en_m = Local(east_m, north_m);
  o.covariance_en_m2 = Eigen::Matrix2d::Identity() * 9.0;
  o.observer_en_m = Local(east_m, north_m - 20.0);
  o.confidence = 0.9;
  return fusion.Add(o).track_id;
}

TEST(Investigations, ChoosesTheNearestSearchingVehicleOtherThanTheReporter) {
  Fixture f;
  const Eigen::Vector2d fire = Local(150.0, 0.0);
  // 1 is as near as 2, but it reported the fire: 2's view is independent.
  EXPECT_EQ(f.investigations->BestPlacedFor(f.registry, fire, 20.0, 1, 2.0, nullptr), 2);
  // Reported by someone else: the nearest wins.
  EXPECT_EQ(f.investigations->BestPlacedFor(f.registry, Local(1'900.0, 0.0), 20.0, 1, 2.0, nullptr),
            3);
  // Only the reporter can go: it goes.
  f.registry.OnTelemetry(At(2, 300.0, 0.0, radio::FlightMode::kReturnToLaunch), 2.0);
  f.registry.OnTelemetry(At(3, 2'000.0, 0.0, radio::FlightMode::kLand), 2.0);
  EXPECT_EQ(f.investigations->BestPlacedFor(f.registry, fire, 20.0, 1, 2.0, nullptr), 1);
}

TEST(Investigations, PassesOverBusyAndNonSearchingVehiclesAndSaysWhyNoneIsLeft) {
  Fixture f;
  const common::LatLon point = kFrame.ToGeodetic({150.0, 0.0});
  f.investigations->Open(f.registry, 2, point, 0.0, 7, 2.0);
  EXPECT_EQ(f.investigations->BestPlacedFor(f.registry, Local(150.0, 0.0), 20.0, 0, 3.0, nullptr),
            1);
  f.registry.OnTelemetry(At(1, 0.0, 0.0, radio::FlightMode::kInvestigate), 3.0);
  f.registry.OnTelemetry(At(3, 2'000.0, 0.0, radio::FlightMode::kHold), 3.0);
  std::string why;
  EXPECT_EQ(f.investigations->BestPlacedFor(f.registry, Local(150.0, 0.0), 20.0, 0, 3.0, &why),
            std::nullopt);
  EXPECT_EQ(why, "no searching vehicle with a working link");
}

TEST(Investigations, OpenCountsTheTransitToThePointInTheOrder) {
  Fixture f;
  // 2 km from vehicle 3 at 8 m/s is 250 s of transit before 60 s on the circle.
  const InvestigationOrder order =
      f.investigations->Open(f.registry, 3, kFrame.ToGeodetic({0.0, 0.0}), 25.0, 4, 10.0);
  EXPECT_EQ(order.command.type, radio::CommandType::kInvestigate);
  EXPECT_EQ(order.command.duration_s, 310);
  EXPECT_EQ(order.command.radius_m, 25.0);
  EXPECT_EQ(order.investigation.until_s, 320.0);
  EXPECT_EQ(order.investigation.track_id, 4);
  EXPECT_NEAR(order.investigation.point_en_m.norm(), 0.0, 1e-6);
  ASSERT_EQ(f.investigations->all().size(), 1U);
  EXPECT_EQ(f.investigations->all()[0].vehicle, 3);
}

TEST(Investigations, RefusesACircleInOrEnteringANoFlyZone) {
  Fixture f(Zone(100.0, 100.0, 200.0, 200.0));
  EXPECT_EQ(f.investigations->CircleRefusal(Local(150.0, 150.0), 20.0),
            "the point is inside a no-fly zone");
  EXPECT_EQ(f.investigations->CircleRefusal(Local(150.0, 90.0), 20.0),
            "the 20 m circle around the point enters a no-fly zone");
  EXPECT_EQ(f.investigations->CircleRefusal(Local(150.0, 50.0), 20.0), std::nullopt);
  Fixture open;
  EXPECT_EQ(open.investigations->CircleRefusal(Local(150.0, 150.0), 20.0), std::nullopt);
}

TEST(Investigations, RefusesAnApproachThatCrossesANoFlyZone) {
  // A zone between vehicle 2 (300 m east) and a point 300 m north of it.
  Fixture f(Zone(250.0, 100.0, 350.0, 200.0));
  const Eigen::Vector2d point = Local(300.0, 300.0);
  const std::optional<std::string> no =
      f.investigations->ApproachRefusal(f.registry, 2, point, 20.0);
  ASSERT_TRUE(no.has_value());
  EXPECT_THAT(*no, HasSubstr("vehicle 2's straight way to the circle"));
  // Vehicle 1 at the origin flies past the zone's west side: it is chosen.
  EXPECT_EQ(f.investigations->ApproachRefusal(f.registry, 1, point, 20.0), std::nullopt);
  EXPECT_EQ(f.investigations->BestPlacedFor(f.registry, point, 20.0, 0, 2.0, nullptr), 1);
}

TEST(Investigations, SaysHowManyVehiclesTheZonesBlocked) {
  // A wall east-west between every vehicle and the point.
  Fixture f(Zone(-500.0, 100.0, 2'500.0, 200.0));
  std::string why;
  EXPECT_EQ(f.investigations->BestPlacedFor(f.registry, Local(300.0, 400.0), 20.0, 0, 2.0, &why),
            std::nullopt);
  EXPECT_THAT(why, HasSubstr("(3 would cross one)"));
}

TEST(Investigations, RefusesAnApproachItCannotCheckForAVehicleNeverHeard) {
  Fixture f(Zone(100.0, 100.0, 200.0, 200.0));
  f.registry.Register(9);
  const std::optional<std::string> no =
      f.investigations->ApproachRefusal(f.registry, 9, Local(0.0, 500.0), 20.0);
  ASSERT_TRUE(no.has_value());
  EXPECT_THAT(*no, HasSubstr("vehicle 9 has sent no position"));
}

TEST(Investigations, RejectsATrackTheInvestigatorDidNotSeeAgain) {
  Fixture f;
  FireFusion fusion;
  const std::int32_t track = TrackAt(fusion, 150.0, 0.0, 1, 2.0);
  const InvestigationOrder order =
      f.investigations->Open(f.registry, 2, kFrame.ToGeodetic({150.0, 0.0}), 0.0, track, 2.0);
  f.investigations->OnPosition(2, Local(160.0, 0.0), 30.0);  // it got there
  const Nanos due = common::FromSeconds(order.investigation.until_s + f.config.reject_grace_s);
  EXPECT_EQ(f.investigations->NextVerdict(fusion, Nanos::max()), due);
  EXPECT_TRUE(f.investigations->Judge(due - Nanos{1}, fusion).empty());
  const std::vector<Rejection> rejected = f.investigations->Judge(due, fusion);
  ASSERT_EQ(rejected.size(), 1U);
  EXPECT_EQ(rejected[0].track_id, track);
  EXPECT_EQ(rejected[0].by_vehicle, 2);
  EXPECT_EQ(fusion.Find(track)->status, FireTrackStatus::kRejected);
  EXPECT_TRUE(f.investigations->all()[0].judged);
  EXPECT_EQ(f.investigations->NextVerdict(fusion, Nanos::max()), Nanos::max());
}

TEST(Investigations, KeepsATrackTheInvestigatorSawAgain) {
  Fixture f;
  FireFusion fusion;
  const std::int32_t track = TrackAt(fusion, 150.0, 0.0, 1, 2.0);
  // The reporter is the only one sent; it sees the fire again from the same
  // place soon after: not an independent view, so the track stays tentative.
  f.investigations->Open(f.registry, 1, kFrame.ToGeodetic({150.0, 0.0}), 0.0, track, 2.0);
  f.investigations->OnPosition(1, Local(150.0, 10.0), 10.0);
  TrackAt(fusion, 151.0, 0.0, 1, 12.0, 2);
  ASSERT_EQ(fusion.Find(track)->status, FireTrackStatus::kTentative);
  EXPECT_TRUE(f.investigations->Judge(common::FromSeconds(1'000.0), fusion).empty());
  EXPECT_EQ(fusion.Find(track)->status, FireTrackStatus::kTentative);
  EXPECT_TRUE(f.investigations->all()[0].judged);
}

TEST(Investigations, JudgesNothingWhenTheInvestigatorNeverGotNear) {
  Fixture f;
  FireFusion fusion;
  const std::int32_t track = TrackAt(fusion, 150.0, 0.0, 1, 2.0);
  f.investigations->Open(f.registry, 3, kFrame.ToGeodetic({150.0, 0.0}), 0.0, track, 2.0);
  f.investigations->OnPosition(3, Local(1'000.0, 0.0), 30.0);  // still far away
  // A position after the investigation ended does not count.
  f.investigations->OnPosition(3, Local(150.0, 0.0), 10'000.0);
  EXPECT_TRUE(f.investigations->Judge(common::FromSeconds(20'000.0), fusion).empty());
  EXPECT_EQ(fusion.Find(track)->status, FireTrackStatus::kTentative);
  EXPECT_TRUE(f.investigations->all()[0].judged);
}

TEST(Investigations, EndsTheRunningInvestigationsOfAConfirmedTrack) {
  Fixture f;
  const common::LatLon point = kFrame.ToGeodetic({150.0, 0.0});
  f.investigations->Open(f.registry, 2, point, 0.0, 5, 2.0);
  f.investigations->Open(f.registry, 3, point, 0.0, 6, 2.0);
  EXPECT_EQ(f.investigations->EndForConfirmed(5, 40.0), std::vector<std::uint8_t>{2});
  EXPECT_EQ(f.investigations->all()[0].until_s, 40.0);
  EXPECT_TRUE(f.investigations->EndForConfirmed(5, 41.0).empty());  // over already
}

TEST(Investigations, RestoresAnInvestigationAsItWasOpened) {
  Fixture f;
  Investigation saved;
  saved.vehicle = 2;
  saved.track_id = 3;
  saved.started_s = 5.0;
  saved.until_s = 90.0;
  saved.point_en_m = Local(150.0, 0.0);
  f.investigations->Restore(saved);
  ASSERT_EQ(f.investigations->all().size(), 1U);
  EXPECT_EQ(f.investigations->all()[0].until_s, 90.0);
  // Restored, it keeps the vehicle busy like any other.
  EXPECT_EQ(f.investigations->BestPlacedFor(f.registry, Local(150.0, 0.0), 20.0, 0, 3.0, nullptr),
            1);
}

TEST(Investigations, RadiusIsTheOrderedThenTheConfiguredThenTheVehiclesOwn) {
  InvestigationsConfig config;
  EXPECT_EQ(Investigations(config, kFrame, nullptr).RadiusM(0.0), 20.0);
  EXPECT_EQ(Investigations(config, kFrame, nullptr).RadiusM(35.0), 35.0);
  config.investigate_radius_m = 50.0;
  EXPECT_EQ(Investigations(config, kFrame, nullptr).RadiusM(0.0), 50.0);
}

}  // namespace
}  // namespace fireswarm::server
