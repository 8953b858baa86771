// Coverage of one drone's region: the path that sweeps a camera footprint of
// `sweep_width_m` over every part of it. Two variants, selected by PlannerKind.
#pragma once

#include "fireswarm/planner/geometry.hpp"
#include "transit.hpp"

namespace fireswarm::planner {

/// Boustrophedon lawnmower: decomposes `region` (holes and no-fly zones already
/// cut out) into cells, sweeps each along its best direction, orders the cells to
/// keep transit short, and joins them with `transit`. Starts near `start`.
Path CoverLawnmower(const MultiPolygon& region, double sweep_width_m, Point start,
                    const TransitPlanner& transit);

/// The OMPL-based variant: viewpoints one footprint apart over `region`, toured
/// in a short order, legs that would cross a no-fly zone planned with OMPL.
/// Deterministic for a given seed.
Path CoverOmpl(const MultiPolygon& region, double sweep_width_m, Point start,
               const TransitPlanner& transit, unsigned seed);

}  // namespace fireswarm::planner
