// The server's journal entries in the journal file (journal.hpp): each entry is
// one record whose kind names its event and whose data holds its fields. The
// JSON of a record's data lives here and in journal.cpp only.
//
// Kinds and data (positions local (north, east) m; waypoints as
// [lat_deg, lon_deg, altitude_m, speed_mps, flags]); every data object also
// holds "radio_seq", the radio's next sequence number:
//   vehicle            {"id"}
//   mission            {"drones": [{"vehicle", "mission_id", "waypoints"}], "airspace"?:
//                      {"rule", "base_altitude_m", "layer_m", "search_layers",
//                       "transit_sectors", "drones": [{"vehicle", "search_layer",
//                       "search_altitude_m"}]}}
//   start, abort, return_all, investigate_order (investigate and retask), hold,
//   resume, return, land, hold_all, resume_all
//                      {"command", "vehicle", "lat_deg", "lon_deg", "reason",
//                       ["command_id"]}  (OperatorCommand::Kind's value; the ID
//                       from 1, absent in journals written before commands had IDs)
//   phase              {"vehicle", "phase"}            (DronePhase's value)
//   handover           {"lost", "why", "drones", ["straight_joins"]}
//   state              {"state"}                       (MissionState's value)
//   report             {"vehicle", "report_id", "detection_s", "position_ne_m",
//                       "covariance_ne_m2": [nn, ne, ee], "observer_ne_m", "confidence"}
//   reject             {"track_id", "by_vehicle"}
//   investigation      {"vehicle", "track_id", "until_s", "point_ne_m"}
//   no_investigation   {"track_id", "why"}
//   recall             {"vehicle", "why"}
// Journal files of format version 0 (no "v" on a line) hold the same records.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

#include "fireswarm/server/journal.hpp"
#include "fireswarm/server/journal_entry.hpp"

namespace fireswarm::server {

/// The record kind of `entry` ("vehicle", "report", ...).
std::string JournalKindOf(const JournalEntry& entry);
/// The record data of `entry`.
nlohmann::json JournalDataOf(const JournalEntry& entry);
/// The entry a record holds. Throws std::runtime_error naming the record's line
/// (its seq), its kind and what was wrong (an unknown kind, a missing or
/// mistyped field).
JournalEntry JournalEntryOf(const JournalRecord& record);
/// Appends `entry` to `journal` and returns its seq (Journal::Append's throws).
std::uint64_t AppendEntry(Journal& journal, const JournalEntry& entry);

}  // namespace fireswarm::server
