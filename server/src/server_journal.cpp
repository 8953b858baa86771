// The server's journal half: what each recorded entry holds (Server::Record),
// and Server::Restore, which replays a journal to rebuild the core after a
// restart. Kept apart from server.cpp, which runs the mission; the JSON that
// both sides write and read is here, declared for server.cpp in
// server_journal_json.hpp.
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "fireswarm/server/server.hpp"
#include "server_journal_json.hpp"

namespace fireswarm::server {

namespace {

// Every journal entry carries the radio's next sequence number, so a restored
// server can start half the sequence space away from where its predecessor was.
constexpr const char* kRadioSequenceKey = "radio_seq";
constexpr std::uint16_t kRestartSequenceJump = 0x8000;

std::vector<radio::Waypoint> WaypointsFrom(const nlohmann::json& list) {
  std::vector<radio::Waypoint> waypoints;
  for (const nlohmann::json& item : list) {
    radio::Waypoint w;
    w.lat_deg = item.at(0).get<double>();
    w.lon_deg = item.at(1).get<double>();
    w.altitude_m = item.at(2).get<double>();
    w.speed_mps = item.at(3).get<double>();
    w.flags = item.at(4).get<std::uint8_t>();
    waypoints.push_back(w);
  }
  return waypoints;
}

FireObservation ObservationFrom(const nlohmann::json& j) {
  FireObservation o;
  o.vehicle_id = j.at("vehicle").get<std::uint8_t>();
  o.report_id = j.at("report_id").get<std::uint16_t>();
  o.detection_time_s = j.at("detection_s").get<double>();
  o.position_ne_m = {j.at("position_ne_m").at(0).get<double>(),
                     j.at("position_ne_m").at(1).get<double>()};
  const nlohmann::json& c = j.at("covariance_ne_m2");
  o.covariance_ne_m2 << c.at(0).get<double>(), c.at(1).get<double>(), c.at(1).get<double>(),
      c.at(2).get<double>();
  o.observer_ne_m = {j.at("observer_ne_m").at(0).get<double>(),
                     j.at("observer_ne_m").at(1).get<double>()};
  o.confidence = j.at("confidence").get<double>();
  return o;
}

std::vector<DroneMission> MissionsFrom(const nlohmann::json& drones) {
  std::vector<DroneMission> missions;
  for (const nlohmann::json& drone : drones) {
    DroneMission m;
    m.vehicle = drone.at("vehicle").get<std::uint8_t>();
    m.mission_id = drone.at("mission_id").get<std::uint16_t>();
    m.waypoints = WaypointsFrom(drone.at("waypoints"));
    missions.push_back(std::move(m));
  }
  return missions;
}

Investigation InvestigationFrom(const JournalEntry& entry) {
  const nlohmann::json& data = entry.data;
  Investigation i;
  i.vehicle = data.at("vehicle").get<std::uint8_t>();
  i.track_id = data.at("track_id").get<std::int32_t>();
  i.started_s = entry.t_s;
  i.until_s = data.at("until_s").get<double>();
  i.point_ne_m = {data.at("point_ne_m").at(0).get<double>(),
                  data.at("point_ne_m").at(1).get<double>()};
  return i;
}

// The configuration a restored server runs with: the radio's sequence restarts
// half the space away from the last one journaled.
ServerConfig RestartedConfig(const ServerConfig& config, const std::vector<JournalEntry>& entries) {
  ServerConfig restarted = config;
  for (auto entry = entries.rbegin(); entry != entries.rend(); ++entry) {
    if (!entry->data.is_object() || !entry->data.contains(kRadioSequenceKey)) continue;
    restarted.radio.first_sequence = static_cast<std::uint16_t>(
        entry->data[kRadioSequenceKey].get<std::uint16_t>() + kRestartSequenceJump);
    break;
  }
  return restarted;
}

}  // namespace

nlohmann::json WaypointsJson(const std::vector<radio::Waypoint>& waypoints) {
  nlohmann::json list = nlohmann::json::array();
  for (const radio::Waypoint& w : waypoints) {
    list.push_back({w.lat_deg, w.lon_deg, w.altitude_m, w.speed_mps, w.flags});
  }
  return list;
}

nlohmann::json ObservationJson(const FireObservation& o) {
  return {{"vehicle", o.vehicle_id},
          {"report_id", o.report_id},
          {"detection_s", o.detection_time_s},
          {"position_ne_m", {o.position_ne_m.x(), o.position_ne_m.y()}},
          {"covariance_ne_m2",
           {o.covariance_ne_m2(0, 0), o.covariance_ne_m2(0, 1), o.covariance_ne_m2(1, 1)}},
          {"observer_ne_m", {o.observer_ne_m.x(), o.observer_ne_m.y()}},
          {"confidence", o.confidence}};
}

void Server::Record(double t_s, std::string kind, nlohmann::json data) {
  if (restoring_) return;
  data[kRadioSequenceKey] = scheduler_->next_sequence();
  journal_.push_back(JournalEntry{t_s, std::move(kind), std::move(data)});
}

std::vector<JournalEntry> Server::TakeJournalEntries() {
  return std::exchange(journal_, {});
}

Server Server::Restore(const ServerConfig& config, const common::LocalFrame& frame,
                       const std::vector<JournalEntry>& entries) {
  const ServerConfig restarted = RestartedConfig(config, entries);
  Server server(restarted, frame);
  server.restoring_ = true;
  for (std::size_t index = 0; index < entries.size(); ++index) {
    const JournalEntry& entry = entries[index];
    const nlohmann::json& data = entry.data;
    try {
      if (entry.kind == "vehicle") {
        server.AddVehicle(data.at("id").get<int>(), entry.t_s);
      } else if (entry.kind == "mission") {
        server.LoadMission(MissionsFrom(data.at("drones")), entry.t_s);
      } else if (entry.kind == "start") {
        if (!server.mission_) throw std::runtime_error("start before any mission");
        server.state_ = MissionState::kUploading;
        server.mission_started_s_ = entry.t_s;
      } else if (entry.kind == "phase") {
        if (!server.mission_) throw std::runtime_error("phase before any mission");
        const auto vehicle = data.at("vehicle").get<std::uint8_t>();
        const auto phase = static_cast<DronePhase>(data.at("phase").get<int>());
        server.mission_->RestorePhase(vehicle, phase);
        server.journaled_phases_[vehicle] = phase;
      } else if (entry.kind == "handover") {
        if (!server.mission_) throw std::runtime_error("handover before any mission");
        const auto lost = data.at("lost").get<std::uint8_t>();
        server.mission_->MarkLost(lost, data.at("why").get<std::string>());
        server.handed_over_[lost] = false;
        for (DroneMission& m : MissionsFrom(data.at("drones"))) {
          server.mission_->Replace(std::move(m), /*send=*/false);
        }
      } else if (entry.kind == "state") {
        server.state_ = static_cast<MissionState>(data.at("state").get<int>());
      } else if (entry.kind == "abort") {
        server.state_ = MissionState::kAborted;
      } else if (entry.kind == "return_all") {
        if (server.state_ != MissionState::kAborted) server.state_ = MissionState::kReturning;
      } else if (entry.kind == "report") {
        const FireObservation observation = ObservationFrom(data);
        server.report_receipts_.emplace(
            std::make_pair(observation.vehicle_id, observation.report_id), entry.t_s);
        server.fusion_.Add(observation);
      } else if (entry.kind == "reject") {
        server.fusion_.Reject(data.at("track_id").get<std::int32_t>());
      } else if (entry.kind == "investigation") {
        server.investigations_.Restore(InvestigationFrom(entry));
      } else if (entry.kind == "investigate_order") {
        // The order itself is carried out by its "investigation" entry.
      } else if (entry.kind == "recall") {
        server.handed_over_[data.at("vehicle").get<std::uint8_t>()] = true;
      } else if (entry.kind == "no_investigation") {
        // Why a new track got no investigator: for the operator, nothing to rebuild.
      } else {
        throw std::runtime_error("unknown kind");
      }
    } catch (const std::exception& e) {
      throw std::runtime_error("journal entry " + std::to_string(index) + " (" + entry.kind +
                               "): " + e.what());
    }
  }
  // Missions still uploading when the server stopped (the first, or one handed
  // over) go up again: chunks are idempotent on the vehicle.
  if (server.mission_ &&
      (server.state_ == MissionState::kUploading || server.state_ == MissionState::kRunning)) {
    server.mission_->Begin();
  }
  server.restoring_ = false;
  return server;
}

}  // namespace fireswarm::server
