// `fireswarm serve`: the command server on the wall clock. Plans the search of a
// GeoJSON area, registers the fleet, uploads and starts the mission over a real
// radio link (a serial modem, or UDP), fuses the fire reports, publishes on LCM
// and journals what must survive a restart. Started again on the same --journal
// it resumes the mission where the journal left it: no new plan, no new upload.
#include <cstdint>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli.hpp"
#include "commands.hpp"
#include "fireswarm/common/camera_model.hpp"
#include "fireswarm/common/time.hpp"
#include "fireswarm/planner/area_io.hpp"
#include "fireswarm/planner/plan.hpp"
#include "fireswarm/server/airspace.hpp"
#include "fireswarm/server/journal.hpp"
#include "fireswarm/server/journal_format.hpp"
#include "fireswarm/server/lcm_bridge.hpp"
#include "fireswarm/server/mission_manager.hpp"
#include "fireswarm/server/operator_keys.hpp"
#include "fireswarm/server/server.hpp"
#include "key_store.hpp"
#include "launch_flags.hpp"
#include "link_flags.hpp"
#include "serve_loop.hpp"
#include "stop_signals.hpp"
#include "web_feed.hpp"
#include "web_flags.hpp"

namespace fireswarm::app {
namespace {

namespace po = boost::program_options;
namespace fs = std::filesystem;
using common::Nanos;

constexpr const char* kName = "serve";
constexpr int kMaxId = 254;
constexpr std::uint16_t kMissionId = 1;

struct Flags {
  std::string area;
  std::string no_fly;
  int drones = 0;
  int first_id = 1;
  std::vector<std::string> launch;
  std::string launch_file;
  double altitude_m = 60.0;
  double speed_mps = 10.0;
  double endurance_s = 1'800.0;
  double swap_s = 300.0;
  std::string camera = "seed";
  double telemetry_hz = 1.0;
  LinkFlags link;
  std::string lcm_url;
  std::string log;
  std::string csv;
  std::string journal;
  std::string radio_state;
  bool start = false;
  std::optional<double> duration_s;
  bool until_complete = false;
  bool recover = false;  ///< keep a corrupt journal's valid records, move the rest aside
  WebFlags web;
};

[[noreturn]] void BadFlag(const std::string& flag, const std::string& requirement,
                          const std::string& got) {
  ThrowBadFlag(kName, flag, requirement, got);
}

// Where the server keeps its frame counter and replay floors: --radio-state, else
// next to the journal; empty when unsecured.
fs::path RadioStatePath(const Flags& f) {
  if (!f.radio_state.empty()) return f.radio_state;
  if (!f.journal.empty()) return fs::path(f.journal + ".radio-state");
  return {};
}

void CheckFlags(const Flags& f, const po::variables_map& values) {
  CheckLinkFlags(kName, f.link, values, radio::kMaxChannels);
  if (f.area.empty()) BadFlag("area", "given (a GeoJSON file)", "");
  if (f.drones < 1 || f.drones > kMaxId) BadFlag("drones", "in 1..254", std::to_string(f.drones));
  if (f.first_id < 1 || f.first_id + f.drones - 1 > kMaxId) {
    BadFlag("first-id", "in 1..254 with every ID up to first-id + drones - 1 <= 254",
            std::to_string(f.first_id));
  }
  CheckLaunchFlags(kName, f.launch, f.launch_file);
  CheckFlagRange(kName, "altitude-m", f.altitude_m, {0.0, planner::kMaxAltitudeM, true});
  CheckFlagRange(kName, "speed-mps", f.speed_mps, {0.0, planner::kMaxSpeedMps, true});
  CheckFlagRange(kName, "endurance-s", f.endurance_s, {0.0, planner::kMaxEnduranceS, true});
  CheckFlagRange(kName, "swap-s", f.swap_s, {0.0, planner::kMaxSwapS});
  if (common::FindCameraModel(f.camera) == nullptr) {
    BadFlag("camera", common::CameraModelNames(), f.camera);
  }
  if (!(f.telemetry_hz > 0.0 && f.telemetry_hz <= 50.0)) {
    BadFlag("telemetry-hz", "in (0, 50]", FlagText(f.telemetry_hz));
  }
  if (f.duration_s) {
    CheckFlagRange(kName, "duration-s", *f.duration_s, {0.0, kMaxCommandDurationS, true});
  }
  CheckWebFlags(kName, f.web);
  if (f.recover && f.journal.empty()) {
    throw UsageError("fireswarm serve: --recover goes with --journal");
  }
  // --log is written as the server runs; the journal and radio state are read and
  // appended: each must be a regular file (or new) and none of the inputs.
  CheckOutputFlags(
      kName, {{"log", f.log}, {"journal", f.journal}, {"radio-state", f.radio_state}},
      {f.area, f.no_fly, f.launch_file});
  if (!f.start && f.lcm_url.empty() && f.web.http.empty()) {
    throw UsageError(
        "fireswarm serve: give --start, or --lcm URL or --http HOST:PORT to wait for an "
        "operator's START (otherwise the mission would never start)");
  }
  if (!f.start && f.link.keys.empty()) {
    throw UsageError(
        "fireswarm serve: without --start, give --keys DIR: an operator's START must be signed "
        "with a key in DIR/operators/ (otherwise every command is refused and the mission would "
        "never start)");
  }
  // Last, so a flag above that is wrong is named first.
  RequireKeys(kName, f.link);
  if (IsSecure(f.link) && RadioStatePath(f).empty()) {
    throw UsageError(
        "fireswarm serve: --checksum secure needs --journal FILE or --radio-state FILE: the "
        "frame counter must survive a restart, or the vehicles refuse the restarted server");
  }
  if (!f.radio_state.empty() && !IsSecure(f.link)) {
    throw UsageError("fireswarm serve: --radio-state goes with --checksum secure");
  }
}

std::vector<int> ReceiverIds(const Flags& f) {
  std::vector<int> ids;
  for (int i = 0; i < f.drones; ++i) ids.push_back(f.first_id + i);
  return ids;
}

// The fleet the flags describe: its sites (--launch, repeated, or --launch-file;
// the area's default), altitude, speed, camera and sorties.
planner::FleetSpec FleetFor(const Flags& f, const planner::SearchArea& area) {
  planner::FleetSpec fleet;
  fleet.receiver_ids = ReceiverIds(f);
  SetLaunchSites(kName, f.launch, f.launch_file, area, fleet);
  fleet.altitude_m = f.altitude_m;
  fleet.speed_mps = f.speed_mps;
  fleet.endurance_s = f.endurance_s;
  fleet.swap_s = f.swap_s;
  fleet.camera = common::FindCameraModel(f.camera);
  return fleet;
}

// `area`: the search area as planned, its no-fly zones (--no-fly and the area
// file's) kept out of by the legs the server makes up. The coverage on LCM is
// the --camera's from telemetry, mounted straight down (serve has no pitch flag:
// the planner's default, planner::FleetSpec::camera_pitch_deg).
server::ServerConfig ServerConfigFor(const Flags& f, const planner::SearchArea& area) {
  server::ServerConfig config;
  config.radio.mode = ModeOf(f.link);
  config.radio.checksum = ChecksumOf(f.link);
  if (IsSecure(f.link)) {
    try {
      config.radio.security =
          ServerSecurityFromStore(f.link.keys, ReceiverIds(f), RadioStatePath(f));
    } catch (const std::runtime_error& e) {
      throw UsageError(std::string("fireswarm serve: ") + e.what());
    }
  }
  config.radio.timing.baud = static_cast<int>(f.link.baud);
  // Several links, one radio channel each (issue 21): the drones' IDs in order,
  // in contiguous blocks as even as can be, the first block on the first link.
  const std::size_t links = LinkCount(f.link);
  if (links > 1) {
    config.channels.assign(links, config.radio.timing);
    for (int i = 0; i < f.drones; ++i) {
      config.vehicle_channels[f.first_id + i] =
          static_cast<std::size_t>(i) * links / static_cast<std::size_t>(f.drones);
    }
  }
  config.telemetry_hz = f.telemetry_hz;
  config.no_fly = area.no_fly;
  config.area = area.area;
  config.camera = common::CameraModelByName(f.camera);
  config.camera_pitch_deg = planner::FleetSpec{}.camera_pitch_deg;
  // The published plan shows one site: the first.
  const planner::Point launch = FleetFor(f, area).launch_points.front();
  config.launch_en_m = common::EastNorth{launch.x(), launch.y()};
  if (!f.link.keys.empty()) {
    try {
      config.operators = server::LoadOperatorKeys(f.link.keys);
    } catch (const std::runtime_error& e) {
      throw UsageError(std::string("fireswarm serve: --keys: ") + e.what());
    }
  }
  if (!f.start && config.operators.empty()) {
    throw UsageError("fireswarm serve: without --start, --keys DIR needs an operator key in " +
                     f.link.keys +
                     "/operators/ (fireswarm keys add-operator): an unsigned START is refused, "
                     "so the mission would never start");
  }
  return config;
}

// Operator commands come in signed only (docs/lcm.md): say at the start which
// operators may command, or loudly that nobody can.
void PrintOperators(const Flags& f, const server::ServerConfig& config) {
  if (f.lcm_url.empty() && f.web.http.empty()) return;
  if (config.operators.empty()) {
    std::cerr << "fireswarm serve: WARNING: no --keys: every operator command (LCM and --http) "
                 "is refused; give --keys DIR with DIR/operators/NAME.key to take them"
              << std::endl;
    return;
  }
  std::cerr << "fireswarm serve: operator commands signed by";
  for (const auto& [id, key] : config.operators) std::cerr << ' ' << id;
  std::cerr << " (window +-" << config.command_window_us / 1'000'000 << " s)" << std::endl;
}

// The missions in their altitude layers (server/airspace.hpp), and the layers.
struct PlannedMissions {
  std::vector<server::DroneMission> missions;
  server::AirspacePlan airspace;
};

PlannedMissions PlanMissions(const Flags& f, const planner::SearchArea& area) {
  const planner::FleetSpec fleet = FleetFor(f, area);
  planner::Plan plan;
  try {
    plan = planner::PlanSearch(area, fleet);
  } catch (const std::invalid_argument& e) {
    throw UsageError(std::string("fireswarm serve: the planner refused the fleet: ") + e.what());
  }
  PlannedMissions planned;
  planned.missions = server::WithoutLaunchSite(
      server::ToDroneMissions(plan, kMissionId, f.altitude_m, f.speed_mps), area.frame,
      server::LaunchSitesOf(plan));
  planned.airspace = server::AssignAirspace(planned.missions, area.frame,
                                            server::LaunchSitesOf(plan), f.altitude_m,
                                            server::SeparationConfig{});
  nlohmann::ordered_json line;
  line["event"] = "planned";
  line["drones"] = plan.drones.size();
  int sorties = 0;
  std::vector<int> site_drones(fleet.launch_points.size(), 0);
  for (const planner::DronePlan& drone : plan.drones) {
    sorties += drone.sorties;
    ++site_drones.at(drone.site);
  }
  line["sorties"] = sorties;
  nlohmann::ordered_json sites = nlohmann::ordered_json::array();
  for (std::size_t k = 0; k < fleet.launch_points.size(); ++k) {
    const planner::Point& site = fleet.launch_points[k];
    const common::LatLon position = area.frame.ToGeodetic({site.x(), site.y()});
    sites.push_back(
        {{"lat", position.lat_deg}, {"lon", position.lon_deg}, {"drones", site_drones[k]}});
  }
  line["sites"] = std::move(sites);
  line["coverage"] = plan.coverage;
  line["makespan_s"] = plan.makespan_s;
  line["separation"] = planned.airspace.rule;
  std::cout << line.dump() << std::endl;
  return planned;
}

std::optional<server::LcmBridge> BridgeFor(const Flags& f) {
  if (f.lcm_url.empty() && f.log.empty() && f.csv.empty()) return std::nullopt;
  server::LcmBridgeConfig config;
  config.url = f.lcm_url;
  if (!f.log.empty()) config.log_path = f.log;
  if (!f.csv.empty()) config.csv_dir = f.csv;
  return std::optional<server::LcmBridge>(std::in_place, config);
}

void PrintResumed(const server::Journal& journal, std::size_t records, const server::Server& server,
                  Nanos clock_offset) {
  nlohmann::ordered_json line;
  line["event"] = "resumed";
  line["journal"] = journal.path().string();
  line["records"] = records;
  line["dropped_lines"] = journal.recovery().dropped_lines;
  if (!journal.recovery().moved_aside.empty()) {
    line["moved_aside"] = journal.recovery().moved_aside.string();
  }
  line["state"] = server::ToString(server.state());
  line["tracks"] = server.fusion().tracks().size();
  line["t_s"] = common::ToSeconds(clock_offset);
  std::cout << line.dump() << std::endl;
}

// What a journal did not bring back (all of it for a new mission): the fleet, the
// mission (planned now), the start.
void CompleteSetup(const Flags& f, const planner::SearchArea& area, Nanos now,
                   server::Server& server) {
  const double now_s = common::ToSeconds(now);
  for (const int id : ReceiverIds(f)) {
    if (!server.registry().Contains(static_cast<std::uint8_t>(id))) server.AddVehicle(id, now_s);
  }
  if (server.mission() == nullptr) {
    PlannedMissions planned = PlanMissions(f, area);
    server.LoadMission(std::move(planned.missions), now_s, std::move(planned.airspace));
  }
  if (f.start && server.state() == server::MissionState::kIdle) {
    server::OperatorCommand start;
    start.reason = "--start";
    std::string why;
    if (!server.Handle(start, now, &why)) {
      throw std::runtime_error("the server refused to start the mission: " + why);
    }
  }
}

// The options, written into `f` (which must outlive them).
po::options_description OptionsFor(Flags& f) {
  po::options_description options("serve options");
  auto add = options.add_options();
  add("area", po::value(&f.area)->value_name("FILE"),
      "search area: GeoJSON Polygon/MultiPolygon (features with \"no_fly\": true are no-fly)");
  add("no-fly", po::value(&f.no_fly)->value_name("FILE"), "no-fly zones: GeoJSON polygons");
  add("drones", po::value(&f.drones), "number of vehicles, 1..254");
  add("first-id", po::value(&f.first_id)->default_value(f.first_id),
      "receiver ID of the first vehicle; the others follow");
  add("launch", po::value(&f.launch)->value_name("LAT,LON")->composing(),
      "a launch site; repeat for several (the planner spreads the drones over them). Default: "
      "the area's centroid, or its corner nearest to it");
  add("launch-file", po::value(&f.launch_file)->value_name("FILE"),
      "launch sites as GeoJSON Points, each with an optional integer property \"drones\"");
  add("altitude-m", po::value(&f.altitude_m)->default_value(f.altitude_m),
      "search altitude above ground, m");
  add("speed-mps", po::value(&f.speed_mps)->default_value(f.speed_mps), "cruise speed, m/s");
  add("endurance-s", po::value(&f.endurance_s)->default_value(f.endurance_s),
      "flight time per sortie, s; longer plans are flown in sorties with a battery swap "
      "between them");
  add("swap-s", po::value(&f.swap_s)->default_value(f.swap_s),
      "time on the ground between two sorties (battery swap), s");
  add("camera", po::value(&f.camera)->default_value(f.camera),
      ("the fleet's thermal camera (sets the lane spacing): " + common::CameraModelNames())
          .c_str());
  add("telemetry-hz", po::value(&f.telemetry_hz)->default_value(f.telemetry_hz),
      "telemetry turns per vehicle and second");
  AddLinkOptions(options, f.link);
  add("lcm", po::value(&f.lcm_url)->value_name("URL"),
      (std::string("publish on LCM and take signed operator commands there, e.g. ") +
       server::kDefaultLcmUrl + " (host-local; default: no LCM network)")
          .c_str());
  add("log", po::value(&f.log)->value_name("FILE"), "write an LCM log for lcm-logplayer");
  add("csv", po::value(&f.csv)->value_name("DIR"), "write one CSV per message type into DIR");
  add("journal", po::value(&f.journal)->value_name("FILE"),
      "append mission state and fire reports here; an existing journal is resumed");
  add("recover", po::bool_switch(&f.recover),
      "a journal corrupt before its last line: resume from the valid records before the bad "
      "line and move it and every line after it to JOURNAL.corrupt (named on stderr)");
  add("radio-state", po::value(&f.radio_state)->value_name("FILE"),
      "secure mode: the frame counter and replay floors (default: JOURNAL.radio-state)");
  add("start", po::bool_switch(&f.start),
      "start the mission at once (default: wait for an operator START on LCM)");
  add("duration-s", po::value<double>()->notifier([&f](double v) { f.duration_s = v; }),
      "stop after this much wall time, s (default: run until SIGINT or SIGTERM)");
  add("until-complete", po::bool_switch(&f.until_complete),
      "stop once the mission is complete: exit 0 (1 when aborted or --duration-s passed first)");
  AddWebOptions(options, f.web);
  return options;
}

}  // namespace

int RunServe(const std::vector<std::string>& args) {
  Flags f;
  const po::options_description options = OptionsFor(f);
  po::variables_map values;
  if (!ParseCommandLine(kName,
                        "--area A.geojson --drones N (--serial DEVICE | --udp LOCAL REMOTE)... "
                        "(--start | --keys DIR (--lcm URL | --http HOST:PORT)) [options]",
                        options, {}, args, values)) {
    return kExitOk;
  }
  CheckFlags(f, values);
  WarnIfUnsecured(kName, f.link);
  const planner::SearchArea area = planner::LoadSearchArea(
      f.area, f.no_fly.empty() ? std::nullopt : std::optional<fs::path>(f.no_fly));
  const server::ServerConfig config = ServerConfigFor(f, area);
  PrintOperators(f, config);

  // The journal first: a resumed mission needs no plan.
  std::vector<server::JournalEntry> entries;
  std::optional<server::Journal> journal;
  if (!f.journal.empty()) {
    const auto visit = [&](const server::JournalRecord& record) {
      try {
        entries.push_back(server::JournalEntryOf(record));
      } catch (const std::runtime_error& e) {
        throw std::runtime_error(f.journal + ": " + e.what());
      }
    };
    try {
      journal.emplace(server::Journal::Open(f.journal, visit, server::JournalSync::kEveryAppend,
                                            f.recover ? server::JournalCorruption::kKeepValidPrefix
                                                      : server::JournalCorruption::kRefuse));
    } catch (const server::JournalCorruptError& e) {
      throw UsageError(std::string("fireswarm serve: ") + e.what() +
                       "; to resume from the valid records before it and move the rest aside, "
                       "start again with --recover");
    }
    const server::JournalRecovery& recovery = journal->recovery();
    if (!recovery.moved_aside.empty()) {
      std::cerr << "fireswarm serve: WARNING: " << f.journal << ": " << recovery.corruption
                << "; kept the " << recovery.records << " records before it and moved "
                << recovery.dropped_lines << " lines (" << recovery.dropped_bytes
                << " bytes) from it on to " << recovery.moved_aside.string() << std::endl;
    }
  }
  const bool resumed = !entries.empty();
  Nanos clock_offset{0};
  for (const server::JournalEntry& entry : entries) {
    clock_offset = std::max(clock_offset, common::FromSeconds(entry.t_s));
  }
  server::Server server = resumed ? server::Server::Restore(config, area.frame, entries)
                                  : server::Server(config, area.frame);
  if (resumed) PrintResumed(*journal, entries.size(), server, clock_offset);

  const StopOnSignals stop_on_signals;
  std::vector<OpenedLink> links;
  std::vector<radio::IoLink*> channels;
  for (std::size_t k = 0; k < LinkCount(f.link); ++k) {
    links.push_back(OpenLink(f.link, k));
    channels.push_back(links.back().link.get());
  }
  std::optional<server::LcmBridge> bridge = BridgeFor(f);
  ServeLoop loop(server, channels, journal ? &*journal : nullptr, bridge ? &*bridge : nullptr);
  const std::unique_ptr<server::WebServer> web = StartWebServer(kName, f.web, false);

  CompleteSetup(f, area, clock_offset, server);
  loop.FlushJournal();
  if (f.link.print_bound_port) {
    for (const OpenedLink& link : links) {
      std::cout << "bound_port=" << link.udp->local_port() << std::endl;
    }
  }

  ServeOptions run;
  run.clock_offset = clock_offset;
  run.duration_s = f.duration_s;
  run.until_complete = f.until_complete;
  std::optional<WebFeed> feed;
  if (web) {
    feed.emplace(*web, "live");
    run.on_step = [&](Nanos now, std::int64_t utime, std::int64_t utime_at_zero) {
      feed->Step(server, now, utime, utime_at_zero);
    };
  }
  const ServeStop stop = loop.Run(run);
  nlohmann::ordered_json summary = loop.Summary();
  summary["stop"] = ToString(stop);
  summary["resumed"] = resumed;
  std::cout << summary.dump() << std::endl;
  if (f.until_complete && stop != ServeStop::kComplete && stop != ServeStop::kSignal) {
    return kExitCheckFailed;
  }
  return kExitOk;
}

}  // namespace fireswarm::app
