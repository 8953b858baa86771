// large_area_bench: the planner on real forest boundaries (every *.geojson of a
// folder, e.g. scenarios/areas/osm or ../shared/areas) with 1 to 4 launch sites,
// fleets of 5 to 50 drones and endurances of 20 to 60 min: coverage, makespan
// against the lower bound (and what the bound rests on), sorties, planning time.
// Sites are spread deterministically: the area's bounding box is cut into k equal
// slices along its longer side and each slice's site is the centroid of the area
// inside it (or that part's vertex nearest to the centroid when it falls outside),
// a stand-in for the road-side points an operation would pick.
//
//   large_area_bench [--areas DIR] [--only NAME,...] [--drones 5,20,50]
//                    [--sites 1,2,4] [--endurance 1200,2400,3600] [--json]
//                    [--check-coverage]
// --check-coverage exits 1 when a plan covers < 99.5 %, enters a no-fly zone or
// a reachable area is refused.
#include <algorithm>
#include <boost/geometry.hpp>
#include <cmath>
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
namespace bg = boost::geometry;

constexpr double kMinCoverage = 0.995;

struct Options {
  std::string areas_dir = "scenarios/areas/osm";
  std::vector<std::string> only;
  std::vector<int> drones{5, 20, 50};
  std::vector<int> sites{1, 2, 4};
  std::vector<double> endurance_s{1'200, 2'400, 3'600};
  bool json = false;
  bool check = false;
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
    } else if (flag == "--check-coverage") {
      o.check = true;
    } else if (i + 1 < argc && flag == "--areas") {
      o.areas_dir = argv[++i];
    } else if (i + 1 < argc && flag == "--only") {
      o.only = Split(argv[++i]);
    } else if (i + 1 < argc && flag == "--drones") {
      o.drones.clear();
      for (const std::string& n : Split(argv[++i])) o.drones.push_back(std::atoi(n.c_str()));
    } else if (i + 1 < argc && flag == "--sites") {
      o.sites.clear();
      for (const std::string& n : Split(argv[++i])) o.sites.push_back(std::atoi(n.c_str()));
    } else if (i + 1 < argc && flag == "--endurance") {
      o.endurance_s.clear();
      for (const std::string& n : Split(argv[++i])) o.endurance_s.push_back(std::atof(n.c_str()));
    } else {
      std::cerr << "large_area_bench: unknown or incomplete option '" << flag << "'\n";
      return std::nullopt;
    }
  }
  return o;
}

// k sites over the area (see the file comment).
std::vector<fp::Point> SpreadSites(const fp::SearchArea& area, int k) {
  fp::Box box;
  bg::envelope(area.area, box);
  const double dx = box.max_corner().x() - box.min_corner().x();
  const double dy = box.max_corner().y() - box.min_corner().y();
  std::vector<fp::Point> sites;
  for (int i = 0; i < k; ++i) {
    fp::Box slice = box;
    if (dx >= dy) {
      slice.min_corner().x(box.min_corner().x() + dx * i / k);
      slice.max_corner().x(box.min_corner().x() + dx * (i + 1) / k);
    } else {
      slice.min_corner().y(box.min_corner().y() + dy * i / k);
      slice.max_corner().y(box.min_corner().y() + dy * (i + 1) / k);
    }
    fp::SearchArea part;
    part.frame = area.frame;
    bg::intersection(area.area, slice, part.area);
    if (bg::area(part.area) <= 0.0) continue;
    sites.push_back(fp::DefaultLaunchPoint(part));
  }
  return sites;
}

struct Row {
  std::string area;
  double km2 = 0.0;
  int drones = 0;
  int sites = 0;
  double endurance_s = 0.0;
  std::optional<fp::Plan> plan;
  std::string refused;
};

// Connected pieces per sortie's region: the mean and the largest.
std::pair<double, std::size_t> SortiePieces(const fp::Plan& plan) {
  std::size_t sorties = 0, pieces = 0, most = 0;
  for (const fp::DronePlan& d : plan.drones) {
    for (const fp::MultiPolygon& region : d.sortie_regions) {
      ++sorties;
      pieces += region.size();
      most = std::max(most, region.size());
    }
  }
  return {sorties ? static_cast<double>(pieces) / static_cast<double>(sorties) : 0.0, most};
}

int MostSorties(const fp::Plan& plan) {
  int most = 0;
  for (const fp::DronePlan& d : plan.drones) most = std::max(most, d.sorties);
  return most;
}

void PrintHeader() {
  std::cout << std::left << std::setw(18) << "area" << std::right << std::setw(8) << "km2"
            << std::setw(7) << "drones" << std::setw(6) << "sites" << std::setw(10) << "endur_s"
            << std::setw(8) << "sorties" << std::setw(10) << "coverage%" << std::setw(12)
            << "makespan_m" << std::setw(9) << "bound_m" << std::setw(8) << "ratio" << std::setw(9)
            << "plan_s"
            << "  bound from\n";
}

void PrintRow(const Row& r) {
  std::cout << std::left << std::setw(18) << r.area << std::right << std::fixed
            << std::setprecision(1) << std::setw(8) << r.km2 << std::setw(7) << r.drones
            << std::setw(6) << r.sites << std::setw(10) << std::setprecision(0) << r.endurance_s;
  if (!r.plan) {
    std::cout << "  refused: " << r.refused << std::endl;
    return;
  }
  const fp::Plan& p = *r.plan;
  std::cout << std::setw(8) << MostSorties(p) << std::setw(10) << std::setprecision(2)
            << 100.0 * p.coverage << std::setw(12) << std::setprecision(1) << p.makespan_s / 60.0
            << std::setw(9) << p.lower_bound_s / 60.0 << std::setw(8) << std::setprecision(3)
            << p.makespan_s / p.lower_bound_s << std::setw(9) << std::setprecision(2)
            << p.planning_seconds << std::setw(8) << SortiePieces(p).first << " max "
            << SortiePieces(p).second << "  " << p.lower_bound_basis.substr(0, 30) << std::endl;
}

nlohmann::ordered_json ToJson(const Row& r) {
  nlohmann::ordered_json j{{"area", r.area},
                           {"area_km2", r.km2},
                           {"drones", r.drones},
                           {"sites", r.sites},
                           {"endurance_s", r.endurance_s}};
  if (!r.plan) {
    j["refused"] = r.refused;
    return j;
  }
  j["sorties"] = MostSorties(*r.plan);
  j["coverage"] = r.plan->coverage;
  j["makespan_s"] = r.plan->makespan_s;
  j["lower_bound_s"] = r.plan->lower_bound_s;
  j["ratio"] = r.plan->makespan_s / r.plan->lower_bound_s;
  j["lower_bound_basis"] = r.plan->lower_bound_basis;
  j["nofly_violation_m"] = r.plan->nofly_violation_m;
  j["planning_seconds"] = r.plan->planning_seconds;
  j["pieces_per_sortie_mean"] = SortiePieces(*r.plan).first;
  j["pieces_per_sortie_max"] = SortiePieces(*r.plan).second;
  return j;
}

}  // namespace

int main(int argc, char** argv) {
  const std::optional<Options> options = ParseOptions(argc, argv);
  if (!options) return 2;
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(options->areas_dir)) {
    if (entry.path().extension() == ".geojson") files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  if (!options->json) PrintHeader();
  bool all_met = true;
  for (const std::filesystem::path& file : files) {
    const std::string name = file.stem().string();
    if (!options->only.empty() &&
        std::find(options->only.begin(), options->only.end(), name) == options->only.end()) {
      continue;
    }
    const fp::SearchArea area = fp::LoadSearchArea(file);
    double km2 = 0.0;
    for (const fp::Polygon& p : area.area) km2 += bg::area(p);
    km2 /= fireswarm::common::kSquareMetresPerKm2;
    for (const int sites : options->sites) {
      for (const int drones : options->drones) {
        for (const double endurance_s : options->endurance_s) {
          Row row{name, km2, drones, sites, endurance_s, std::nullopt, {}};
          fp::FleetSpec fleet;
          for (int id = 1; id <= drones; ++id) fleet.receiver_ids.push_back(id);
          fleet.launch_points = SpreadSites(area, sites);
          fleet.camera = &fireswarm::common::CameraModelByName("seed");
          fleet.altitude_m = 100.0;
          fleet.speed_mps = 12.0;
          fleet.endurance_s = endurance_s;
          try {
            row.plan = fp::PlanSearch(area, fleet);
            if (row.plan->coverage < kMinCoverage || row.plan->nofly_violation_m > 0.0) {
              all_met = false;
            }
          } catch (const std::exception& e) {
            row.refused = e.what();
            // Refused only when out of reach: anything else is a miss.
            if (row.refused.find("from the nearest launch site") == std::string::npos) {
              all_met = false;
            }
          }
          if (options->json) {
            std::cout << ToJson(row).dump() << std::endl;
          } else {
            PrintRow(row);
          }
        }
      }
    }
  }
  return options->check && !all_met ? 1 : 0;
}
