// Strategic deconfliction: search layers by drone, transit layers by heading
// sector, the way home; and the assignment surviving a restart (journal).
#include "fireswarm/server/airspace.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <set>
#include <vector>

#include "fireswarm/server/journal_format.hpp"
#include "fireswarm/server/server.hpp"

namespace fireswarm::server {
namespace {

const common::LocalFrame kFrame{common::LatLon{46.0, -74.5}};
constexpr double kBaseM = 60.0;

radio::Waypoint Point(double east_m, double north_m, std::uint8_t flags) {
  const common::LatLon p = kFrame.ToGeodetic({east_m, north_m});
  radio::Waypoint w;
  w.lat_deg = p.lat_deg;
  w.lon_deg = p.lon_deg;
  w.altitude_m = kBaseM;
  w.speed_mps = 10.0;
  w.flags = flags;
  return w;
}

// Drone `id`'s region 1 km north-east of the site: two lanes, then a jump of
// 670 m east-south-east to a third (a transit), over the site at (0, 0).
DroneMission Region(std::uint8_t id) {
  DroneMission m;
  m.vehicle = id;
  m.mission_id = 1;
  const double east_m = 1'000.0 + 20.0 * id;
  m.waypoints = {Point(east_m, 1'000, radio::Waypoint::kLaneStart), Point(east_m, 1'400, 0),
                 Point(east_m + 20, 1'400, radio::Waypoint::kLaneStart),
                 Point(east_m + 20, 1'000, 0),
                 Point(east_m + 620, 700, radio::Waypoint::kLaneStart),
                 Point(east_m + 620, 1'100, 0)};
  return m;
}

std::map<std::uint8_t, common::EastNorth> SitesAtOrigin(int drones) {
  std::map<std::uint8_t, common::EastNorth> sites;
  for (int id = 1; id <= drones; ++id) sites[static_cast<std::uint8_t>(id)] = {0.0, 0.0};
  return sites;
}

TEST(AssignAirspace, SearchesInLayersByDroneAndTransitsInLayersByHeading) {
  std::vector<DroneMission> missions;
  for (std::uint8_t id = 1; id <= 6; ++id) missions.push_back(Region(id));
  const SeparationConfig config;
  const AirspacePlan plan =
      AssignAirspace(missions, kFrame, SitesAtOrigin(6), kBaseM, config);
  ASSERT_EQ(plan.drones.size(), 6U);
  EXPECT_FALSE(plan.rule.empty());
  for (std::size_t k = 0; k < missions.size(); ++k) {
    const double search_m = kBaseM + config.layer_m * static_cast<double>(k % 3);
    EXPECT_DOUBLE_EQ(plan.drones[k].search_altitude_m, search_m);
    const std::vector<radio::Waypoint>& route = missions[k].waypoints;
    // Climb-out transit (north-east: sector 0 of 4), the six search waypoints
    // with a transit pair between lanes 2 and 3 (117 deg: sector 1), the way home
    // (south-west: sector 2).
    ASSERT_EQ(route.size(), 1U + 6U + 2U + 1U) << "drone " << k;
    const double transit_base_m = kBaseM + config.layer_m * config.search_layers;
    EXPECT_DOUBLE_EQ(route[0].altitude_m, transit_base_m + 0 * config.layer_m);
    for (const std::size_t i : {1U, 2U, 3U, 4U, 7U, 8U}) {
      EXPECT_DOUBLE_EQ(route[i].altitude_m, search_m) << "drone " << k << " waypoint " << i;
    }
    EXPECT_DOUBLE_EQ(route[5].altitude_m, transit_base_m + 1 * config.layer_m);
    EXPECT_DOUBLE_EQ(route[6].altitude_m, transit_base_m + 1 * config.layer_m);
    EXPECT_EQ(route[5].flags, 0);  // no lane starts up there
    EXPECT_DOUBLE_EQ(route.back().altitude_m, transit_base_m + 2 * config.layer_m);
    EXPECT_EQ(route.back().flags, 0);
    EXPECT_DOUBLE_EQ(route.back().lat_deg, route[route.size() - 2].lat_deg);
  }
}

TEST(AssignAirspace, OppositeHeadingsNeverShareATransitLayer) {
  AirspacePlan plan;
  plan.base_altitude_m = kBaseM;
  plan.layer_m = 15.0;
  plan.search_layers = 3;
  plan.transit_sectors = 4;
  for (double deg = 0.0; deg < 360.0; deg += 7.5) {
    const double heading = deg * std::numbers::pi / 180.0;
    EXPECT_NE(TransitAltitudeM(plan, heading), TransitAltitudeM(plan, heading + std::numbers::pi))
        << deg << " deg";
    EXPECT_GT(TransitAltitudeM(plan, heading), kBaseM + 2 * plan.layer_m);
  }
}

TEST(AssignAirspace, WithoutLayersOnlyTheWayHomeIsAdded) {
  std::vector<DroneMission> missions = {Region(1), Region(2)};
  SeparationConfig config;
  config.layers = false;
  const AirspacePlan plan = AssignAirspace(missions, kFrame, SitesAtOrigin(2), kBaseM, config);
  for (const DroneMission& m : missions) {
    ASSERT_EQ(m.waypoints.size(), 7U);
    for (const radio::Waypoint& w : m.waypoints) EXPECT_DOUBLE_EQ(w.altitude_m, kBaseM);
  }
  EXPECT_EQ(plan.search_layers, 1);
}

TEST(AssignAirspace, EverySortieGetsItsOwnWayHome) {
  std::vector<DroneMission> missions = {Region(1)};
  missions[0].sortie_starts = {4};  // sorties of 4 and 2 waypoints
  AssignAirspace(missions, kFrame, SitesAtOrigin(1), kBaseM, SeparationConfig{});
  const std::vector<std::vector<radio::Waypoint>> sorties = SortiesOf(missions[0]);
  ASSERT_EQ(sorties.size(), 2U);
  for (const std::vector<radio::Waypoint>& sortie : sorties) {
    EXPECT_EQ(sortie.back().flags, 0);
    EXPECT_GT(sortie.back().altitude_m, kBaseM + 2 * 15.0);
  }
}

TEST(AssignAirspace, ARestoredServerKeepsTheAssignments) {
  std::vector<DroneMission> missions;
  for (std::uint8_t id = 1; id <= 4; ++id) missions.push_back(Region(id));
  const AirspacePlan plan = AssignAirspace(missions, kFrame, SitesAtOrigin(4), kBaseM, {});
  Server original(ServerConfig{}, kFrame);
  for (std::uint8_t id = 1; id <= 4; ++id) original.AddVehicle(id);
  original.LoadMission(missions, 0.0, plan);
  // Through the journal's own text: each entry written as its record and read back.
  std::vector<JournalEntry> read_back;
  std::uint64_t seq = 0;
  for (const JournalEntry& entry : original.TakeJournalEntries()) {
    JournalRecord record;
    record.seq = ++seq;
    record.t_s = entry.t_s;
    record.kind = JournalKindOf(entry);
    record.data = nlohmann::json::parse(JournalDataOf(entry).dump());
    read_back.push_back(JournalEntryOf(record));
  }
  const Server restored = Server::Restore(ServerConfig{}, kFrame, read_back);
  ASSERT_TRUE(restored.airspace().has_value());
  EXPECT_EQ(*restored.airspace(), plan);
  ASSERT_NE(restored.mission(), nullptr);
  for (const DroneMission& m : missions) {
    EXPECT_EQ(restored.mission()->mission_of(m.vehicle).waypoints.size(), m.waypoints.size());
  }
}

}  // namespace
}  // namespace fireswarm::server
