// A lower bound on any plan's makespan, from the area, the sites and the fleet
// alone (not from the plan): what the plan is measured against.
#pragma once

#include <string>
#include <vector>

#include "fireswarm/planner/geometry.hpp"

namespace fireswarm::planner {

struct BoundInputs {
  std::size_t drones = 1;
  double sweep_width_m = 1.0;      ///< area seen per metre flown
  double footprint_width_m = 1.0;  ///< a drone sees this far across its track
  double speed_mps = 1.0;
  double endurance_s = 0.0;  ///< level flight per sortie (the climb and descent excluded)
  double swap_s = 0.0;       ///< on the ground between sorties
  double vertical_s = 0.0;   ///< every sortie's climb to altitude and descent to land
};

struct LowerBound {
  double seconds = 0.0;
  std::string basis;  ///< which term gave it, with its numbers, in words
};

/// The farthest point of `region` from its nearest site (on a raster of about
/// 250,000 cells) and that distance.
struct FarthestPoint {
  Point point;
  double distance_m = 0.0;
};
FarthestPoint FarthestFromSites(const MultiPolygon& region, const std::vector<Point>& sites);

/// The largest of three bounds (W: the region's area / (sweep width * speed),
/// the fleet's sweep seconds; F(r): the same for the part farther than r from the
/// nearest site; a drone sees that part only from farther than r' = r - footprint /
/// 2, so a sortie that sees any of it flies >= 2 r' / speed out and back and
/// sweeps <= e(r) = endurance - 2 r' / speed in all):
///  * busiest drone: some drone sweeps >= W / N, in >= ceil(W / (N endurance))
///    sorties: W / N + (sorties - 1) * swap;
///  * busiest far drone, for every r: some drone sweeps >= F(r) / N, in k >=
///    ceil(F(r) / (N e(r))) sorties: F(r) / N + k * 2 r' / speed + (k - 1) * swap;
///  * fleet, for every r: n(rho) = ceil(F(rho) / e(rho)) sorties must reach beyond
///    rho'; the time all sorties spend within r' is >= the integral over rho' in
///    [0, r'] of 2 n(rho) / speed (layer by layer, out and back), and the time
///    beyond r' >= F(r); their sum (at least W) is flown in >= max(n, flight /
///    endurance) sorties, of which all but N need a swap: that total / N.
///    (Sweep and transit are not added: a drone flying out sweeps on its way.)
/// Precondition: every point is within reach (2 r'max / speed < endurance).
LowerBound MakespanLowerBound(const MultiPolygon& region, const std::vector<Point>& sites,
                              const BoundInputs& in);

}  // namespace fireswarm::planner
