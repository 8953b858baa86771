#include "lower_bound.hpp"

#include <algorithm>
#include <boost/geometry.hpp>
#include <cmath>
#include <functional>
#include <limits>
#include <sstream>

#include "lanes.hpp"

namespace fireswarm::planner {
namespace bg = boost::geometry;

namespace {

constexpr double kBoundCells = 2.5e5;
constexpr double kRadialSteps = 4000.0;

double NearestM(Point p, const std::vector<Point>& sites) {
  double best = std::numeric_limits<double>::infinity();
  for (const Point& s : sites) best = std::min(best, bg::distance(p, s));
  return best;
}

// Calls visit(point) at the centre of every raster cell of the region.
template <typename Visit>
void ForEachCell(const MultiPolygon& region, double cell_m, Visit visit) {
  Box box;
  bg::envelope(region, box);
  for (double y = box.min_corner().y() + cell_m / 2; y < box.max_corner().y(); y += cell_m) {
    for (const Polygon& polygon : region) {
      for (const auto& [a, b] : LineIntervals(polygon, y)) {
        const double first = box.min_corner().x() +
                             cell_m * (std::ceil((a - box.min_corner().x()) / cell_m - 0.5) + 0.5);
        for (double x = first; x <= b; x += cell_m) visit(Point{x, y});
      }
    }
  }
}

double CellM(const MultiPolygon& region) {
  return std::max(std::sqrt(AreaM2(region) / kBoundCells), 0.1);
}

std::string Minutes(double seconds) {
  std::ostringstream out;
  out.setf(std::ios::fixed);
  out.precision(1);
  out << seconds / 60.0 << " min";
  return out.str();
}

std::string Km(double metres) {
  std::ostringstream out;
  out.setf(std::ios::fixed);
  out.precision(2);
  out << metres / 1000.0 << " km";
  return out.str();
}

}  // namespace

FarthestPoint FarthestFromSites(const MultiPolygon& region, const std::vector<Point>& sites) {
  FarthestPoint far;
  auto consider = [&](Point p) {
    const double d = NearestM(p, sites);
    if (d > far.distance_m) far = {p, d};
  };
  ForEachCell(region, CellM(region), consider);
  for (const Polygon& polygon : region) {
    for (const Point& p : polygon.outer()) consider(p);
  }
  return far;
}

LowerBound MakespanLowerBound(const MultiPolygon& region, const std::vector<Point>& sites,
                              const BoundInputs& in) {
  const double n = static_cast<double>(in.drones);
  const double rate_m2ps = in.sweep_width_m * in.speed_mps;
  const double area_m2 = AreaM2(region);
  const double work_s = area_m2 / rate_m2ps;
  LowerBound bound;
  {
    const double sorties = std::ceil(work_s / (n * in.endurance_s) - 1e-9);
    bound.seconds = work_s / n + sorties * in.vertical_s + std::max(0.0, sorties - 1.0) * in.swap_s;
    bound.basis = "busiest drone: the area's sweep " + Minutes(work_s) + " / " +
                  std::to_string(in.drones) + " drones in " + std::to_string(std::lround(sorties)) +
                  " sortie(s), each with its climb and descent, swaps between them";
  }
  std::vector<double> distances;
  ForEachCell(region, CellM(region), [&](Point p) { distances.push_back(NearestM(p, sites)); });
  std::sort(distances.begin(), distances.end(), std::greater<>());
  const double cell_work_s =
      area_m2 / static_cast<double>(std::max<std::size_t>(distances.size(), 1)) / rate_m2ps;
  // Busiest far drone, at every distance.
  for (std::size_t k = 0; k < distances.size(); ++k) {
    const double far_s = static_cast<double>(k + 1) * cell_work_s;
    const double trip_s =
        2.0 * std::max(0.0, distances[k] - in.footprint_width_m / 2.0) / in.speed_mps;
    const double room_s = in.endurance_s - trip_s;
    if (room_s <= 0.0) continue;  // out of reach: the caller refuses such areas
    const double sorties = std::ceil(far_s / (n * room_s) - 1e-9);
    const double busiest_s =
        far_s / n + sorties * (trip_s + in.vertical_s) + std::max(0.0, sorties - 1.0) * in.swap_s;
    if (busiest_s > bound.seconds) {
      bound.seconds = busiest_s;
      bound.basis = "busiest far drone: beyond " + Km(distances[k]) + " of the nearest site lies " +
                    Minutes(far_s) + " of sweep; 1/" + std::to_string(in.drones) + " of it in " +
                    std::to_string(std::lround(sorties)) + " sortie(s) of " + Minutes(trip_s) +
                    " transit each, swaps between them";
    }
  }
  // The fleet. n(r): sorties that must reach beyond r' (F(r) over what one can
  // see out there). Time spent within r' by all sorties >= the integral of
  // 2 n(rho + footprint / 2) / speed over rho in [0, r'] (layer by layer), and
  // time beyond r' >= F(r): their sum bounds the fleet's flight at every r.
  if (distances.empty()) return bound;
  const double half_m = in.footprint_width_m / 2.0;
  auto far_s = [&](double r) {  // F(r), seconds of sweep
    const auto beyond = std::upper_bound(distances.begin(), distances.end(), r, std::greater<>()) -
                        distances.begin();
    return static_cast<double>(beyond) * cell_work_s;
  };
  auto sorties_beyond = [&](double r) {
    const double room_s = in.endurance_s - 2.0 * std::max(0.0, r - half_m) / in.speed_mps;
    return room_s > 0.0 ? std::ceil(far_s(r) / room_s - 1e-9) : 0.0;
  };
  const double reach_m = distances.front();
  const double step_m = std::max(reach_m / kRadialSteps, 1e-3);
  double layers_s = 0.0, most_sorties = 0.0, flight_s = work_s, at_m = 0.0;
  for (double r = half_m; r <= reach_m + step_m; r += step_m) {
    const double here = sorties_beyond(r), next = sorties_beyond(r + step_m);
    most_sorties = std::max(most_sorties, here);
    const double total_s = far_s(r) + layers_s;
    if (total_s > flight_s) {
      flight_s = total_s;
      at_m = r;
    }
    layers_s += 2.0 * step_m / in.speed_mps * std::min(here, next);
  }
  const double sorties = std::max(most_sorties, std::ceil(flight_s / in.endurance_s - 1e-9));
  const double swaps = std::max(0.0, sorties - n);
  const double fleet_s = (flight_s + sorties * in.vertical_s + swaps * in.swap_s) / n;
  if (fleet_s > bound.seconds) {
    bound.seconds = fleet_s;
    bound.basis = "fleet: " + Minutes(flight_s) + " of flight (the sweep beyond " + Km(at_m) +
                  " of the nearest site, " + Minutes(far_s(at_m)) +
                  ", plus the sorties' way out to there and back, counted layer by layer) in >= " +
                  std::to_string(std::lround(sorties)) +
                  " sorties (each with its climb and descent), " +
                  std::to_string(std::lround(swaps)) + " swaps, over " + std::to_string(in.drones) +
                  " drones";
  }
  return bound;
}

}  // namespace fireswarm::planner
