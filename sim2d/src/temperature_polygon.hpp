// Area of overlap between a convex polygon and a convex quadrilateral: how much
// of a pixel's ground footprint a fire cell or a rock covers (private to sim2d).
#pragma once

#include <span>

#include "fireswarm/sim2d/temperature_field.hpp"

namespace fireswarm::sim2d {

/// Signed area (shoelace), m^2: positive for counter-clockwise vertices.
double SignedAreaM2(std::span<const Vec2> polygon);

/// Area, m^2, of the intersection of the convex polygon `subject` (<= 32
/// vertices) with the convex quad `ccw_quad` given counter-clockwise
/// (Sutherland-Hodgman clipping in fixed-size buffers: this runs per pixel near
/// hot things, where a general polygon library's allocations would dominate).
double OverlapAreaM2(std::span<const Vec2> subject, const GroundQuad& ccw_quad);

/// Area, m^2, of the intersection of the convex `quad` (either winding) with
/// the axis-aligned box [lo_m, hi_m] (a grid cell): clipping by four axis lines
/// is cheaper than by four general edges.
double QuadBoxOverlapAreaM2(const GroundQuad& quad, const Vec2& lo_m, const Vec2& hi_m);

/// The area of a quad that falls into one grid cell.
struct CellOverlap {
  int col = 0;
  int row = 0;
  double area_m2 = 0.0;
};

/// Cuts the convex `quad` along the grid lines of square cells of side `cell_m`
/// whose corner (0, 0) is at `origin_m` (cell (c, r) covers origin + cell_m *
/// [c, c+1) x [r, r+1)), writing one entry per cell the quad overlaps, in no
/// particular order, areas summing to the quad's. Cost: one split per grid line
/// crossed. Writes at most `max_out` entries and returns how many it wrote, or
/// -1 when the quad's bounding box spans more than `max_out` cells.
int SplitQuadIntoCells(const GroundQuad& quad, const Vec2& origin_m, double cell_m,
                       CellOverlap* out, int max_out);

}  // namespace fireswarm::sim2d
