// The server's journal half: recording typed entries (Server::Record) and
// Server::Restore, which replays them to rebuild the core after a restart. Kept
// apart from server.cpp, which runs the mission. The entries' file format is
// journal_format.cpp's.
#include <algorithm>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "fireswarm/server/journal_format.hpp"
#include "fireswarm/server/server.hpp"

namespace fireswarm::server {

namespace {

// A restored server's radio starts half the sequence space away from where its
// predecessor was.
constexpr std::uint16_t kRestartSequenceJump = 0x8000;

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
// Deduction guide: clang 14 (the fuzz build) lacks C++20's aggregate deduction.
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

// The configuration a restored server runs with: the radio's sequence restarts
// half the space away from the last one journaled.
ServerConfig RestartedConfig(const ServerConfig& config, const std::vector<JournalEntry>& entries) {
  ServerConfig restarted = config;
  for (auto entry = entries.rbegin(); entry != entries.rend(); ++entry) {
    if (!entry->radio_seq) continue;
    restarted.radio.first_sequence =
        static_cast<std::uint16_t>(*entry->radio_seq + kRestartSequenceJump);
    break;
  }
  return restarted;
}

Investigation InvestigationFrom(const InvestigationOpened& opened, double started_s) {
  Investigation i;
  i.vehicle = opened.vehicle;
  i.track_id = opened.track_id;
  i.started_s = started_s;
  i.until_s = opened.until_s;
  i.point_en_m = opened.point_en_m;
  return i;
}

}  // namespace

void Server::Record(double t_s, JournalEvent event) {
  if (restoring_) return;
  journal_.push_back(JournalEntry{t_s, scheduler_->next_sequence(), std::move(event)});
}

std::vector<JournalEntry> Server::TakeJournalEntries() {
  return std::exchange(journal_, {});
}

void Server::Replay(const JournalEntry& entry) {
  const double t_s = entry.t_s;
  const auto need_mission = [&](const char* what) {
    if (!mission_) throw std::runtime_error(std::string(what) + " before any mission");
  };
  std::visit(
      Overloaded{
          [&](const VehicleAdded& e) { AddVehicle(e.id, t_s); },
          [&](const MissionLoaded& e) { LoadMission(e.drones, t_s, e.airspace); },
          [&](const CommandAccepted& e) {
            using Kind = OperatorCommand::Kind;
            // Its ID is taken; a journal from before IDs took the next one.
            commands_.Reserve(e.command_id > 0 ? e.command_id : commands_.next_id());
            // Its nonce stays taken: a replay after the restart is refused as before.
            if (!e.operator_id.empty()) verifier_.Remember(e.operator_id, e.nonce, e.utime);
            CallOff(e, t_s);
            if (e.command == Kind::kStart) {
              need_mission("start");
              state_ = MissionState::kUploading;
              mission_started_s_ = t_s;
            } else if (e.command == Kind::kAbort) {
              state_ = MissionState::kAborted;
              if (mission_) mission_->StopSorties();
            } else if (e.command == Kind::kReturnAll) {
              if (state_ != MissionState::kAborted) state_ = MissionState::kReturning;
              if (mission_) mission_->StopSorties();
            }
            // An investigation order is carried out by its InvestigationOpened
            // entry; holds, resumes, returns and landings left nothing to rebuild
            // but the investigations they called off.
          },
          [&](const PhaseChanged& e) {
            need_mission("phase");
            mission_->RestorePhase(e.vehicle, e.phase, e.sortie, e.sortie_starts);
            journaled_phases_[e.vehicle] =
                JournaledPhase{e.phase, mission_->mission_of(e.vehicle).sortie_starts};
          },
          [&](const LanesHandedOver& e) {
            need_mission("handover");
            mission_->MarkLost(e.lost, e.why);
            handed_over_[e.lost] = false;
            for (DroneMission m : e.drones) mission_->Replace(std::move(m), /*send=*/false);
          },
          [&](const MissionStateChanged& e) { state_ = e.state; },
          [&](const ReportFused&) { ReplayFusion(entry, fusion_, report_stats_); },
          [&](const TrackRejected&) { ReplayFusion(entry, fusion_, report_stats_); },
          [&](const InvestigationOpened& e) { investigations_.Restore(InvestigationFrom(e, t_s)); },
          // Why a new track got no investigator: for the operator, nothing to rebuild.
          [](const InvestigationNotSent&) {},
          [&](const DroneRecalled& e) { handed_over_[e.vehicle] = true; },
          [&](const SortieMoved& e) {
            need_mission("sortie move");
            if (!mission_->TakeLastSortie(e.from)) {
              throw std::runtime_error("vehicle " + std::to_string(e.from) +
                                       " has no sortie left to give");
            }
            mission_->Replace(e.taker, /*send=*/false);
          },
          // A refused command changed nothing (the counters are this life's).
          [](const CommandRefused&) {},
          [&](const JournalCompacted& e) {
            if (e.next_command_id > 1) commands_.Reserve(e.next_command_id - 1);
            ReplayFusion(entry, fusion_, report_stats_);
          }},
      entry.event);
}

void ReportStats::Add(double received_s, double detected_s) {
  ++fused;
  latency_s.Add(received_s - detected_s);
}

void ReplayFusion(const JournalEntry& entry, FireFusion& fusion, ReportStats& reports) {
  if (const auto* fused = std::get_if<ReportFused>(&entry.event)) {
    fusion.Add(fused->observation);
    reports.Add(entry.t_s, fused->observation.detection_time_s);
  } else if (const auto* rejected = std::get_if<TrackRejected>(&entry.event)) {
    fusion.Reject(rejected->track_id);
  } else if (const auto* compacted = std::get_if<JournalCompacted>(&entry.event)) {
    // A snapshot holds every report and rejection before it; one from before
    // snapshots left them as entries, already replayed.
    if (compacted->fusion) {
      fusion = FireFusion::Restore(fusion.config(), *compacted->fusion);
      reports = compacted->reports;
    }
  }
}

std::vector<JournalEntry> CompactJournal(std::vector<JournalEntry> entries,
                                         const FireFusionConfig& fusion_config) {
  std::size_t latest = entries.size();  // the latest mission's entry
  std::size_t missions = 0;
  for (std::size_t i = 0; i < entries.size(); ++i) {
    if (!std::holds_alternative<MissionLoaded>(entries[i].event)) continue;
    latest = i;
    ++missions;
  }
  if (missions < 2) return entries;
  std::vector<JournalEntry> out;
  JournalCompacted compacted;
  FireFusion fusion(fusion_config);
  std::int32_t last_command_id = 0;
  for (std::size_t i = 0; i < latest; ++i) {
    JournalEntry& entry = entries[i];
    ReplayFusion(entry, fusion, compacted.reports);
    if (const auto* command = std::get_if<CommandAccepted>(&entry.event)) {
      last_command_id = std::max(last_command_id, command->command_id);
    } else if (const auto* earlier = std::get_if<JournalCompacted>(&entry.event)) {
      last_command_id = std::max(last_command_id, earlier->next_command_id - 1);
      compacted.entries_dropped += earlier->entries_dropped;
    }
    if (std::holds_alternative<VehicleAdded>(entry.event)) {
      out.push_back(std::move(entry));
    } else if (!std::holds_alternative<JournalCompacted>(entry.event)) {
      ++compacted.entries_dropped;
    }
  }
  compacted.next_command_id = last_command_id + 1;
  compacted.fusion = fusion.state();
  const JournalEntry& first_kept = entries[latest];
  out.push_back(JournalEntry{first_kept.t_s, first_kept.radio_seq, std::move(compacted)});
  for (std::size_t i = latest; i < entries.size(); ++i) out.push_back(std::move(entries[i]));
  return out;
}

Server Server::Restore(const ServerConfig& config, const common::LocalFrame& frame,
                       const std::vector<JournalEntry>& entries) {
  const ServerConfig restarted = RestartedConfig(config, entries);
  Server server(restarted, frame);
  server.restoring_ = true;
  for (std::size_t index = 0; index < entries.size(); ++index) {
    try {
      server.Replay(entries[index]);
    } catch (const std::exception& e) {
      throw std::runtime_error("journal entry " + std::to_string(index) + " (" +
                               JournalKindOf(entries[index]) + "): " + e.what());
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
