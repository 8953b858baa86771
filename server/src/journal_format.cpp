// The server's journal entries as journal records: kind names and JSON data
// (journal_format.hpp lists them). The only place that JSON is written or read.
#include "fireswarm/server/journal_format.hpp"

#include <set>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <vector>

#include "fireswarm/common/north_east.hpp"

namespace fireswarm::server {

namespace {

constexpr const char* kRadioSequenceKey = "radio_seq";

template <class... Ts>
struct Overloaded : Ts... {
  using Ts::operator()...;
};
// Deduction guide: clang 14 (the fuzz build) lacks C++20's aggregate deduction.
template <class... Ts>
Overloaded(Ts...) -> Overloaded<Ts...>;

nlohmann::json WaypointsJson(const std::vector<radio::Waypoint>& waypoints) {
  nlohmann::json list = nlohmann::json::array();
  for (const radio::Waypoint& w : waypoints) {
    list.push_back({w.lat_deg, w.lon_deg, w.altitude_m, w.speed_mps, w.flags});
  }
  return list;
}

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

nlohmann::json MissionsJson(const std::vector<DroneMission>& missions) {
  nlohmann::json drones = nlohmann::json::array();
  for (const DroneMission& m : missions) {
    nlohmann::json drone = {{"vehicle", m.vehicle},
                            {"mission_id", m.mission_id},
                            {"waypoints", WaypointsJson(m.waypoints)}};
    if (!m.sortie_starts.empty()) drone["sortie_starts"] = m.sortie_starts;
    drones.push_back(std::move(drone));
  }
  return drones;
}

nlohmann::json AirspaceJson(const AirspacePlan& plan) {
  nlohmann::json drones = nlohmann::json::array();
  for (const DroneLayers& d : plan.drones) {
    drones.push_back({{"vehicle", d.vehicle},
                      {"search_layer", d.search_layer},
                      {"search_altitude_m", d.search_altitude_m}});
  }
  return {{"rule", plan.rule},
          {"base_altitude_m", plan.base_altitude_m},
          {"layer_m", plan.layer_m},
          {"search_layers", plan.search_layers},
          {"transit_sectors", plan.transit_sectors},
          {"drones", drones}};
}

AirspacePlan AirspaceFrom(const nlohmann::json& data) {
  AirspacePlan plan;
  plan.rule = data.at("rule").get<std::string>();
  plan.base_altitude_m = data.at("base_altitude_m").get<double>();
  plan.layer_m = data.at("layer_m").get<double>();
  plan.search_layers = data.at("search_layers").get<int>();
  plan.transit_sectors = data.at("transit_sectors").get<int>();
  if (plan.search_layers < 1 || plan.transit_sectors < 1) {
    throw std::runtime_error("airspace: search_layers and transit_sectors must be >= 1");
  }
  for (const nlohmann::json& d : data.at("drones")) {
    plan.drones.push_back({d.at("vehicle").get<std::uint8_t>(), d.at("search_layer").get<int>(),
                           d.at("search_altitude_m").get<double>()});
  }
  return plan;
}

std::vector<DroneMission> MissionsFrom(const nlohmann::json& drones) {
  std::vector<DroneMission> missions;
  for (const nlohmann::json& drone : drones) {
    DroneMission m;
    m.vehicle = drone.at("vehicle").get<std::uint8_t>();
    m.mission_id = drone.at("mission_id").get<std::uint16_t>();
    m.waypoints = WaypointsFrom(drone.at("waypoints"));
    if (drone.contains("sortie_starts")) {
      m.sortie_starts = drone.at("sortie_starts").get<std::vector<std::size_t>>();
    }
    missions.push_back(std::move(m));
  }
  return missions;
}

// A local (east, north) vector as the file's [north, east] pair, and back.
nlohmann::json NorthEastJson(const Eigen::Vector2d& en_m) {
  const Eigen::Vector2d ne_m = common::SwapAxes(en_m);
  return {ne_m.x(), ne_m.y()};
}

Eigen::Vector2d FromNorthEast(const nlohmann::json& pair) {
  return common::SwapAxes(Eigen::Vector2d(pair.at(0).get<double>(), pair.at(1).get<double>()));
}

nlohmann::json ObservationJson(const FireObservation& o) {
  return {{"vehicle", o.vehicle_id},
          {"report_id", o.report_id},
          {"detection_s", o.detection_time_s},
          {"position_ne_m", NorthEastJson(o.position_en_m)},
          {"covariance_ne_m2", common::NorthEastTriangle(o.covariance_en_m2)},
          {"observer_ne_m", NorthEastJson(o.observer_en_m)},
          {"confidence", o.confidence}};
}

FireObservation ObservationFrom(const nlohmann::json& j) {
  FireObservation o;
  o.vehicle_id = j.at("vehicle").get<std::uint8_t>();
  o.report_id = j.at("report_id").get<std::uint16_t>();
  o.detection_time_s = j.at("detection_s").get<double>();
  o.position_en_m = FromNorthEast(j.at("position_ne_m"));
  const nlohmann::json& c = j.at("covariance_ne_m2");
  Eigen::Matrix2d covariance_ne_m2;
  covariance_ne_m2 << c.at(0).get<double>(), c.at(1).get<double>(), c.at(1).get<double>(),
      c.at(2).get<double>();
  o.covariance_en_m2 = common::SwapAxes(covariance_ne_m2);
  o.observer_en_m = FromNorthEast(j.at("observer_ne_m"));
  o.confidence = j.at("confidence").get<double>();
  return o;
}

// A 2x2 matrix in (north, east) order, all four elements: a track's evidence is
// a sum of inverses, symmetric only to the last bit, and must come back exact.
nlohmann::json NorthEastMatrixJson(const Eigen::Matrix2d& en) {
  const Eigen::Matrix2d ne = common::SwapAxes(en);
  return {ne(0, 0), ne(0, 1), ne(1, 0), ne(1, 1)};
}

Eigen::Matrix2d FromNorthEastMatrix(const nlohmann::json& four) {
  if (!four.is_array() || four.size() != 4) throw std::runtime_error("a matrix needs 4 numbers");
  Eigen::Matrix2d ne;
  ne << four.at(0).get<double>(), four.at(1).get<double>(), four.at(2).get<double>(),
      four.at(3).get<double>();
  return common::SwapAxes(ne);
}

nlohmann::json TrackJson(const FireTrack& track) {
  nlohmann::json evidence = nlohmann::json::array();
  for (const VehicleEvidence& e : track.evidence) {
    evidence.push_back({{"vehicle", e.vehicle_id},
                        {"reports", e.report_count},
                        {"information_ne", NorthEastMatrixJson(e.information_en)},
                        {"information_vector_ne", NorthEastJson(e.information_vector_en)}});
  }
  nlohmann::json reports = nlohmann::json::array();
  for (const FireObservation& o : track.reports) reports.push_back(ObservationJson(o));
  nlohmann::json out;
  out["track_id"] = track.track_id;
  out["status"] = static_cast<int>(track.status);
  out["report_count"] = track.report_count;
  out["first_seen_s"] = track.first_seen_s;
  out["last_seen_s"] = track.last_seen_s;
  out["max_confidence"] = track.max_confidence;
  out["evidence"] = std::move(evidence);
  out["reports"] = std::move(reports);
  return out;
}

// The saved fields of a track; FireFusion::Restore checks and completes it.
FireTrack TrackFrom(const nlohmann::json& j) {
  FireTrack track;
  track.track_id = j.at("track_id").get<std::int32_t>();
  track.status = static_cast<FireTrackStatus>(j.at("status").get<std::int8_t>());
  track.report_count = j.at("report_count").get<std::int32_t>();
  track.first_seen_s = j.at("first_seen_s").get<double>();
  track.last_seen_s = j.at("last_seen_s").get<double>();
  track.max_confidence = j.at("max_confidence").get<double>();
  for (const nlohmann::json& e : j.at("evidence")) {
    VehicleEvidence evidence;
    evidence.vehicle_id = e.at("vehicle").get<std::uint8_t>();
    evidence.report_count = e.at("reports").get<std::int32_t>();
    evidence.information_en = FromNorthEastMatrix(e.at("information_ne"));
    evidence.information_vector_en = FromNorthEast(e.at("information_vector_ne"));
    track.evidence.push_back(evidence);
  }
  for (const nlohmann::json& o : j.at("reports")) track.reports.push_back(ObservationFrom(o));
  return track;
}

nlohmann::json FusionJson(const FireFusionState& state) {
  nlohmann::json tracks = nlohmann::json::array();
  for (const FireTrack& track : state.tracks) tracks.push_back(TrackJson(track));
  nlohmann::json seen = nlohmann::json::array();
  for (const SeenReport& r : state.seen) seen.push_back({r.vehicle_id, r.report_id, r.track_id});
  return {{"next_track_id", state.next_track_id},
          {"tracks", std::move(tracks)},
          {"seen", std::move(seen)}};
}

FireFusionState FusionFrom(const nlohmann::json& j) {
  FireFusionState state;
  state.next_track_id = j.at("next_track_id").get<std::int32_t>();
  for (const nlohmann::json& track : j.at("tracks")) state.tracks.push_back(TrackFrom(track));
  for (const nlohmann::json& r : j.at("seen")) {
    if (!r.is_array() || r.size() != 3) {
      throw std::runtime_error("a remembered report is [vehicle, report_id, track_id]");
    }
    state.seen.push_back(
        {r.at(0).get<std::uint8_t>(), r.at(1).get<std::uint16_t>(), r.at(2).get<std::int32_t>()});
  }
  return state;
}

nlohmann::json ReportStatsJson(const ReportStats& stats) {
  nlohmann::json bins = nlohmann::json::array();
  for (const auto& [bin, count] : stats.latency_s.NonEmptyBins()) bins.push_back({bin, count});
  return {{"fused", stats.fused},
          {"latency_max_s", stats.latency_s.max_s()},
          {"latency_bins", std::move(bins)}};
}

ReportStats ReportStatsFrom(const nlohmann::json& j) {
  ReportStats stats;
  stats.fused = j.at("fused").get<std::uint64_t>();
  common::AgeHistogram::Bins bins;
  for (const nlohmann::json& bin : j.at("latency_bins")) {
    if (!bin.is_array() || bin.size() != 2) {
      throw std::runtime_error("a latency bin is [index, count]");
    }
    bins.emplace_back(bin.at(0).get<std::size_t>(), bin.at(1).get<std::uint64_t>());
  }
  stats.latency_s = common::AgeHistogram::FromBins(bins, j.at("latency_max_s").get<double>());
  if (stats.latency_s.count() != stats.fused) {
    throw std::runtime_error("fused " + std::to_string(stats.fused) + " reports but " +
                             std::to_string(stats.latency_s.count()) + " latencies");
  }
  return stats;
}

// The record kind of a command: its name (operator_command.hpp), but one kind for
// both investigation orders (as journals have always had it).
std::string CommandKind(OperatorCommand::Kind command) {
  if (command == OperatorCommand::Kind::kInvestigatePoint ||
      command == OperatorCommand::Kind::kRetaskVehicle) {
    return "investigate_order";
  }
  return ToString(command);
}

bool IsCommandKind(const std::string& kind) {
  static const std::set<std::string> kKinds = {
      "start",  "abort",  "return_all", "investigate_order", "hold",
      "resume", "return", "land",       "hold_all",          "resume_all"};
  return kKinds.contains(kind);
}

constexpr int kFirstCommand = static_cast<int>(OperatorCommand::Kind::kStart);
constexpr int kLastCommand = static_cast<int>(OperatorCommand::Kind::kResumeAll);

CommandAccepted CommandFrom(const nlohmann::json& data) {
  CommandAccepted c;
  const int command = data.at("command").get<int>();
  if (command < kFirstCommand || command > kLastCommand) {
    throw std::runtime_error("unknown command " + std::to_string(command));
  }
  c.command = static_cast<OperatorCommand::Kind>(command);
  c.vehicle = data.at("vehicle").get<std::uint8_t>();
  c.point = {data.at("lat_deg").get<double>(), data.at("lon_deg").get<double>()};
  c.reason = data.at("reason").get<std::string>();
  c.command_id = data.value("command_id", std::int32_t{0});
  c.operator_id = data.value("operator_id", std::string());
  c.utime = data.value("utime", std::int64_t{0});
  c.nonce = data.value("nonce", std::int64_t{0});
  return c;
}

CommandRefused RefusalFrom(const nlohmann::json& data) {
  CommandRefused r;
  const std::string verdict = data.at("verdict").get<std::string>();
  for (int v = static_cast<int>(CommandVerdict::kMalformed);
       v <= static_cast<int>(CommandVerdict::kReplayed); ++v) {
    if (verdict == ToString(static_cast<CommandVerdict>(v)))
      r.verdict = static_cast<CommandVerdict>(v);
  }
  if (verdict != ToString(r.verdict)) throw std::runtime_error("unknown verdict '" + verdict + "'");
  r.command = data.at("command").get<int>();
  r.vehicle = data.at("vehicle").get<int>();
  r.operator_id = data.at("operator_id").get<std::string>();
  r.utime = data.at("utime").get<std::int64_t>();
  r.nonce = data.at("nonce").get<std::int64_t>();
  r.why = data.at("why").get<std::string>();
  return r;
}

// The event of a record of `kind`; throws nlohmann::json::exception for a bad
// field and std::runtime_error for an unknown kind or a command under another's name.
JournalEvent EventFrom(const std::string& kind, const nlohmann::json& data) {
  if (kind == "vehicle") return VehicleAdded{data.at("id").get<int>()};
  if (kind == "mission") {
    MissionLoaded loaded{MissionsFrom(data.at("drones")), std::nullopt};
    if (data.contains("airspace")) loaded.airspace = AirspaceFrom(data.at("airspace"));
    return loaded;
  }
  if (IsCommandKind(kind)) {
    CommandAccepted command = CommandFrom(data);
    if (kind != CommandKind(command.command)) {
      throw std::runtime_error("kind " + kind + " holds command " +
                               std::to_string(static_cast<int>(command.command)) + " (" +
                               CommandKind(command.command) + ")");
    }
    return command;
  }
  if (kind == "phase") {
    PhaseChanged changed;
    changed.vehicle = data.at("vehicle").get<std::uint8_t>();
    changed.phase = static_cast<DronePhase>(data.at("phase").get<int>());
    changed.sortie = data.value("sortie", std::size_t{0});
    if (data.contains("sortie_starts")) {
      changed.sortie_starts = data.at("sortie_starts").get<std::vector<std::size_t>>();
    }
    return changed;
  }
  if (kind == "handover") {
    LanesHandedOver handed;
    handed.lost = data.at("lost").get<std::uint8_t>();
    handed.why = data.at("why").get<std::string>();
    handed.drones = MissionsFrom(data.at("drones"));
    handed.straight_joins = data.value("straight_joins", 0);
    return handed;
  }
  if (kind == "sortie_moved") {
    SortieMoved moved;
    moved.from = data.at("from").get<std::uint8_t>();
    const std::vector<DroneMission> taker = MissionsFrom(nlohmann::json::array({data.at("taker")}));
    moved.taker = taker.front();
    return moved;
  }
  if (kind == "state")
    return MissionStateChanged{static_cast<MissionState>(data.at("state").get<int>())};
  if (kind == "report") return ReportFused{ObservationFrom(data)};
  if (kind == "reject") {
    return TrackRejected{data.at("track_id").get<std::int32_t>(),
                         data.at("by_vehicle").get<std::uint8_t>()};
  }
  if (kind == "investigation") {
    return InvestigationOpened{
        data.at("vehicle").get<std::uint8_t>(), data.at("track_id").get<std::int32_t>(),
        data.at("until_s").get<double>(), FromNorthEast(data.at("point_ne_m"))};
  }
  if (kind == "no_investigation") {
    return InvestigationNotSent{data.at("track_id").get<std::int32_t>(),
                                data.at("why").get<std::string>()};
  }
  if (kind == "compacted") {
    JournalCompacted compacted;
    compacted.next_command_id = data.at("next_command_id").get<std::int32_t>();
    compacted.entries_dropped = data.at("entries_dropped").get<std::uint64_t>();
    // Without them: compacted before snapshots (its reports stayed as entries).
    if (data.contains("fusion")) compacted.fusion = FusionFrom(data.at("fusion"));
    if (data.contains("reports")) compacted.reports = ReportStatsFrom(data.at("reports"));
    return compacted;
  }
  if (kind == "recall") {
    return DroneRecalled{data.at("vehicle").get<std::uint8_t>(), data.at("why").get<std::string>()};
  }
  if (kind == "command_refused") return RefusalFrom(data);
  throw std::runtime_error("unknown kind");
}

}  // namespace

std::string JournalKindOf(const JournalEntry& entry) {
  return std::visit(
      Overloaded{[](const VehicleAdded&) -> std::string { return "vehicle"; },
                 [](const MissionLoaded&) -> std::string { return "mission"; },
                 [](const CommandAccepted& c) -> std::string { return CommandKind(c.command); },
                 [](const PhaseChanged&) -> std::string { return "phase"; },
                 [](const LanesHandedOver&) -> std::string { return "handover"; },
                 [](const MissionStateChanged&) -> std::string { return "state"; },
                 [](const ReportFused&) -> std::string { return "report"; },
                 [](const TrackRejected&) -> std::string { return "reject"; },
                 [](const InvestigationOpened&) -> std::string { return "investigation"; },
                 [](const InvestigationNotSent&) -> std::string { return "no_investigation"; },
                 [](const DroneRecalled&) -> std::string { return "recall"; },
                 [](const SortieMoved&) -> std::string { return "sortie_moved"; },
                 [](const CommandRefused&) -> std::string { return "command_refused"; },
                 [](const JournalCompacted&) -> std::string { return "compacted"; }},
      entry.event);
}

nlohmann::json JournalDataOf(const JournalEntry& entry) {
  nlohmann::json data = std::visit(
      Overloaded{
          [](const VehicleAdded& e) -> nlohmann::json {
            return {{"id", e.id}};
          },
          [](const MissionLoaded& e) -> nlohmann::json {
            nlohmann::json mission = {{"drones", MissionsJson(e.drones)}};
            if (e.airspace) mission["airspace"] = AirspaceJson(*e.airspace);
            return mission;
          },
          [](const CommandAccepted& e) -> nlohmann::json {
            nlohmann::json command = {{"command", static_cast<int>(e.command)},
                                      {"vehicle", e.vehicle},
                                      {"lat_deg", e.point.lat_deg},
                                      {"lon_deg", e.point.lon_deg},
                                      {"reason", e.reason}};
            if (e.command_id > 0) command["command_id"] = e.command_id;
            // Only for signed commands, so the server's own read as before.
            if (!e.operator_id.empty()) {
              command["operator_id"] = e.operator_id;
              command["utime"] = e.utime;
              command["nonce"] = e.nonce;
            }
            return command;
          },
          [](const PhaseChanged& e) -> nlohmann::json {
            nlohmann::json changed = {{"vehicle", e.vehicle}, {"phase", static_cast<int>(e.phase)}};
            // Only with sorties, so a one-sortie journal reads as before.
            if (e.sortie > 0) changed["sortie"] = e.sortie;
            if (e.sortie_starts && !e.sortie_starts->empty()) {
              changed["sortie_starts"] = *e.sortie_starts;
            }
            return changed;
          },
          [](const LanesHandedOver& e) -> nlohmann::json {
            nlohmann::json handed = {
                {"lost", e.lost}, {"why", e.why}, {"drones", MissionsJson(e.drones)}};
            // Only when it happened, so a journal without zones reads as before.
            if (e.straight_joins > 0) handed["straight_joins"] = e.straight_joins;
            return handed;
          },
          [](const MissionStateChanged& e) -> nlohmann::json {
            return {{"state", static_cast<int>(e.state)}};
          },
          [](const ReportFused& e) -> nlohmann::json { return ObservationJson(e.observation); },
          [](const TrackRejected& e) -> nlohmann::json {
            return {{"track_id", e.track_id}, {"by_vehicle", e.by_vehicle}};
          },
          [](const InvestigationOpened& e) -> nlohmann::json {
            return {{"vehicle", e.vehicle},
                    {"track_id", e.track_id},
                    {"until_s", e.until_s},
                    {"point_ne_m", NorthEastJson(e.point_en_m)}};
          },
          [](const InvestigationNotSent& e) -> nlohmann::json {
            return {{"track_id", e.track_id}, {"why", e.why}};
          },
          [](const DroneRecalled& e) -> nlohmann::json {
            return {{"vehicle", e.vehicle}, {"why", e.why}};
          },
          [](const JournalCompacted& e) -> nlohmann::json {
            nlohmann::json compacted = {{"next_command_id", e.next_command_id},
                                        {"entries_dropped", e.entries_dropped}};
            if (e.fusion) {
              compacted["fusion"] = FusionJson(*e.fusion);
              compacted["reports"] = ReportStatsJson(e.reports);
            }
            return compacted;
          },
          [](const SortieMoved& e) -> nlohmann::json {
            return {{"from", e.from}, {"taker", MissionsJson({e.taker}).front()}};
          },
          [](const CommandRefused& e) -> nlohmann::json {
            return {{"verdict", ToString(e.verdict)},
                    {"command", e.command},
                    {"vehicle", e.vehicle},
                    {"operator_id", e.operator_id},
                    {"utime", e.utime},
                    {"nonce", e.nonce},
                    {"why", e.why}};
          }},
      entry.event);
  if (entry.radio_seq) data[kRadioSequenceKey] = *entry.radio_seq;
  return data;
}

JournalEntry JournalEntryOf(const JournalRecord& record) {
  try {
    if (!record.data.is_object()) throw std::runtime_error("data is not a JSON object");
    JournalEntry entry{record.t_s, std::nullopt, EventFrom(record.kind, record.data)};
    if (record.data.contains(kRadioSequenceKey)) {
      entry.radio_seq = record.data.at(kRadioSequenceKey).get<std::uint16_t>();
    }
    return entry;
  } catch (const std::exception& e) {
    throw std::runtime_error("journal line " + std::to_string(record.seq) + " (" + record.kind +
                             "): " + e.what());
  }
}

std::uint64_t AppendEntry(Journal& journal, const JournalEntry& entry) {
  return journal.Append(entry.t_s, JournalKindOf(entry), JournalDataOf(entry));
}

}  // namespace fireswarm::server
