// Reading RFC 7946 GeoJSON polygons: text -> WGS84 rings, every problem reported
// against the source (file name), the feature and the ring. No projection here:
// area_io.cpp projects what this returns through common::LocalFrame.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "fireswarm/common/local_frame.hpp"

namespace fireswarm::planner::geojson {

/// A ring as read: closed (first position == last), at least 4 positions.
using GeoRing = std::vector<common::LatLon>;

/// One polygon: the outer ring, then its holes.
struct GeoPolygon {
  std::vector<GeoRing> rings;
};

/// One feature's polygons and the label its errors carry, e.g.
/// `feature 2 ("north block")`, `feature 0 (id 17)` or `geometry` for a bare one.
struct GeoFeature {
  std::string label;
  std::vector<GeoPolygon> polygons;
  bool is_multi = false;  ///< a MultiPolygon: errors say "polygon k, ring r"
  bool no_fly = false;    ///< properties.no_fly is true: a no-fly zone, not area
};

/// Parses `text`: a FeatureCollection, a Feature, or a bare Polygon / MultiPolygon.
/// Positions are [lon, lat] or [lon, lat, altitude] (altitude ignored).
/// Throws std::invalid_argument "<source>: <label>: <problem>" on malformed JSON
/// (with line and column), an unsupported or missing geometry, a position that is
/// not two finite numbers, latitude or longitude out of range, a ring with fewer
/// than 4 positions or not closed, or no polygon at all.
std::vector<GeoFeature> ReadPolygonFeatures(std::string_view text, std::string_view source);

/// One Point feature of a launch-site file.
struct GeoPoint {
  std::string label;
  common::LatLon position;
  int drones = -1;  ///< properties.drones, -1 when absent
};

/// Parses `text`: a FeatureCollection of Point features, a Point Feature or a bare
/// Point; properties.drones, when present, an integer in 0..254. Throws
/// std::invalid_argument "<source>: <label>: <problem>" on malformed JSON, a
/// geometry that is not a Point, a bad position or count, or no point at all.
std::vector<GeoPoint> ReadPointFeatures(std::string_view text, std::string_view source);

/// The error label of feature `index`: `feature 2`, or with a description such as
/// `"north block"` (quoted name) or `id 17`: `feature 2 ("north block")`.
std::string FeatureLabel(std::size_t index, const std::string& description);

}  // namespace fireswarm::planner::geojson
