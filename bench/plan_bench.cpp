// plan_bench: both coverage planners on every scenario area with small and large
// fleets; prints a table (or JSON lines) of coverage, makespan / lower bound,
// metres flown in no-fly zones and planning time, and marks every target of the
// issue a row misses. --check exits 1 when coverage, no-fly or planning time is
// missed; --check-ratio also when a makespan / lower bound target is (not met
// today on every row: README.md has the figures and why):
//   coverage >= 99.5 % and 0 m in no-fly zones: every row, both planners;
//   makespan / lower bound, lawnmower rows of the areas the issue names:
//     <= 1.05 on the convex area, <= 1.15 on the areas with holes (holes,
//     forest_large); the concave and no-fly rows print their ratio unchecked
//     (the issue sets no target for them, and the bound ignores the detour
//     around a no-fly zone);
//   lawnmower planning < 2 s for any area with 20 drones (one core).
// Every row also splits the slowest drone's time (makespan_s) into sweeping lanes,
// turning at lane ends and the rest ("transit": lane-to-lane connections, cell
// changes, launch to share and back), next to the lower bound it is compared
// with. The OMPL planner's path has no lanes: all its flight shows as transit.
//
//   plan_bench [--areas DIR] [--only NAME[,NAME...]] [--drones 4,20]
//              [--planners lawnmower,ompl] [--json] [--check] [--check-ratio]
#include <algorithm>
#include <boost/geometry/algorithms/area.hpp>
#include <boost/geometry/strategies/cartesian/area.hpp>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "fireswarm/common/camera_model.hpp"
#include "fireswarm/common/units.hpp"
#include "fireswarm/planner/area_io.hpp"
#include "fireswarm/planner/plan.hpp"

namespace {

namespace fp = fireswarm::planner;

constexpr double kMinCoverage = 0.995;
constexpr double kMaxRatioConvex = 1.05;
constexpr double kMaxRatioHoles = 1.15;
constexpr double kMaxPlanningSeconds = 2.0;

// Which makespan / lower bound target the issue sets for an area.
enum class RatioTarget { kConvex, kHoles, kNone };

struct Scenario {
  const char* name;
  const char* area_file;
  const char* no_fly_file;  // nullptr = none
  RatioTarget target;
};

constexpr Scenario kScenarios[] = {
    {"convex", "convex.geojson", nullptr, RatioTarget::kConvex},
    {"concave_u", "concave_u.geojson", nullptr, RatioTarget::kNone},
    {"concave_l", "concave_l.geojson", nullptr, RatioTarget::kNone},
    {"holes", "holes.geojson", nullptr, RatioTarget::kHoles},
    {"nofly", "nofly_area.geojson", "nofly_zones.geojson", RatioTarget::kNone},
    {"forest_large", "forest_large.geojson", nullptr, RatioTarget::kHoles},
};

struct Options {
  std::string areas_dir = "scenarios/areas";
  std::vector<std::string> only;
  std::vector<int> drones{4, 20};
  std::vector<std::string> planners{"lawnmower", "ompl"};
  bool json = false;
  bool check = false;
  bool check_ratio = false;
};

std::vector<std::string> Split(const std::string& text) {
  std::vector<std::string> parts;
  std::istringstream in(text);
  for (std::string part; std::getline(in, part, ',');) parts.push_back(part);
  return parts;
}

std::optional<Options> ParseOptions(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    if (flag == "--json") {
      o.json = true;
    } else if (flag == "--check") {
      o.check = true;
    } else if (flag == "--check-ratio") {
      o.check = true;
      o.check_ratio = true;
    } else if (i + 1 < argc && flag == "--areas") {
      o.areas_dir = argv[++i];
    } else if (i + 1 < argc && flag == "--only") {
      o.only = Split(argv[++i]);
    } else if (i + 1 < argc && flag == "--planners") {
      o.planners = Split(argv[++i]);
    } else if (i + 1 < argc && flag == "--drones") {
      o.drones.clear();
      for (const std::string& n : Split(argv[++i])) o.drones.push_back(std::atoi(n.c_str()));
    } else {
      std::cerr << "plan_bench: unknown or incomplete option '" << flag << "'\n"
                << "usage: plan_bench [--areas DIR] [--only NAME,...] [--drones 4,20] "
                   "[--planners lawnmower,ompl] [--json] [--check] [--check-ratio]\n";
      return std::nullopt;
    }
  }
  return o;
}

struct Row {
  std::string scenario;
  std::string planner;
  int drones = 0;
  double area_km2 = 0.0;
  fp::Plan plan;
  std::string target = "-";         // the ratio target --check applies, "-" none
  std::vector<std::string> missed;  // targets this row misses
};

fp::FleetSpec Fleet(const fp::SearchArea& area, int drones) {
  fp::FleetSpec fleet;
  for (int id = 1; id <= drones; ++id) fleet.receiver_ids.push_back(id);
  fleet.launch_points = {fp::DefaultLaunchPoint(area)};
  fleet.camera = &fireswarm::common::CameraModelByName("seed");
  fleet.altitude_m = 60.0;
  fleet.speed_mps = 10.0;
  fleet.endurance_s = 1e9;  // figures of one flight each: sorties are not what is measured
  return fleet;
}

Row Measure(const Scenario& s, const fp::SearchArea& area, const std::string& planner, int drones) {
  Row row{s.name, planner, drones, 0.0, {}, "-", {}};
  if (planner == "lawnmower" && s.target == RatioTarget::kConvex) row.target = "1.05";
  if (planner == "lawnmower" && s.target == RatioTarget::kHoles) row.target = "1.15";
  for (const fp::Polygon& p : area.area) row.area_km2 += boost::geometry::area(p);
  row.area_km2 /= fireswarm::common::kSquareMetresPerKm2;
  const auto kind = planner == "ompl" ? fp::PlannerKind::kOmpl : fp::PlannerKind::kLawnmower;
  try {
    row.plan = fp::PlanSearch(area, Fleet(area, drones), kind, 1);
  } catch (const std::exception& e) {
    row.missed.push_back(std::string("planning failed: ") + e.what());
    return row;
  }
  const fp::Plan& p = row.plan;
  if (p.coverage < kMinCoverage) row.missed.push_back("coverage");
  if (p.nofly_violation_m > 0.0) row.missed.push_back("no-fly");
  if (planner == "lawnmower") {
    const double ratio = p.makespan_s / p.lower_bound_s;
    if ((s.target == RatioTarget::kConvex && ratio > kMaxRatioConvex) ||
        (s.target == RatioTarget::kHoles && ratio > kMaxRatioHoles)) {
      row.missed.push_back("ratio");
    }
    if (drones >= 20 && p.planning_seconds >= kMaxPlanningSeconds) row.missed.push_back("time");
  }
  return row;
}

void PrintHeader() {
  std::cout << std::left << std::setw(14) << "area" << std::right << std::setw(9) << "km2"
            << std::setw(11) << "planner" << std::setw(7) << "drones" << std::setw(11)
            << "coverage%" << std::setw(12) << "makespan_s" << std::setw(9) << "ratio"
            << std::setw(8) << "target" << std::setw(11) << "nofly_m" << std::setw(11) << "plan_s"
            << std::setw(9) << "bound_s" << std::setw(9) << "sweep_s" << std::setw(8) << "turn_s"
            << std::setw(10) << "transit_s" << std::setw(9) << "spread%"
            << "  missed\n";
}

// (slowest - fastest) / slowest over the drones that fly: the partition's balance.
double SpreadFraction(const fp::Plan& plan) {
  double slowest_s = 0.0, fastest_s = 0.0;
  bool first = true;
  for (const fp::DronePlan& d : plan.drones) {
    if (d.time_s <= 0.0) continue;
    slowest_s = first ? d.time_s : std::max(slowest_s, d.time_s);
    fastest_s = first ? d.time_s : std::min(fastest_s, d.time_s);
    first = false;
  }
  return slowest_s > 0.0 ? (slowest_s - fastest_s) / slowest_s : 0.0;
}

// The drone whose time is the makespan.
fp::DronePlan Slowest(const fp::Plan& plan) {
  fp::DronePlan slowest;
  for (const fp::DronePlan& d : plan.drones) {
    if (d.time_s > slowest.time_s) slowest = d;
  }
  return slowest;
}

void PrintRow(const Row& r) {
  const fp::Plan& p = r.plan;
  const fp::DronePlan slowest = Slowest(p);
  std::string missed;
  for (const std::string& m : r.missed) missed += (missed.empty() ? "" : ",") + m;
  std::cout << std::left << std::setw(14) << r.scenario << std::right << std::fixed
            << std::setprecision(2) << std::setw(9) << r.area_km2 << std::setw(11) << r.planner
            << std::setw(7) << r.drones << std::setw(11) << 100.0 * p.coverage << std::setw(12)
            << std::setprecision(0) << p.makespan_s << std::setw(9) << std::setprecision(3)
            << (p.lower_bound_s > 0.0 ? p.makespan_s / p.lower_bound_s : 0.0) << std::setw(8)
            << r.target << std::setw(11) << std::setprecision(1) << p.nofly_violation_m
            << std::setw(11) << std::setprecision(3) << p.planning_seconds << std::setprecision(0)
            << std::setw(9) << p.lower_bound_s << std::setw(9) << slowest.sweep_s << std::setw(8)
            << slowest.turn_s << std::setw(10) << slowest.transit_s << std::setw(9)
            << std::setprecision(2) << 100.0 * SpreadFraction(p) << "  "
            << (missed.empty() ? "-" : missed) << std::endl;
}

nlohmann::ordered_json ToJson(const Row& r) {
  const fp::DronePlan slowest = Slowest(r.plan);
  return {{"area", r.scenario},
          {"area_km2", r.area_km2},
          {"planner", r.planner},
          {"drones", r.drones},
          {"coverage", r.plan.coverage},
          {"makespan_s", r.plan.makespan_s},
          {"lower_bound_s", r.plan.lower_bound_s},
          {"ratio", r.plan.makespan_s / r.plan.lower_bound_s},
          {"nofly_violation_m", r.plan.nofly_violation_m},
          {"planning_seconds", r.plan.planning_seconds},
          {"slowest_sweep_s", slowest.sweep_s},
          {"slowest_turn_s", slowest.turn_s},
          {"slowest_transit_s", slowest.transit_s},
          {"spread", SpreadFraction(r.plan)},
          {"missed", r.missed}};
}

bool Selected(const Options& o, const std::string& name) {
  if (o.only.empty()) return true;
  for (const std::string& n : o.only) {
    if (n == name) return true;
  }
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  const std::optional<Options> options = ParseOptions(argc, argv);
  if (!options) return 2;
  if (!options->json) PrintHeader();
  bool all_met = true;
  for (const Scenario& s : kScenarios) {
    if (!Selected(*options, s.name)) continue;
    const std::string dir = options->areas_dir + "/";
    fp::SearchArea area;
    try {
      area = fp::LoadSearchArea(
          dir + s.area_file,
          s.no_fly_file ? std::optional<std::filesystem::path>(dir + s.no_fly_file) : std::nullopt);
    } catch (const std::exception& e) {
      std::cerr << "plan_bench: " << e.what() << "\n";
      return 2;
    }
    for (const std::string& planner : options->planners) {
      for (const int drones : options->drones) {
        const Row row = Measure(s, area, planner, drones);
        for (const std::string& missed : row.missed) {
          if (missed != "ratio" || options->check_ratio) all_met = false;
        }
        if (options->json) {
          std::cout << ToJson(row).dump() << std::endl;
        } else {
          PrintRow(row);
        }
      }
    }
  }
  return options->check && !all_met ? 1 : 0;
}
