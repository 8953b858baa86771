// A drone's flight: its sortie units flown out of its launch site and back, each
// leg around the no-fly zones, with landings between the sorties.
#pragma once

#include <vector>

#include "fireswarm/planner/geometry.hpp"
#include "fireswarm/planner/transit.hpp"
#include "sortie_blocks.hpp"

namespace fireswarm::planner {

/// One point of a flight, local frame.
struct FlightPoint {
  Point point;
  bool is_return = false;    ///< the landing at the site that ends a sortie (not the last)
  bool starts_lane = false;  ///< the leg that begins here flies a search lane
};

struct Flight {
  std::vector<FlightPoint> points;  ///< starts and ends at the launch site
  int sorties = 0;
  double length_m = 0.0;
  double time_s = 0.0;     ///< flight time: distance / speed plus lane turns
  double sweep_s = 0.0;    ///< of time_s: on lanes
  double turn_s = 0.0;     ///< turning between passes
  double transit_s = 0.0;  ///< everything else (hops, links, out and back)
  double longest_sortie_s = 0.0;
};

/// Flies `units` (oriented for `site`) one sortie each, in order, from `site`:
/// transit out, the passes (a pass that crosses a no-fly zone is flown in pieces,
/// joined around the zone), the hops between passes and the links between blocks,
/// transit home. Every transit is planned with `transit`.
Flight FlySorties(const std::vector<SortieUnit>& units, Point site, double speed_mps,
                  double turn_cost_s, const TransitPlanner& transit);

/// Flies `paths` (one per sortie, e.g. OMPL coverage paths) the same way, a turn
/// charged wherever the heading changes by more than `turn_angle_rad`.
Flight FlyPaths(const std::vector<Path>& paths, Point site, double speed_mps, double turn_cost_s,
                double turn_angle_rad, const TransitPlanner& transit);

}  // namespace fireswarm::planner
