// The coverage figure: how much of the region the camera footprints see.
#pragma once

#include <vector>

#include "fireswarm/planner/geometry.hpp"

namespace fireswarm::planner {

/// Fraction (0..1) of `region` seen from `paths`: the region is rasterised into
/// square cells of `cell_m` (a cell belongs to it when its centre does) and a
/// cell counts as seen when its centre lies within `radius_m` of a path segment,
/// i.e. the footprint is taken as a disc of the across-track half width swept
/// along the path (the camera is on all the time, transit included). Returns 1 for
/// an empty region. Precondition: cell_m > 0, radius_m >= 0.
double CoverageFraction(const MultiPolygon& region, const std::vector<Path>& paths, double radius_m,
                        double cell_m);

/// The raster cell used for Plan::coverage: about 4 million cells over the region,
/// at least 1 m and at most a tenth of the sweep width.
double CoverageCellM(double region_area_m2, double sweep_width_m);

}  // namespace fireswarm::planner
