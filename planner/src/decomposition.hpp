// Boustrophedon cell decomposition: splits a region with holes and concave
// boundaries into cells that every lane crosses in one piece.
#pragma once

#include <vector>

#include "fireswarm/planner/geometry.hpp"

namespace fireswarm::planner {

/// Cells of `region_lane`, given in the lane frame (lanes along x): each cell is
/// y-monotone (every horizontal line meets it in at most one interval) and has no
/// holes; together they tile the region without overlap. The region is cut at its
/// critical levels (ring vertices that are local extremes in y) into slab pieces,
/// and pieces that meet one-to-one across a level are merged back (Choset's
/// boustrophedon decomposition), so a convex region stays one cell.
std::vector<Polygon> DecomposeLaneFrame(const MultiPolygon& region_lane);

/// The same for a region in the local frame with lanes heading `direction_rad`
/// (counter-clockwise from east); the cells come back in the local frame.
std::vector<Polygon> Decompose(const MultiPolygon& region, double direction_rad);

}  // namespace fireswarm::planner
