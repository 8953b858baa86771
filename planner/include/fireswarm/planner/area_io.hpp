// Search areas from GeoJSON (RFC 7946): the area to cover and the no-fly zones,
// projected to one local frame (common::LocalFrame) and checked.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "fireswarm/planner/plan.hpp"

namespace fireswarm::planner {

/// The largest area a plan may cover; beyond it the input is more likely a mistake
/// (degrees read as metres, a country instead of a forest) than a search area.
inline constexpr double kMaxSearchAreaKm2 = 10'000.0;
/// The farthest any position (area or no-fly) may lie from the frame's origin.
inline constexpr double kMaxDistanceFromOriginM = 200'000.0;
/// Less area than this left after cutting out the no-fly zones is "no area left".
inline constexpr double kMinSearchAreaM2 = 100.0;

/// GeoJSON text and the name its errors carry (normally the file name).
struct GeoJsonText {
  std::string text;
  std::string source;
};

/// Reads the area to search and, optionally, no-fly zones from a separate document.
///
/// Each document is a FeatureCollection, a Feature or a bare Polygon / MultiPolygon;
/// polygons may have holes. In the area document a feature whose properties hold
/// `"no_fly": true` is a no-fly zone too. Area features are united; the no-fly
/// zones (united) are cut out of the area and kept whole in `SearchArea::no_fly`,
/// also where they reach beyond the area (transit must avoid them there as well).
///
/// The local frame's origin is the centre of the area's latitude/longitude bounding
/// box (areas crossing the antimeridian are rejected as beyond a sane size).
///
/// Throws std::invalid_argument with "<source>: feature <i> ("<name>"): <problem>"
/// for malformed JSON, unsupported geometry, latitude/longitude out of range, rings
/// not closed or with too few positions, self-intersecting or otherwise invalid
/// polygons, an area larger than kMaxSearchAreaKm2 or farther than
/// kMaxDistanceFromOriginM from the origin, and no area left after the no-fly zones.
SearchArea ParseSearchArea(const GeoJsonText& area,
                           const std::optional<GeoJsonText>& no_fly = std::nullopt);

/// ParseSearchArea on files; the error source is each path as given. Throws
/// std::invalid_argument as ParseSearchArea, and also when a file cannot be read.
SearchArea LoadSearchArea(const std::filesystem::path& area_path,
                          const std::optional<std::filesystem::path>& no_fly_path = std::nullopt);

/// Launch sites as a file gives them: each position and, when the file says,
/// how many drones fly from it.
struct LaunchSites {
  std::vector<common::LatLon> positions;
  std::vector<int> drones;  ///< empty, or one count per site
};

/// Reads launch sites from GeoJSON: a FeatureCollection of Point features (or one
/// Point), each with an optional integer property `drones` (0..254), given for
/// every site or for none. Throws std::invalid_argument naming `source`, the
/// feature and the problem.
LaunchSites ParseLaunchSites(const GeoJsonText& sites);
LaunchSites LoadLaunchSites(const std::filesystem::path& path);

/// Where the fleet launches when nobody says: the area's centroid when it lies in
/// the area, otherwise the area corner nearest to it (the centroid of a U, or of
/// a forest around a lake, can fall outside). Local metres.
Point DefaultLaunchPoint(const SearchArea& area);

}  // namespace fireswarm::planner
