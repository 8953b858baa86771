// `fireswarm plan`: a search area (GeoJSON) and a fleet in; per-drone search plans
// out as GeoJSON and QGroundControl .plan files, with the figures as a table or JSON.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "cli.hpp"
#include "commands.hpp"
#include "fireswarm/common/output_files.hpp"
#include "fireswarm/common/camera_model.hpp"
#include "fireswarm/planner/area_io.hpp"
#include "fireswarm/planner/export.hpp"
#include "fireswarm/planner/plan.hpp"
#include "launch_flags.hpp"

namespace fireswarm::app {
namespace {

namespace po = boost::program_options;
namespace fs = std::filesystem;
using planner::FleetSpec;
using planner::Plan;
using planner::SearchArea;

constexpr const char* kName = "plan";
constexpr int kMaxDrones = 254;  // receiver IDs 1..254

struct Flags {
  std::string area;
  std::string no_fly;
  int drones = 0;
  std::string receiver_ids;
  std::vector<std::string> launch;
  std::string launch_file;
  double swap_s = 300.0;
  double climb_mps = 3.0;
  double descent_mps = 1.0;
  double altitude_m = 60.0;
  double speed_mps = 10.0;
  double endurance_s = 1'800.0;
  std::string camera = "seed";
  double camera_pitch_deg = -90.0;
  double overlap = 0.10;
  double turn_cost_s = 4.0;
  std::string planner = "lawnmower";
  unsigned seed = 1;
  std::string out;
  std::string qgc;
  bool json = false;
};

[[noreturn]] void BadFlag(const std::string& flag, const std::string& problem) {
  throw UsageError("fireswarm plan: --" + flag + " " + problem);
}

std::string Text(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

std::vector<std::string> SplitOn(const std::string& text, char separator) {
  std::vector<std::string> parts;
  std::istringstream in(text);
  for (std::string part; std::getline(in, part, separator);) parts.push_back(part);
  return parts;
}

std::optional<double> ParseNumber(const std::string& text) {
  std::size_t used = 0;
  try {
    const double value = std::stod(text, &used);
    if (used == text.size() && std::isfinite(value)) return value;
  } catch (const std::exception&) {
  }
  return std::nullopt;
}

std::vector<int> ReceiverIds(const Flags& f) {
  std::vector<int> ids;
  if (f.receiver_ids.empty()) {
    for (int id = 1; id <= f.drones; ++id) ids.push_back(id);
    return ids;
  }
  for (const std::string& part : SplitOn(f.receiver_ids, ',')) {
    const auto value = ParseNumber(part);
    if (!value || *value != std::floor(*value) || *value < 1 || *value > kMaxDrones) {
      BadFlag("receiver-ids", "must be comma-separated integers in 1..254, got '" + part + "'");
    }
    const int id = static_cast<int>(*value);
    if (std::find(ids.begin(), ids.end(), id) != ids.end()) {
      BadFlag("receiver-ids", "lists " + part + " twice");
    }
    ids.push_back(id);
  }
  if (ids.size() != static_cast<std::size_t>(f.drones)) {
    BadFlag("receiver-ids",
            "has " + std::to_string(ids.size()) + " IDs for --drones " + std::to_string(f.drones));
  }
  return ids;
}

// Every flag's range, checked before any file is read or written.
void CheckFlags(const Flags& f) {
  if (f.area.empty()) BadFlag("area", "is required (a GeoJSON file)");
  if (f.out.empty()) BadFlag("out", "is required (the GeoJSON file to write)");
  if (f.drones < 1 || f.drones > kMaxDrones) {
    BadFlag("drones", "must be in 1..254, got " + std::to_string(f.drones));
  }
  CheckFlagRange(kName, "altitude-m", f.altitude_m, {0.0, planner::kMaxAltitudeM, true});
  CheckFlagRange(kName, "speed-mps", f.speed_mps, {0.0, planner::kMaxSpeedMps, true});
  CheckFlagRange(kName, "endurance-s", f.endurance_s, {0.0, planner::kMaxEnduranceS, true});
  CheckFlagRange(kName, "swap-s", f.swap_s, {0.0, planner::kMaxSwapS});
  CheckFlagRange(kName, "climb-mps", f.climb_mps, {0.0, planner::kMaxVerticalMps, true});
  CheckFlagRange(kName, "descent-mps", f.descent_mps, {0.0, planner::kMaxVerticalMps, true});
  CheckLaunchFlags("plan", f.launch, f.launch_file);
  if (!(f.overlap >= 0 && f.overlap < 1)) {
    BadFlag("overlap", "must be in [0, 1), got " + Text(f.overlap));
  }
  CheckFlagRange(kName, "turn-cost-s", f.turn_cost_s, {0.0, planner::kMaxTurnCostS});
  if (!(f.camera_pitch_deg >= -90 && f.camera_pitch_deg < 0)) {
    BadFlag("camera-pitch-deg", "must be in [-90, 0), got " + Text(f.camera_pitch_deg));
  }
  if (common::FindCameraModel(f.camera) == nullptr) {
    BadFlag("camera", "must be one of " + common::CameraModelNames() + ", got '" + f.camera + "'");
  }
  if (f.planner != "lawnmower" && f.planner != "ompl") {
    BadFlag("planner", "must be lawnmower or ompl, got '" + f.planner + "'");
  }
  CheckOutputFlags(kName, {{"out", f.out}}, {f.area, f.no_fly, f.launch_file});
  if (!f.qgc.empty()) {
    std::error_code error;
    const fs::file_status status = fs::symlink_status(f.qgc, error);
    if (status.type() == fs::file_type::not_found) {
      // Created when the plan is written: its parent must take it.
      CheckOutputFlags(kName, {{"qgc", f.qgc}}, {});
    } else if (status.type() != fs::file_type::directory) {
      BadFlag("qgc", "must be a directory, got " + f.qgc + " (not a directory)");
    }
  }
}

FleetSpec ToFleet(const Flags& f, const SearchArea& area) {
  FleetSpec fleet;
  fleet.receiver_ids = ReceiverIds(f);
  SetLaunchSites("plan", f.launch, f.launch_file, area, fleet);
  fleet.swap_s = f.swap_s;
  fleet.climb_mps = f.climb_mps;
  fleet.descent_mps = f.descent_mps;
  fleet.altitude_m = f.altitude_m;
  fleet.speed_mps = f.speed_mps;
  fleet.endurance_s = f.endurance_s;
  fleet.camera = common::FindCameraModel(f.camera);
  fleet.camera_pitch_deg = f.camera_pitch_deg;
  fleet.side_overlap = f.overlap;
  fleet.turn_cost_s = f.turn_cost_s;
  return fleet;
}

// FleetSpec field names in PlanSearch's messages -> the flags that set them.
std::string InFlagTerms(const std::string& message) {
  static const std::pair<const char*, const char*> kFlagOfField[] = {
      {"receiver_ids", "receiver-ids"},
      {"launch_points", "launch"},
      {"site_drones", "launch-file"},
      {"swap_s", "swap-s"},
      {"climb_mps", "climb-mps"},
      {"descent_mps", "descent-mps"},
      {"altitude_m", "altitude-m"},
      {"speed_mps", "speed-mps"},
      {"endurance_s", "endurance-s"},
      {"turn_cost_s", "turn-cost-s"},
      {"camera_pitch_deg", "camera-pitch-deg"},
      {"side_overlap", "overlap"},
      {"camera", "camera"}};
  for (const auto& [field, flag] : kFlagOfField) {
    if (message.rfind(field, 0) == 0)
      return "--" + std::string(flag) + message.substr(std::string(field).size());
  }
  return message;
}

nlohmann::ordered_json ToJson(const Flags& f, const Plan& plan,
                              const std::vector<fs::path>& qgc_files) {
  nlohmann::ordered_json drones = nlohmann::ordered_json::array();
  for (const planner::DronePlan& d : plan.drones) {
    drones.push_back({{"receiver_id", d.receiver_id},
                      {"site", d.site},
                      {"waypoints", d.waypoints.size()},
                      {"sorties", d.sorties},
                      {"length_m", d.length_m},
                      {"time_s", d.time_s},
                      {"sweep_s", d.sweep_s},
                      {"turn_s", d.turn_s},
                      {"transit_s", d.transit_s},
                      {"ground_s", d.ground_s},
                      {"vertical_s", d.vertical_s},
                      {"longest_sortie_s", d.longest_sortie_s}});
  }
  nlohmann::ordered_json files = nlohmann::ordered_json::array();
  for (const fs::path& p : qgc_files) files.push_back(p.string());
  return {{"area", f.area},
          {"planner", f.planner},
          {"camera", f.camera},
          {"sweep_width_m", plan.sweep_width_m},
          {"coverage", plan.coverage},
          {"makespan_s", plan.makespan_s},
          {"lower_bound_s", plan.lower_bound_s},
          {"lower_bound_basis", plan.lower_bound_basis},
          {"nofly_violation_m", plan.nofly_violation_m},
          {"planning_seconds", plan.planning_seconds},
          {"drones", std::move(drones)},
          {"out", f.out},
          {"qgc_files", std::move(files)}};
}

void PrintTable(const Flags& f, const Plan& plan, const std::vector<fs::path>& qgc_files) {
  std::cout << "plan: " << f.area << ", " << plan.drones.size() << " drones, " << f.planner
            << ", camera " << f.camera << ", sweep width " << std::fixed << std::setprecision(1)
            << plan.sweep_width_m << " m\n";
  std::cout
      << "  receiver  site  waypoints  sorties  length (km)  time (min)  longest sortie (min)\n";
  for (const planner::DronePlan& d : plan.drones) {
    std::cout << "  " << std::setw(8) << d.receiver_id << std::setw(6) << d.site + 1
              << std::setw(11) << d.waypoints.size() << std::setw(9) << d.sorties << std::setw(13)
              << std::setprecision(2) << d.length_m / 1e3 << std::setw(12) << std::setprecision(1)
              << d.time_s / 60.0 << std::setw(22) << d.longest_sortie_s / 60.0 << "\n";
  }
  const double ratio = plan.lower_bound_s > 0 ? plan.makespan_s / plan.lower_bound_s : 0.0;
  std::cout << std::setprecision(2) << "  coverage " << 100.0 * plan.coverage << " %, makespan "
            << std::setprecision(1) << plan.makespan_s / 60.0 << " min (lower bound "
            << plan.lower_bound_s / 60.0 << " min, ratio " << std::setprecision(3) << ratio
            << "), in no-fly zones " << std::setprecision(1) << plan.nofly_violation_m
            << " m, planned in " << std::setprecision(3) << plan.planning_seconds << " s\n";
  std::cout << "  lower bound from " << plan.lower_bound_basis << "\n";
  std::cout << "  wrote " << f.out;
  if (!qgc_files.empty()) std::cout << " and " << qgc_files.size() << " .plan files in " << f.qgc;
  std::cout << "\n";
}

}  // namespace

int RunPlan(const std::vector<std::string>& args) {
  Flags f;
  po::options_description options("plan options");
  auto add = options.add_options();
  add("area", po::value(&f.area)->value_name("FILE"),
      "search area: GeoJSON Polygon/MultiPolygon (holes allowed; features with "
      "\"no_fly\": true are no-fly zones)");
  add("no-fly", po::value(&f.no_fly)->value_name("FILE"), "no-fly zones: GeoJSON polygons");
  add("drones", po::value(&f.drones), "number of drones, 1..254");
  add("receiver-ids", po::value(&f.receiver_ids)->value_name("LIST"),
      "comma-separated receiver IDs, one per drone (default 1..N)");
  add("launch", po::value(&f.launch)->value_name("LAT,LON")->composing(),
      "a launch site; repeat for several (the planner spreads the drones over them). Default: "
      "the area's centroid, or the area corner nearest to it when the centroid is outside");
  add("launch-file", po::value(&f.launch_file)->value_name("FILE"),
      "launch sites as GeoJSON Points, each with an optional integer property \"drones\"");
  add("swap-s", po::value(&f.swap_s)->default_value(f.swap_s),
      "time on the ground between two sorties (battery swap, checks)");
  add("climb-mps", po::value(&f.climb_mps)->default_value(f.climb_mps),
      "take-off climb rate: every sortie climbs to --altitude-m over its site");
  add("descent-mps", po::value(&f.descent_mps)->default_value(f.descent_mps),
      "landing descent rate: every sortie descends from its altitude to land");
  add("altitude-m", po::value(&f.altitude_m)->default_value(f.altitude_m),
      "flight altitude above ground");
  add("speed-mps", po::value(&f.speed_mps)->default_value(f.speed_mps), "cruise speed");
  add("endurance-s", po::value(&f.endurance_s)->default_value(f.endurance_s),
      "flight time per sortie; longer plans are split into sorties");
  add("camera", po::value(&f.camera)->default_value(f.camera), common::CameraModelNames().c_str());
  add("camera-pitch-deg", po::value(&f.camera_pitch_deg)->default_value(f.camera_pitch_deg),
      "camera mount pitch from the horizon, -90 = straight down");
  add("overlap", po::value(&f.overlap)->default_value(f.overlap, "0.1"),
      "side overlap of neighbouring lanes, fraction of the footprint width");
  add("turn-cost-s", po::value(&f.turn_cost_s)->default_value(f.turn_cost_s),
      "time lost at each lane turn");
  add("planner", po::value(&f.planner)->default_value(f.planner), "lawnmower or ompl");
  add("seed", po::value(&f.seed)->default_value(f.seed), "random seed (OMPL transit)");
  add("out", po::value(&f.out)->value_name("FILE"), "GeoJSON FeatureCollection to write");
  add("qgc", po::value(&f.qgc)->value_name("DIR"),
      "also write QGroundControl .plan files (one per drone and sortie) into DIR");
  add("json", po::bool_switch(&f.json), "print one JSON object instead of the table");
  po::variables_map values;
  if (!ParseCommandLine(kName,
                        "--area A.geojson [--no-fly B.geojson] --drones N --out plan.geojson "
                        "[options]",
                        options, {}, args, values)) {
    return kExitOk;
  }
  CheckFlags(f);

  const SearchArea area = planner::LoadSearchArea(
      f.area, f.no_fly.empty() ? std::nullopt : std::optional<fs::path>(f.no_fly));
  const FleetSpec fleet = ToFleet(f, area);
  const auto kind =
      f.planner == "ompl" ? planner::PlannerKind::kOmpl : planner::PlannerKind::kLawnmower;
  Plan plan;
  try {
    plan = planner::PlanSearch(area, fleet, kind, f.seed);
  } catch (const std::invalid_argument& e) {
    throw UsageError("fireswarm plan: " + InFlagTerms(e.what()));
  }

  // Every text is built before the first file is touched; all files or none are written.
  const std::string geojson = planner::PlanToGeoJson(plan, area, fleet);
  const std::vector<planner::QgcPlanFile> qgc =
      f.qgc.empty() ? std::vector<planner::QgcPlanFile>{} : planner::PlanToQgc(plan, area, fleet);
  std::vector<fs::path> qgc_files;
  common::OutputFiles output;
  const bool made_qgc_dir = !f.qgc.empty() && fs::create_directory(f.qgc);
  try {
    for (const planner::QgcPlanFile& file : qgc) {
      qgc_files.push_back(fs::path(f.qgc) / file.file_name);
      output.Stage(qgc_files.back(), file.json);
    }
    output.Stage(f.out, geojson);
    output.Commit();
  } catch (const std::exception&) {
    std::error_code ignored;
    if (made_qgc_dir && fs::is_empty(f.qgc, ignored)) fs::remove(f.qgc, ignored);
    throw;
  }

  if (f.json) {
    std::cout << ToJson(f, plan, qgc_files).dump() << "\n";
  } else {
    PrintTable(f, plan, qgc_files);
  }
  return kExitOk;
}

}  // namespace fireswarm::app
