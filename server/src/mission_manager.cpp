#include "fireswarm/server/mission_manager.hpp"

#include <algorithm>
#include <stdexcept>
#include <utility>
#include <variant>

#include "fireswarm/common/time.hpp"
#include "fireswarm/radio/mission_chunks.hpp"

namespace fireswarm::server {

const char* ToString(DronePhase phase) {
  switch (phase) {
    case DronePhase::kUploading:
      return "uploading";
    case DronePhase::kStarting:
      return "starting";
    case DronePhase::kFlying:
      return "flying";
    case DronePhase::kDone:
      return "done";
    case DronePhase::kFailed:
      return "failed";
    case DronePhase::kSwapping:
      return "swapping";
  }
  return "unknown";
}

MissionManager::MissionManager(radio::ChannelRouter& scheduler,
                               std::vector<DroneMission> missions,
                               const MissionManagerConfig& config)
    : scheduler_(scheduler), config_(config) {
  for (DroneMission& mission : missions) {
    const std::uint8_t vehicle = mission.vehicle;
    if (drones_.contains(vehicle)) {
      throw std::invalid_argument("vehicle " + std::to_string(vehicle) +
                                  " has two missions in one plan");
    }
    by_id_[vehicle] = &drones_.emplace(vehicle, DroneFor(std::move(mission))).first->second;
    next_wakeup_.reset();
  }
  for (const auto& [vehicle, drone] : drones_) vehicles_.push_back(vehicle);
}

MissionManager::Drone MissionManager::DroneFor(DroneMission mission) {
  Drone drone;
  drone.progress.waypoint_count = mission.waypoints.size();
  drone.progress.sortie_count = SortieCount(mission);
  drone.mission = std::move(mission);
  if (drone.mission.waypoints.empty()) {
    drone.progress.phase = DronePhase::kDone;  // nothing to fly: it stays on its stand
    return drone;
  }
  LoadSortie(drone, 0);
  return drone;
}

void MissionManager::LoadSortie(Drone& drone, std::size_t sortie) {
  const auto [first, end] = SortieRange(drone.mission, sortie);
  const std::vector<radio::Waypoint> waypoints(
      drone.mission.waypoints.begin() + static_cast<std::ptrdiff_t>(first),
      drone.mission.waypoints.begin() + static_cast<std::ptrdiff_t>(end));
  drone.chunks = radio::SplitMission(SortieMissionId(drone.mission, sortie), waypoints);
  drone.chunk_rounds.assign(drone.chunks.size(), 0);
  drone.progress.sortie = sortie;
  drone.progress.chunk_count = drone.chunks.size();
  drone.progress.chunks_acked = 0;
  drone.progress.start_refusals = 0;
  drone.progress.waypoint_index = std::max(drone.progress.waypoint_index, first);
}

void MissionManager::Replace(DroneMission mission, bool send) {
  const std::uint8_t vehicle = mission.vehicle;
  Drone& drone = Find(vehicle);
  if (mission.mission_id == drone.mission.mission_id) {
    throw std::invalid_argument("vehicle " + std::to_string(vehicle) + " already has mission " +
                                std::to_string(mission.mission_id));
  }
  // Answers to the old mission's requests are no longer this drone's business.
  std::erase_if(pending_, [&](const auto& entry) { return entry.second.vehicle == vehicle; });
  const std::size_t flown = drone.progress.sorties_flown;
  const bool swapping = drone.progress.phase == DronePhase::kSwapping;
  drone = DroneFor(std::move(mission));
  next_wakeup_.reset();
  drone.progress.sorties_flown = flown;
  ++missions_version_;
  if (swapping) {
    // On the ground for its pack: the new mission's first sortie waits for it too.
    drone.progress.phase = DronePhase::kSwapping;
    drone.next_sortie = 0;
    return;
  }
  if (!send) return;
  for (std::size_t i = 0; i < drone.chunks.size(); ++i) SendChunk(drone, i);
}

void MissionManager::MarkLost(std::uint8_t vehicle, std::string why) {
  Drone& drone = Find(vehicle);
  std::erase_if(pending_, [&](const auto& entry) { return entry.second.vehicle == vehicle; });
  Fail(drone, std::move(why));
}

std::vector<radio::Waypoint> MissionManager::Remaining(
    std::uint8_t vehicle, bool from_leg_start, std::vector<std::size_t>* sortie_starts) const {
  const Drone& drone = Find(vehicle);
  const DroneMission& mission = drone.mission;
  const std::vector<radio::Waypoint>& route = mission.waypoints;
  if (sortie_starts != nullptr) sortie_starts->clear();
  std::size_t first = drone.progress.waypoint_index;
  std::size_t sortie = drone.progress.sortie;
  if (drone.progress.phase == DronePhase::kSwapping) {
    // Its sortie is flown: the next ones are still to fly, whole.
    sortie = drone.next_sortie;
    if (sortie >= SortieCount(mission)) return {};
    first = SortieRange(mission, sortie).first;
  } else if (from_leg_start && first > SortieRange(mission, sortie).first) {
    --first;
  }
  if (first >= route.size()) return {};
  if (sortie_starts != nullptr) {
    for (std::size_t k = sortie + 1; k < SortieCount(mission); ++k) {
      sortie_starts->push_back(SortieRange(mission, k).first - first);
    }
  }
  return {route.begin() + static_cast<std::ptrdiff_t>(first), route.end()};
}

std::size_t MissionManager::UnstartedSorties(std::uint8_t vehicle) const {
  const Drone& drone = Find(vehicle);
  const std::size_t count = SortieCount(drone.mission);
  switch (drone.progress.phase) {
    case DronePhase::kDone:
    case DronePhase::kFailed:
      return 0;
    case DronePhase::kSwapping:
      return count - std::min(count, drone.next_sortie);
    case DronePhase::kUploading:
    case DronePhase::kStarting:
    case DronePhase::kFlying:
      break;
  }
  return count - std::min(count, drone.progress.sortie + 1);
}

std::optional<std::vector<radio::Waypoint>> MissionManager::TakeLastSortie(std::uint8_t vehicle) {
  // A mission's only sortie stays (a mission handed to a drone on the ground
  // waits for its pack at its first).
  if (UnstartedSorties(vehicle) == 0 || SortieCount(Find(vehicle).mission) < 2) {
    return std::nullopt;
  }
  Drone& drone = Find(vehicle);
  DroneMission& mission = drone.mission;
  const std::size_t last = SortieCount(mission) - 1;
  const std::size_t first = SortieRange(mission, last).first;
  std::vector<radio::Waypoint> taken(mission.waypoints.begin() + static_cast<std::ptrdiff_t>(first),
                                     mission.waypoints.end());
  mission.waypoints.resize(first);
  mission.sortie_starts.pop_back();
  drone.progress.sortie_count = SortieCount(mission);
  drone.progress.waypoint_count = mission.waypoints.size();
  if (drone.progress.phase == DronePhase::kSwapping && drone.next_sortie >= last) {
    drone.progress.phase = DronePhase::kDone;
  }
  ++missions_version_;
  return taken;
}

std::uint16_t MissionManager::LastMissionId() const {
  std::uint16_t last = 0;
  for (const auto& [vehicle, drone] : drones_) {
    last = std::max(last, SortieMissionId(drone.mission, SortieCount(drone.mission) - 1));
  }
  return last;
}

const DroneMission& MissionManager::mission_of(std::uint8_t vehicle) const {
  return Find(vehicle).mission;
}

const MissionManager::Drone& MissionManager::Find(std::uint8_t vehicle) const {
  const Drone* drone = by_id_[vehicle];
  if (drone == nullptr) {
    throw std::out_of_range("vehicle " + std::to_string(vehicle) + " has no mission");
  }
  return *drone;
}

MissionManager::Drone& MissionManager::Find(std::uint8_t vehicle) {
  return const_cast<Drone&>(std::as_const(*this).Find(vehicle));
}

void MissionManager::Begin() {
  for (auto& [vehicle, drone] : drones_) {
    if (drone.progress.phase != DronePhase::kUploading) continue;
    for (std::size_t i = 0; i < drone.chunks.size(); ++i) SendChunk(drone, i);
  }
}

void MissionManager::SendChunk(Drone& drone, std::size_t index) {
  ++drone.chunk_rounds[index];
  const radio::RequestId id =
      scheduler_.SendMissionChunk(drone.mission.vehicle, drone.chunks[index]);
  pending_[id] = Pending{drone.mission.vehicle, static_cast<int>(index)};
}

void MissionManager::SendStart(Drone& drone, common::Nanos now, const StartGate& gate) {
  if (gate && !gate(drone.mission.vehicle, now)) {
    drone.progress.phase = DronePhase::kStarting;
    ++drone.progress.start_holds;
    SetRetry(drone, now + common::FromSeconds(config_.gate_retry_s));
    return;
  }
  radio::Command start;
  start.type = radio::CommandType::kStartMission;
  start.mission_id = SortieMissionId(drone.mission, drone.progress.sortie);
  drone.progress.phase = DronePhase::kStarting;
  SetRetry(drone, common::Nanos::max());
  pending_[scheduler_.SendCommand(drone.mission.vehicle, start)] =
      Pending{drone.mission.vehicle, -1};
}

void MissionManager::Fail(Drone& drone, std::string why) {
  drone.progress.phase = DronePhase::kFailed;
  drone.progress.failure = std::move(why);
  SetRetry(drone, common::Nanos::max());
}

void MissionManager::OnEvent(const radio::SchedulerEvent& event, const StartGate& gate) {
  if (const auto* finished = std::get_if<radio::RequestFinished>(&event)) {
    OnFinished(*finished, gate);
  } else if (const auto* telemetry = std::get_if<radio::TelemetryReceived>(&event)) {
    OnTelemetry(*telemetry);
  }
}

void MissionManager::OnFinished(const radio::RequestFinished& finished,
                                const StartGate& gate) {
  const auto found = pending_.find(finished.id);
  if (found == pending_.end()) return;  // someone else's request
  const Pending pending = found->second;
  pending_.erase(found);
  Drone& drone = drones_.at(pending.vehicle);
  if (drone.progress.phase == DronePhase::kFailed) return;

  if (pending.chunk >= 0) {
    const auto index = static_cast<std::size_t>(pending.chunk);
    if (finished.status == radio::RequestStatus::kFailed) {
      if (drone.chunk_rounds[index] >= config_.chunk_rounds) {
        Fail(drone, "chunk " + std::to_string(index) + " unanswered after " +
                        std::to_string(drone.chunk_rounds[index]) + " rounds of retries");
      } else {
        SendChunk(drone, index);
      }
      return;
    }
    const auto* ack = finished.ack ? std::get_if<radio::MissionAck>(&*finished.ack) : nullptr;
    if (ack == nullptr || ack->status == radio::MissionAckStatus::kRejected) {
      Fail(drone, "the vehicle rejected chunk " + std::to_string(index));
      return;
    }
    ++drone.progress.chunks_acked;
    if (ack->status == radio::MissionAckStatus::kComplete &&
        drone.progress.phase == DronePhase::kUploading) {
      SendStart(drone, finished.finished, gate);
    }
    return;
  }

  // The start command.
  if (finished.status == radio::RequestStatus::kFailed) {
    SetRetry(drone, finished.finished);  // unanswered: ask again at once
    return;
  }
  const auto* ack = finished.ack ? std::get_if<radio::CommandAck>(&*finished.ack) : nullptr;
  if (ack != nullptr && ack->result == radio::CommandResult::kAccepted) {
    drone.progress.phase = DronePhase::kFlying;
    return;
  }
  ++drone.progress.start_refusals;
  SetRetry(drone, finished.finished + common::FromSeconds(config_.start_retry_s));
}

void MissionManager::OnTelemetry(const radio::TelemetryReceived& received) {
  Drone* const found = by_id_[received.vehicle];
  if (found == nullptr) return;
  Drone& drone = *found;
  DroneProgress& progress = drone.progress;
  const radio::Telemetry& telemetry = received.telemetry;
  // On the ground for its pack, whatever mission it flew last (one handed over
  // while it waits has not gone up yet).
  if (progress.phase == DronePhase::kSwapping) {
    const bool fresh = telemetry.mode == radio::FlightMode::kLanded &&
                       telemetry.battery_percent >= kFreshPackPercent &&
                       (telemetry.flags & radio::telemetry_flags::kLowBattery) == 0;
    if (fresh && !sorties_stopped_) StartNextSortie(drone);
    return;
  }
  if (telemetry.mission_id != SortieMissionId(drone.mission, progress.sortie)) return;
  if (progress.phase != DronePhase::kFlying) return;
  const std::size_t first = SortieRange(drone.mission, progress.sortie).first;
  // Sent home by a low battery: its rest is a sortie of its own from now on, so
  // that a drone standing ready may take it while this one flies home.
  if (telemetry.mode != radio::FlightMode::kSearch && CutShort(drone.mission.vehicle, telemetry)) {
    CutSortie(drone, first + telemetry.waypoint_index);
  }
  progress.waypoint_index =
      std::max(progress.waypoint_index,
               std::min<std::size_t>(first + telemetry.waypoint_index,
                                     SortieRange(drone.mission, progress.sortie).second));
  if (telemetry.mode == radio::FlightMode::kLanded) OnLanded(drone, telemetry);
}

void MissionManager::CutSortie(Drone& drone, std::size_t flying_to) {
  // The rest begins with the leg it was on.
  const auto at =
      drone.mission.sortie_starts.begin() + static_cast<std::ptrdiff_t>(drone.progress.sortie);
  drone.mission.sortie_starts.insert(at, flying_to - 1);
  ++drone.progress.sortie_count;
  ++missions_version_;
}

bool MissionManager::CutShort(std::uint8_t vehicle, const radio::Telemetry& telemetry) const {
  const Drone& drone = Find(vehicle);
  if (drone.progress.phase != DronePhase::kFlying ||
      telemetry.mission_id != SortieMissionId(drone.mission, drone.progress.sortie)) {
    return false;
  }
  // Sent home by a low battery before its sortie's last waypoint. Only when it
  // got somewhere (past its sortie's second waypoint), or a pack too small would
  // loop forever.
  const auto [first, end] = SortieRange(drone.mission, drone.progress.sortie);
  const std::size_t flying_to = first + telemetry.waypoint_index;
  const bool low_battery = (telemetry.flags & radio::telemetry_flags::kLowBattery) != 0;
  return low_battery && flying_to + 1 < end && flying_to >= first + 2;
}

void MissionManager::OnLanded(Drone& drone, const radio::Telemetry& telemetry) {
  DroneProgress& progress = drone.progress;
  DroneMission& mission = drone.mission;
  const std::size_t first = SortieRange(mission, progress.sortie).first;
  // Cut short (and not seen on its way home): the rest, from the leg it was on,
  // becomes a sortie of its own.
  if (CutShort(mission.vehicle, telemetry)) CutSortie(drone, first + telemetry.waypoint_index);
  ++progress.sorties_flown;
  drone.next_sortie = progress.sortie + 1;
  const bool last = progress.sortie + 1 >= SortieCount(mission);
  progress.phase = last || sorties_stopped_ ? DronePhase::kDone : DronePhase::kSwapping;
}

void MissionManager::StartNextSortie(Drone& drone) {
  LoadSortie(drone, drone.next_sortie);
  drone.progress.phase = DronePhase::kUploading;
  for (std::size_t i = 0; i < drone.chunks.size(); ++i) SendChunk(drone, i);
}

void MissionManager::StopSorties() {
  sorties_stopped_ = true;
  for (auto& [vehicle, drone] : drones_) {
    if (drone.progress.phase == DronePhase::kSwapping) drone.progress.phase = DronePhase::kDone;
  }
}

void MissionManager::Step(common::Nanos now, const StartGate& gate) {
  // The server steps on every radio event: most of them find no retry due.
  if (now < NextWakeup()) return;
  for (auto& [vehicle, drone] : drones_) {
    if (drone.progress.phase == DronePhase::kStarting && drone.retry_start_at <= now) {
      SendStart(drone, now, gate);
    }
  }
}

void MissionManager::SetRetry(Drone& drone, common::Nanos at) {
  drone.retry_start_at = at;
  next_wakeup_.reset();
}

common::Nanos MissionManager::NextWakeup() const {
  if (!next_wakeup_) {
    next_wakeup_ = common::Nanos::max();
    for (const auto& [vehicle, drone] : drones_) {
      next_wakeup_ = std::min(*next_wakeup_, drone.retry_start_at);
    }
  }
  return *next_wakeup_;
}

void MissionManager::RestorePhase(std::uint8_t vehicle, DronePhase phase, std::size_t sortie,
                                  const std::optional<std::vector<std::size_t>>& sortie_starts) {
  Drone& drone = Find(vehicle);
  DroneMission& mission = drone.mission;
  if (mission.waypoints.empty()) return;  // nothing to fly: done from the start
  // Sorties cut short made their rests sorties of their own: the journal has
  // where every sortie begins now.
  if (sortie_starts && *sortie_starts != mission.sortie_starts) {
    const bool fits = std::ranges::is_sorted(*sortie_starts) &&
                      std::ranges::all_of(*sortie_starts, [&](std::size_t start) {
                        return start > 0 && start < mission.waypoints.size();
                      });
    if (!fits) {
      throw std::invalid_argument("vehicle " + std::to_string(vehicle) +
                                  ": sortie starts do not fit its route of " +
                                  std::to_string(mission.waypoints.size()) + " waypoints");
    }
    mission.sortie_starts = *sortie_starts;
    drone.progress.sortie_count = SortieCount(mission);
    ++missions_version_;
  }
  if (sortie != drone.progress.sortie) LoadSortie(drone, sortie);
  drone.next_sortie = sortie + 1;
  drone.progress.sorties_flown =
      sortie + (phase == DronePhase::kSwapping || phase == DronePhase::kDone ? 1 : 0);
  drone.progress.phase = phase;
  if (phase != DronePhase::kUploading) drone.progress.chunks_acked = drone.chunks.size();
  SetRetry(drone, phase == DronePhase::kStarting ? common::Nanos{0} : common::Nanos::max());
}

const DroneProgress& MissionManager::progress(std::uint8_t vehicle) const {
  return Find(vehicle).progress;
}

const std::vector<std::uint8_t>& MissionManager::vehicles() const { return vehicles_; }

bool MissionManager::AllStarted() const {
  return std::ranges::none_of(drones_, [](const auto& entry) {
    const DronePhase phase = entry.second.progress.phase;
    return phase == DronePhase::kUploading || phase == DronePhase::kStarting;
  });
}

double MissionManager::WaypointFraction(std::uint8_t vehicle) const {
  const DroneProgress& progress = Find(vehicle).progress;
  if (progress.phase == DronePhase::kDone) return 1.0;
  if (progress.waypoint_count == 0) return 0.0;
  return static_cast<double>(
             std::min<std::size_t>(progress.waypoint_index, progress.waypoint_count)) /
         static_cast<double>(progress.waypoint_count);
}

double MissionManager::WaypointFraction() const {
  std::size_t total = 0;
  std::size_t passed = 0;
  for (const auto& [vehicle, drone] : drones_) {
    const DroneProgress& progress = drone.progress;
    total += progress.waypoint_count;
    passed += progress.phase == DronePhase::kDone
                  ? progress.waypoint_count
                  : std::min<std::size_t>(progress.waypoint_index, progress.waypoint_count);
  }
  return total == 0 ? 0.0 : static_cast<double>(passed) / static_cast<double>(total);
}

}  // namespace fireswarm::server
