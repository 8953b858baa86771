// A drone's flight over its share: out from launch, the share, home; split into
// sorties with returns to launch when it does not fit the endurance.
#pragma once

#include <vector>

#include "fireswarm/planner/geometry.hpp"
#include "fireswarm/planner/transit.hpp"
#include "partition.hpp"

namespace fireswarm::planner {

/// One point of a flight, local frame.
struct FlightPoint {
  Point point;
  bool is_return = false;    ///< a return to launch between two sorties
  bool starts_lane = false;  ///< the leg that begins here flies a search lane
};

struct Flight {
  std::vector<FlightPoint> points;  ///< starts and ends at the launch point
  int sorties = 0;                  ///< 0 when the share is empty
  double length_m = 0.0;
  double time_s = 0.0;     ///< flight time: distance / speed plus lane turns
  double sweep_s = 0.0;    ///< of time_s: on lanes
  double turn_s = 0.0;     ///< turning at lane ends
  double transit_s = 0.0;  ///< everything else (connections, transits, returns)
};

/// Flies `share` of `route` from `launch`: transit to the share's start, the share,
/// transit home, every transit planned with `transit`. When a sortie would exceed
/// `endurance_s`, the drone flies home from the last route vertex (a lane end or a
/// cut) it can still return from and a new sortie resumes there. Throws
/// std::runtime_error naming endurance_s when even one leg of the route (a whole
/// lane) with the transits to and from it does not fit.
Flight FlyShare(const Route& route, const Share& share, Point launch, double endurance_s,
                const TransitPlanner& transit);

}  // namespace fireswarm::planner
