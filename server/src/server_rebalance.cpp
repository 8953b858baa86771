// Keeping the fleet together to the end. The plan balances the drones' sorties,
// but a mission does not keep to it: an investigation costs its drone minutes of
// battery, a sortie cut short by a low battery leaves a rest that needs a sortie
// of its own, and on a real boundary a few drones ended an hour after the rest,
// which stood on the ground with fresh packs. So a drone done with its sorties,
// landed with a fresh pack, takes the last sortie not yet started of the drone
// with the most still to start at its own launch site. The sortie never went up,
// so nothing is recalled: the donor just has one sortie less to fly, and the
// taker flies it at its own altitudes (its layer, its way home) as a new mission.
#include <cmath>
#include <optional>
#include <utility>
#include <vector>

#include "fireswarm/server/server.hpp"

namespace fireswarm::server {

bool Server::ReadyForASortie(std::uint8_t vehicle, double now_s) const {
  if (mission_->progress(vehicle).phase != DronePhase::kDone) return false;
  if (handed_over_.contains(vehicle) || registry_.LinkAt(vehicle, now_s) != LinkState::kOk) {
    return false;
  }
  const std::optional<radio::Telemetry>& telemetry = registry_.state(vehicle).telemetry;
  return telemetry && telemetry->mode == radio::FlightMode::kLanded &&
         telemetry->battery_percent >= kFreshPackPercent &&
         (telemetry->flags & radio::telemetry_flags::kLowBattery) == 0 &&
         stand_en_m_.contains(vehicle);
}

std::optional<std::uint8_t> Server::SortieDonorFor(std::uint8_t taker) const {
  const Eigen::Vector2d& stand = stand_en_m_.at(taker);
  std::optional<std::uint8_t> donor;
  std::size_t most = 0;
  std::size_t most_waypoints = 0;
  for (const std::uint8_t id : mission_->vehicles()) {  // ascending: ties go to the lowest
    const auto other = stand_en_m_.find(id);
    if (id == taker || other == stand_en_m_.end() ||
        (other->second - stand).norm() > config_.same_site_m) {
      continue;
    }
    const std::size_t unstarted = mission_->UnstartedSorties(id);
    // A mission's only sortie is never given away (MissionManager::TakeLastSortie).
    if (unstarted == 0 || SortieCount(mission_->mission_of(id)) < 2) continue;
    const std::size_t waypoints = mission_->Remaining(id, /*from_leg_start=*/false).size();
    if (unstarted > most || (unstarted == most && waypoints > most_waypoints)) {
      donor = id;
      most = unstarted;
      most_waypoints = waypoints;
    }
  }
  return donor;
}

void Server::RebalanceSorties(double now_s) {
  if (!mission_ || !config_.rebalance_sorties || state_ != MissionState::kRunning) return;
  for (const std::uint8_t taker : mission_->vehicles()) {
    if (!ReadyForASortie(taker, now_s)) continue;
    const std::optional<std::uint8_t> donor = SortieDonorFor(taker);
    if (!donor) continue;
    // Above every mission ID in use, taken before the donor's last sortie goes.
    const auto mission_id = static_cast<std::uint16_t>(mission_->LastMissionId() + 1);
    const std::vector<radio::Waypoint>& given = mission_->mission_of(*donor).waypoints;
    const std::vector<radio::Waypoint>& own = mission_->mission_of(taker).waypoints;
    const double donor_search_m = given.front().altitude_m;
    const double donor_home_m = given.back().altitude_m;
    std::vector<radio::Waypoint> sortie = *mission_->TakeLastSortie(*donor);
    // With an airspace plan the sortie keeps its altitudes: the donor's search
    // layer is the one its region was deconflicted in, and its transits' layers
    // are by heading from the site the two share (airspace.hpp). Without one, the
    // taker's own layer and way home (its mission's first and last altitude).
    if (!own.empty() && !airspace_) {
      for (radio::Waypoint& waypoint : sortie) {
        if (waypoint.altitude_m == donor_search_m) {
          waypoint.altitude_m = own.front().altitude_m;
        } else if (waypoint.altitude_m == donor_home_m) {
          waypoint.altitude_m = own.back().altitude_m;
        }
      }
    }
    DroneMission mission;
    mission.vehicle = taker;
    mission.mission_id = mission_id;
    mission.waypoints = std::move(sortie);
    Record(now_s, SortieMoved{*donor, mission});
    mission_->Replace(std::move(mission));
  }
}

}  // namespace fireswarm::server
