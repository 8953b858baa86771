// What the server core journals: one typed event per thing that must survive a
// restart, as radio::SchedulerEvent is for the radio. Server produces them
// (TakeJournalEntries) and Server::Restore rebuilds itself from them; how they
// are written to and read from the journal file is journal_format.hpp's business.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "fireswarm/common/age_histogram.hpp"
#include "fireswarm/common/local_frame.hpp"
#include "fireswarm/server/airspace.hpp"
#include "fireswarm/server/command_auth.hpp"
#include "fireswarm/server/fire_fusion.hpp"
#include "fireswarm/server/mission_manager.hpp"
#include "fireswarm/server/mission_state.hpp"
#include "fireswarm/server/operator_command.hpp"

namespace fireswarm::server {

/// A vehicle was registered.
struct VehicleAdded {
  int id = 0;  ///< receiver ID
  friend bool operator==(const VehicleAdded&, const VehicleAdded&) = default;
};

/// The mission was loaded, one drone mission per vehicle.
struct MissionLoaded {
  std::vector<DroneMission> drones;
  /// The altitude layers the drones were given (airspace.hpp), when they were.
  std::optional<AirspacePlan> airspace;
};

/// An operator command was carried out (start, abort, return all, an
/// investigation order, a per-drone or fleet hold, resume, return or land). The
/// radius is not journaled: the investigation that follows an order carries what
/// the vehicle was told.
struct CommandAccepted {
  OperatorCommand::Kind command = OperatorCommand::Kind::kStart;
  std::uint8_t vehicle = 0;
  common::LatLon point;
  std::string reason;
  /// The command's ID (command_status.hpp); 0: not known (journals written before
  /// commands had IDs).
  std::int32_t command_id = 0;
  /// Who signed it, when (their utime) and with which nonce; operator_id empty:
  /// the server's own (Server::Handle) or a journal from before signed commands.
  /// A restored server remembers the nonce, so a replay stays refused.
  std::string operator_id{};
  std::int64_t utime = 0;
  std::int64_t nonce = 0;
};

/// An operator command refused unread or unauthenticated (command_auth.hpp's
/// verdicts): what it asked, who it claimed to come from, and why. Nothing to
/// rebuild; kept for the operator and the record.
struct CommandRefused {
  CommandVerdict verdict = CommandVerdict::kMalformed;
  int command = 0;          ///< the command constant it carried (as given, for a malformed one)
  int vehicle = 0;          ///< its target_vehicle (as given)
  std::string operator_id;  ///< as claimed (cut to kMaxOperatorIdBytes)
  std::int64_t utime = 0;   ///< as claimed
  std::int64_t nonce = 0;   ///< as claimed
  std::string why;          ///< "stale: ...", "bad_mac: ..."
};

/// A drone's phase changed (a new sortie starts with kUploading).
struct PhaseChanged {
  std::uint8_t vehicle = 0;
  DronePhase phase = DronePhase::kUploading;
  std::size_t sortie = 0;  ///< DroneProgress::sortie, of the mission it has then
  /// Where its mission's sorties after the first begin then (DroneMission::
  /// sortie_starts, which a sortie cut short changes); nullopt: as loaded
  /// (journals written before sorties).
  std::optional<std::vector<std::size_t>> sortie_starts;
};

/// A lost drone was given up and its lanes went to others as new missions.
struct LanesHandedOver {
  std::uint8_t lost = 0;
  std::string why;
  std::vector<DroneMission> drones;  ///< the takers' new missions
  /// Joins that could not be routed around the no-fly zones (0: none, not journaled).
  int straight_joins = 0;
};

/// A drone done with its sorties took another's last one, not yet started
/// (Server::RebalanceSorties).
struct SortieMoved {
  std::uint8_t from = 0;
  DroneMission taker;  ///< the taker's new mission: that sortie, at its own altitudes
};

/// The mission's state changed by itself (all started, all over).
struct MissionStateChanged {
  MissionState state = MissionState::kIdle;
};

/// A fire report was fused (neither a duplicate nor invalid).
struct ReportFused {
  FireObservation observation;
};

/// An investigation's verdict rejected a track.
struct TrackRejected {
  std::int32_t track_id = 0;
  std::uint8_t by_vehicle = 0;
};

/// An investigation was ordered; it started at the entry's time.
struct InvestigationOpened {
  std::uint8_t vehicle = 0;
  std::int32_t track_id = 0;                             ///< 0: an operator's point
  double until_s = 0.0;                                  ///< mission time its circling ends, s
  Eigen::Vector2d point_en_m = Eigen::Vector2d::Zero();  ///< local (east, north) m
};

/// A new track got no investigator, and why (for the operator; nothing to rebuild).
struct InvestigationNotSent {
  std::int32_t track_id = 0;
  std::string why;
};

/// A drone given up as lost was heard again and ordered home.
struct DroneRecalled {
  std::uint8_t vehicle = 0;
  std::string why;
};

/// What the server counts of the fire reports it fused, in fixed memory (the
/// run report's reports received and report latency).
struct ReportStats {
  std::uint64_t fused = 0;  ///< reports fused: neither a resend nor invalid
  /// Reception (mission time) minus detection time of each fused report, s.
  common::AgeHistogram latency_s;
  /// Counts a report fused at `received_s` that was detected at `detected_s`.
  void Add(double received_s, double detected_s);
  friend bool operator==(const ReportStats&, const ReportStats&) = default;
};

/// The journal was compacted (CompactJournal) here: the entries of the missions
/// before were dropped, and what of them must outlive them is this.
struct JournalCompacted {
  std::int32_t next_command_id = 1;  ///< command IDs below were given: none is given twice
  std::uint64_t entries_dropped = 0;
  /// The fire tracks and the duplicate check as the dropped entries left them,
  /// and the report counts. nullopt: a journal compacted before snapshots, whose
  /// reports and rejections stayed as entries before this one.
  std::optional<FireFusionState> fusion;
  ReportStats reports;
};

using JournalEvent = std::variant<VehicleAdded, MissionLoaded, CommandAccepted, PhaseChanged,
                                  LanesHandedOver, MissionStateChanged, ReportFused, TrackRejected,
                                  InvestigationOpened, InvestigationNotSent, DroneRecalled,
                                  SortieMoved, CommandRefused, JournalCompacted>;

/// One thing that must survive a restart, in the order it happened.
struct JournalEntry {
  double t_s = 0.0;  ///< mission time, s
  /// The radio's next sequence number when it was recorded: a restored server
  /// starts half the sequence space away from the last one. nullopt: unknown.
  std::optional<std::uint16_t> radio_seq;
  JournalEvent event;
};

/// The journal of a server that flies mission after mission (a patrol), without
/// what only the missions before the latest one needed: their uploads, phases,
/// states, handovers, investigations and commands, and its fused reports and
/// rejected tracks folded into one snapshot. Kept, in order: every vehicle, one
/// JournalCompacted entry (the next command ID, so none is given twice; the fire
/// tracks and duplicate check as those reports left them, fused with `fusion`;
/// the report counts), then every entry from the latest mission's on. Restoring
/// the result gives the same vehicles, tracks, mission, phases, state and report
/// counts as restoring `entries`, and its size no longer grows with the missions
/// flown. Entries without a second mission are returned as they are.
std::vector<JournalEntry> CompactJournal(std::vector<JournalEntry> entries,
                                         const FireFusionConfig& fusion);

/// What a journal entry changes of the fire tracks and report counts: a fused
/// report, a rejected track, a compaction's snapshot; other entries change
/// nothing. Server::Restore and CompactJournal both replay through this.
void ReplayFusion(const JournalEntry& entry, FireFusion& fusion, ReportStats& reports);

}  // namespace fireswarm::server
