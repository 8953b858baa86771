// Coverage of one drone's region: the path that sweeps a camera footprint of
// `sweep_width_m` over every part of it. Two variants, selected by PlannerKind.
#pragma once

#include <vector>

#include "fireswarm/planner/geometry.hpp"
#include "fireswarm/planner/transit.hpp"
#include "partition.hpp"

namespace fireswarm::planner {

/// How the lawnmower sizes and times its lanes.
struct SweepParams {
  double sweep_width_m = 0.0;      ///< lane spacing (at most)
  double footprint_width_m = 0.0;  ///< across-track footprint width, >= sweep_width_m
  double speed_mps = 1.0;
  double turn_cost_s = 0.0;  ///< charged at every lane end followed by more flight
};

/// The lawnmower's full result: one timed route over the whole `region` (holes
/// and no-fly zones already cut out), starting near `start`. The sweep direction
/// is chosen among the region's edge directions to minimise the estimated time
/// (lane lengths, turns and transit between cells); the region is decomposed into
/// boustrophedon cells along it (decomposition.hpp); each cell is swept in the
/// corner order that starts nearest to where the previous cell ended (greedy
/// nearest neighbour); lane-to-lane connections and cell-to-cell transits that
/// would enter a no-fly zone go around it with `transit`.
Route SweepRoute(const MultiPolygon& region, const SweepParams& params, Point start,
                 const TransitPlanner& transit);

/// The route SweepRoute would build along each candidate direction, best estimate
/// first; the caller picks by what it measures (PlanSearch: the fleet's makespan,
/// which the route's own estimate cannot see: transit to and from each share).
std::vector<Route> SweepRoutes(const MultiPolygon& region, const SweepParams& params, Point start,
                               const TransitPlanner& transit);

/// Boustrophedon lawnmower: decomposes `region` (holes and no-fly zones already
/// cut out) into cells, sweeps each along its best direction, orders the cells to
/// keep transit short, and joins them with `transit`. Starts near `start`. The
/// path of SweepRoute with a footprint of sweep_width_m / 0.9 (10 % overlap),
/// unit speed and no turn cost.
Path CoverLawnmower(const MultiPolygon& region, double sweep_width_m, Point start,
                    const TransitPlanner& transit);

/// The OMPL-based variant: viewpoints one footprint apart over `region`, toured
/// in a short order, legs that would cross a no-fly zone planned with OMPL.
/// Deterministic for a given seed.
Path CoverOmpl(const MultiPolygon& region, double sweep_width_m, Point start,
               const TransitPlanner& transit, unsigned seed);

}  // namespace fireswarm::planner
