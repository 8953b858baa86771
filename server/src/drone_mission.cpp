// A drone's mission as data: its sorties (where they begin in the route, the
// radio mission each goes up as), the planner's plan turned into missions, and
// the launch sites taken off each sortie's ends. MissionManager flies them.
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

#include "fireswarm/radio/mission_chunks.hpp"
#include "fireswarm/server/mission_manager.hpp"

namespace fireswarm::server {

namespace {

// Waypoints this close to the launch site count as the launch site, m.
constexpr double kLaunchSiteM = 1.0;

}  // namespace

std::size_t SortieCount(const DroneMission& mission) {
  return mission.sortie_starts.size() + 1;
}

std::pair<std::size_t, std::size_t> SortieRange(const DroneMission& mission, std::size_t sortie) {
  const std::size_t count = SortieCount(mission);
  if (sortie >= count) {
    throw std::out_of_range("vehicle " + std::to_string(mission.vehicle) + " has no sortie " +
                            std::to_string(sortie + 1) + " (it has " + std::to_string(count) + ")");
  }
  const std::size_t first = sortie == 0 ? 0 : mission.sortie_starts[sortie - 1];
  const std::size_t end =
      sortie + 1 < count ? mission.sortie_starts[sortie] : mission.waypoints.size();
  return {first, end};
}

std::uint16_t SortieMissionId(const DroneMission& mission, std::size_t sortie) {
  return static_cast<std::uint16_t>(mission.mission_id + sortie);
}

std::size_t SortieOf(const DroneMission& mission, std::size_t waypoint) {
  return static_cast<std::size_t>(std::ranges::upper_bound(mission.sortie_starts, waypoint) -
                                  mission.sortie_starts.begin());
}

std::vector<std::vector<radio::Waypoint>> SortiesOf(const DroneMission& mission) {
  std::vector<std::vector<radio::Waypoint>> sorties;
  for (std::size_t k = 0; k < SortieCount(mission); ++k) {
    const auto [first, end] = SortieRange(mission, k);
    sorties.emplace_back(mission.waypoints.begin() + static_cast<std::ptrdiff_t>(first),
                         mission.waypoints.begin() + static_cast<std::ptrdiff_t>(end));
  }
  return sorties;
}

void SetSorties(DroneMission& mission, const std::vector<std::vector<radio::Waypoint>>& sorties) {
  mission.waypoints.clear();
  mission.sortie_starts.clear();
  for (const std::vector<radio::Waypoint>& sortie : sorties) {
    if (sortie.empty()) continue;
    if (!mission.waypoints.empty()) mission.sortie_starts.push_back(mission.waypoints.size());
    mission.waypoints.insert(mission.waypoints.end(), sortie.begin(), sortie.end());
  }
}

std::vector<DroneMission> ToDroneMissions(const planner::Plan& plan, std::uint16_t mission_id,
                                          double altitude_m, double speed_mps) {
  std::vector<DroneMission> missions;
  for (const planner::DronePlan& drone : plan.drones) {
    if (drone.receiver_id < 1 || drone.receiver_id > 254) {
      throw std::invalid_argument("receiver ID " + std::to_string(drone.receiver_id) +
                                  " is outside 1..254");
    }
    DroneMission mission;
    mission.vehicle = static_cast<std::uint8_t>(drone.receiver_id);
    mission.mission_id = mission_id;
    for (std::size_t i = 0; i < drone.waypoints.size(); ++i) {
      const planner::Waypoint& point = drone.waypoints[i];
      radio::Waypoint waypoint;
      waypoint.lat_deg = point.geodetic.lat_deg;
      waypoint.lon_deg = point.geodetic.lon_deg;
      waypoint.altitude_m = altitude_m;
      waypoint.speed_mps = speed_mps;
      waypoint.flags = point.starts_lane ? radio::Waypoint::kLaneStart : std::uint8_t{0};
      mission.waypoints.push_back(waypoint);
      // The landing that ends a sortie is its last waypoint; the next sortie
      // starts after it.
      if (point.is_return && i + 1 < drone.waypoints.size()) {
        mission.sortie_starts.push_back(mission.waypoints.size());
      }
    }
    for (std::size_t k = 0; k < SortieCount(mission); ++k) {
      const auto [first, end] = SortieRange(mission, k);
      if (end - first > radio::kMaxMissionWaypoints) {
        throw std::invalid_argument("drone " + std::to_string(drone.receiver_id) + " has " +
                                    std::to_string(end - first) + " waypoints in sortie " +
                                    std::to_string(k + 1) + "; a mission holds at most " +
                                    std::to_string(radio::kMaxMissionWaypoints));
      }
    }
    missions.push_back(std::move(mission));
  }
  return missions;
}

std::vector<DroneMission> WithoutLaunchSite(
    std::vector<DroneMission> missions, const common::LocalFrame& frame,
    const std::map<std::uint8_t, common::EastNorth>& launch_of) {
  for (DroneMission& mission : missions) {
    const auto site = launch_of.find(mission.vehicle);
    if (site == launch_of.end()) continue;
    const common::EastNorth launch = site->second;
    const auto at_launch = [&](const radio::Waypoint& waypoint) {
      const common::EastNorth local = frame.ToLocal({waypoint.lat_deg, waypoint.lon_deg});
      return std::hypot(local.east_m - launch.east_m, local.north_m - launch.north_m) <
             kLaunchSiteM;
    };
    std::vector<std::vector<radio::Waypoint>> sorties = SortiesOf(mission);
    for (std::vector<radio::Waypoint>& route : sorties) {
      while (!route.empty() && at_launch(route.back())) route.pop_back();
      std::size_t first = 0;
      while (first < route.size() && at_launch(route[first])) ++first;
      route.erase(route.begin(), route.begin() + static_cast<std::ptrdiff_t>(first));
    }
    SetSorties(mission, sorties);
  }
  return missions;
}

std::vector<DroneMission> WithoutLaunchSite(std::vector<DroneMission> missions,
                                            const common::LocalFrame& frame,
                                            common::EastNorth launch) {
  std::map<std::uint8_t, common::EastNorth> launch_of;
  for (const DroneMission& mission : missions) launch_of[mission.vehicle] = launch;
  return WithoutLaunchSite(std::move(missions), frame, launch_of);
}

std::map<std::uint8_t, common::EastNorth> LaunchSitesOf(const planner::Plan& plan) {
  std::map<std::uint8_t, common::EastNorth> sites;
  for (const planner::DronePlan& drone : plan.drones) {
    sites[static_cast<std::uint8_t>(drone.receiver_id)] = {drone.launch.x(), drone.launch.y()};
  }
  return sites;
}

}  // namespace fireswarm::server
