// The map of a `fireswarm run`: one SVG picture, north up, of the search area and
// its no-fly zones, each drone's flown path, the true and the fused fires with the
// fusion's uncertainty, false tracks and collisions, with a title, a scale bar and
// a legend; what a person looks at first after a run.
#pragma once

#include <filesystem>
#include <string>

#include "fireswarm/run/report.hpp"
#include "fireswarm/run/scenario.hpp"

namespace fireswarm::run {

/// The fused fire's ellipse is drawn at this many standard deviations along each
/// principal axis of its covariance (2-sigma: about 86 % of a 2-D Gaussian).
inline constexpr double kFusedEllipseSigmas = 2.0;

/// The map as a standalone SVG document (UTF-8). Positions are projected with
/// `scenario.area.frame` (east right, north up) at one scale chosen so that the
/// area, the tracks and every marker fit about 960 x 720 px; the scale bar gives
/// metres. Drawn: the search area (its holes, e.g. lakes, left open), the no-fly
/// zones (red, hatched), the launch site, each vehicle's `track` in a colour of its
/// own (fixed per receiver ID, named in the legend) ending in a dot, each true fire
/// (red dot, labelled F1, F2, ... in report order; "not confirmed" when it has no
/// fused position), each fused position (black cross) with its covariance ellipse
/// at kFusedEllipseSigmas and a dotted line to its true fire, false tracks (magenta
/// triangles) and collisions (black X on yellow, labelled with time and vehicles).
/// The title names the scenario and gives fires confirmed n/N and coverage.
/// Positions that are not finite or lie beyond planner::kMaxDistanceFromOriginM of
/// the frame's origin are left out. Tracks are thinned to what shows at the map's
/// scale (under a pixel). Deterministic: the same inputs give the same bytes.
std::string SvgMap(const Report& report, const Scenario& scenario);

/// Writes SvgMap(report, scenario) to `path` atomically
/// (common::WriteFileAtomically). Throws std::runtime_error naming the path when
/// it cannot be written.
void WriteSvgMap(const Report& report, const Scenario& scenario, const std::filesystem::path& path);

}  // namespace fireswarm::run
