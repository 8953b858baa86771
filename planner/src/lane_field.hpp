// The lanes of one sweep direction over the whole region: every lane line one
// spacing apart, with the stretches of it a drone must fly so that its footprint
// sees the region's band around the line. The large-area planner cuts this field
// into sortie-sized blocks (sortie_blocks.hpp).
#pragma once

#include <vector>

#include "fireswarm/planner/geometry.hpp"
#include "lanes.hpp"

namespace fireswarm::planner {

/// An x interval of a lane, lane frame metres.
struct Span {
  double lo_m = 0.0;
  double hi_m = 0.0;
};

/// `spans` sorted and united where they overlap or lie less than `gap_m` apart.
std::vector<Span> MergedSpans(std::vector<Span> spans, double gap_m);

/// One lane line and what of it must be flown.
struct LaneRow {
  double y_m = 0.0;         ///< the line, lane frame
  std::vector<Span> spans;  ///< sorted, disjoint
};

struct LaneField {
  LaneFrame frame;
  MultiPolygon region_lane;   ///< the region it covers, lane frame
  double spacing_m = 0.0;     ///< between neighbouring rows, <= the sweep width
  std::vector<LaneRow> rows;  ///< from the region's bottom (lane frame y) up
};

/// Lanes heading `direction_rad` (counter-clockwise from east) over `region`
/// (local frame): n = ceil(height / sweep_width_m) rows spaced height / n, the
/// first and last half a spacing inside the region's bottom and top. A row's spans
/// are the projection onto its line of the region's band within half a spacing of
/// it (the band's x extent, piece by piece), so flying a span's whole length with a
/// footprint wider than the spacing sees every point of the band over it. Spans
/// closer than `merge_gap_m` are joined (a short gap costs less to fly over than
/// to leave and re-enter).
LaneField BuildLaneField(const MultiPolygon& region, double direction_rad, double sweep_width_m,
                         double merge_gap_m);

}  // namespace fireswarm::planner
