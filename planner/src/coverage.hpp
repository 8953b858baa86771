// Coverage of one sortie's region by the OMPL-based variant (PlannerKind::kOmpl);
// the lawnmower's lanes are in lane_field.hpp and sortie_blocks.hpp.
#pragma once

#include "fireswarm/planner/geometry.hpp"
#include "fireswarm/planner/transit.hpp"

namespace fireswarm::planner {

/// The OMPL-based variant: viewpoints one footprint apart over `region`, toured
/// in a short order, legs that would cross a no-fly zone planned with OMPL.
/// Deterministic for a given seed.
Path CoverOmpl(const MultiPolygon& region, double sweep_width_m, Point start,
               const TransitPlanner& transit, unsigned seed);

}  // namespace fireswarm::planner
