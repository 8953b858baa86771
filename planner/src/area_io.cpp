#include "fireswarm/planner/area_io.hpp"

#include <algorithm>
#include <boost/geometry/algorithms/area.hpp>
#include <boost/geometry/algorithms/centroid.hpp>
#include <boost/geometry/algorithms/correct.hpp>
#include <boost/geometry/algorithms/covered_by.hpp>
#include <boost/geometry/algorithms/difference.hpp>
#include <boost/geometry/algorithms/intersects.hpp>
#include <boost/geometry/algorithms/is_valid.hpp>
#include <boost/geometry/algorithms/union.hpp>
#include <boost/geometry/strategies/cartesian/centroid_bashein_detmer.hpp>
#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "fireswarm/common/units.hpp"
#include "geojson_read.hpp"

namespace fireswarm::planner {
namespace {

namespace bg = boost::geometry;
using geojson::GeoFeature;
using geojson::GeoPolygon;

// Boost.Geometry's validity failures in the words of someone drawing a forest.
std::string DescribeFailure(bg::validity_failure_type failure) {
  switch (failure) {
    case bg::failure_few_points:
      return "has too few distinct corners";
    case bg::failure_wrong_topological_dimension:
      return "has no area (its corners are collinear)";
    case bg::failure_spikes:
      return "has a spike (an edge that doubles back on itself)";
    case bg::failure_duplicate_points:
      return "repeats a corner";
    case bg::failure_not_closed:
      return "has a ring that is not closed";
    case bg::failure_self_intersections:
      return "is self-intersecting (edges cross or touch)";
    case bg::failure_wrong_orientation:
      return "has a ring with the wrong orientation";
    case bg::failure_interior_rings_outside:
      return "has a hole outside its outer ring";
    case bg::failure_nested_interior_rings:
      return "has a hole inside another hole";
    case bg::failure_disconnected_interior:
      return "has holes that cut its interior in pieces";
    case bg::failure_intersecting_interiors:
      return "has polygons that overlap each other";
    case bg::failure_invalid_coordinate:
      return "has a coordinate that is not a finite number";
    default:
      return "is not a valid polygon";
  }
}

struct LabelledFeature {
  std::string source;
  GeoFeature feature;
};

common::LatLon BoundingBoxCentre(const std::vector<LabelledFeature>& features) {
  double min_lat = 90.0, max_lat = -90.0, min_lon = 180.0, max_lon = -180.0;
  for (const LabelledFeature& f : features) {
    for (const GeoPolygon& polygon : f.feature.polygons) {
      for (const common::LatLon& p : polygon.rings.front()) {
        min_lat = std::min(min_lat, p.lat_deg);
        max_lat = std::max(max_lat, p.lat_deg);
        min_lon = std::min(min_lon, p.lon_deg);
        max_lon = std::max(max_lon, p.lon_deg);
      }
    }
  }
  return {0.5 * (min_lat + max_lat), 0.5 * (min_lon + max_lon)};
}

// One feature's polygons in local metres, each checked with Boost.Geometry.
MultiPolygon Project(const LabelledFeature& f, const common::LocalFrame& frame) {
  const auto fail = [&f](const std::string& problem) {
    throw std::invalid_argument(f.source + ": " + f.feature.label + ": " + problem);
  };
  MultiPolygon result;
  for (std::size_t k = 0; k < f.feature.polygons.size(); ++k) {
    const std::string name = f.feature.is_multi ? "polygon " + std::to_string(k) : "polygon";
    Polygon polygon;
    const auto& rings = f.feature.polygons[k].rings;
    for (std::size_t r = 0; r < rings.size(); ++r) {
      auto& ring = r == 0 ? polygon.outer() : polygon.inners().emplace_back();
      for (const common::LatLon& p : rings[r]) {
        const common::EastNorth local = frame.ToLocal(p);
        if (std::hypot(local.east_m, local.north_m) > kMaxDistanceFromOriginM) {
          fail(name + " reaches " +
               std::to_string(std::lround(std::hypot(local.east_m, local.north_m) / 1e3)) +
               " km from the area's centre, beyond the sane " +
               std::to_string(std::lround(kMaxDistanceFromOriginM / 1e3)) + " km");
        }
        ring.emplace_back(local.east_m, local.north_m);
      }
    }
    // A ring whose edges cross is reported as such before is_valid(), which may
    // see a bow tie's net winding first and call it wrongly oriented.
    for (std::size_t r = 0; r < rings.size(); ++r) {
      const auto& ring = r == 0 ? polygon.outer() : polygon.inners()[r - 1];
      if (bg::intersects(ring)) {
        fail(name + (r == 0 ? "" : " hole " + std::to_string(r)) +
             " is self-intersecting (edges cross or touch)");
      }
    }
    // GeoJSON winds outer rings counter-clockwise, Boost clockwise: correct() flips them.
    bg::correct(polygon);
    bg::validity_failure_type failure = bg::no_failure;
    if (!bg::is_valid(polygon, failure)) fail(name + " " + DescribeFailure(failure));
    // A flat or sliver polygon (corners nearly on one line) passes is_valid but
    // leaves nothing to search.
    if (bg::area(polygon) < kMinSearchAreaM2) {
      fail(name + " has (near-)zero area: " + std::to_string(bg::area(polygon)) +
           " m2, less than " + std::to_string(std::lround(kMinSearchAreaM2)) + " m2");
    }
    const double area_km2 = bg::area(polygon) / common::kSquareMetresPerKm2;
    if (area_km2 > kMaxSearchAreaKm2) {
      fail(name + " covers " + std::to_string(std::lround(area_km2)) +
           " km2, more than the sane maximum of " + std::to_string(std::lround(kMaxSearchAreaKm2)) +
           " km2");
    }
    result.push_back(std::move(polygon));
  }
  return result;
}

MultiPolygon Union(const MultiPolygon& a, const MultiPolygon& b) {
  MultiPolygon out;
  bg::union_(a, b, out);
  return out;
}

std::string ReadFile(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::invalid_argument(path.string() + ": cannot open the file");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw std::invalid_argument(path.string() + ": cannot read the file");
  return text.str();
}

}  // namespace

SearchArea ParseSearchArea(const GeoJsonText& area, const std::optional<GeoJsonText>& no_fly) {
  std::vector<LabelledFeature> area_features;
  std::vector<LabelledFeature> no_fly_features;
  for (GeoFeature& f : geojson::ReadPolygonFeatures(area.text, area.source)) {
    (f.no_fly ? no_fly_features : area_features).push_back({area.source, std::move(f)});
  }
  if (no_fly) {
    for (GeoFeature& f : geojson::ReadPolygonFeatures(no_fly->text, no_fly->source)) {
      no_fly_features.push_back({no_fly->source, std::move(f)});
    }
  }
  if (area_features.empty()) {
    throw std::invalid_argument(area.source +
                                ": every feature is a no-fly zone; there is no area to search");
  }

  SearchArea result{common::LocalFrame(BoundingBoxCentre(area_features)), {}, {}};
  MultiPolygon whole_area;
  for (const LabelledFeature& f : area_features) {
    whole_area = Union(whole_area, Project(f, result.frame));
  }
  const double whole_km2 = bg::area(whole_area) / common::kSquareMetresPerKm2;
  if (whole_km2 > kMaxSearchAreaKm2) {
    throw std::invalid_argument(area.source + ": the features together cover " +
                                std::to_string(std::lround(whole_km2)) +
                                " km2, more than the sane maximum of " +
                                std::to_string(std::lround(kMaxSearchAreaKm2)) + " km2");
  }
  for (const LabelledFeature& f : no_fly_features) {
    result.no_fly = Union(result.no_fly, Project(f, result.frame));
  }
  bg::difference(whole_area, result.no_fly, result.area);
  if (bg::area(result.area) < kMinSearchAreaM2) {
    const std::string zones_source = no_fly ? no_fly->source : area.source;
    throw std::invalid_argument(
        area.source + ": no area left after subtracting the no-fly zones (" + zones_source + ")");
  }
  return result;
}

SearchArea LoadSearchArea(const std::filesystem::path& area_path,
                          const std::optional<std::filesystem::path>& no_fly_path) {
  std::optional<GeoJsonText> no_fly;
  if (no_fly_path) no_fly = GeoJsonText{ReadFile(*no_fly_path), no_fly_path->string()};
  return ParseSearchArea(GeoJsonText{ReadFile(area_path), area_path.string()}, no_fly);
}

LaunchSites ParseLaunchSites(const GeoJsonText& sites) {
  LaunchSites out;
  std::size_t counted = 0;
  const std::vector<geojson::GeoPoint> points =
      geojson::ReadPointFeatures(sites.text, sites.source);
  for (const geojson::GeoPoint& point : points) {
    out.positions.push_back(point.position);
    if (point.drones >= 0) ++counted;
  }
  if (counted != 0 && counted != points.size()) {
    throw std::invalid_argument(sites.source + ": " + std::to_string(counted) + " of " +
                                std::to_string(points.size()) +
                                " sites give \"drones\": give it for every site or for none");
  }
  if (counted != 0) {
    for (const geojson::GeoPoint& point : points) out.drones.push_back(point.drones);
  }
  return out;
}

LaunchSites LoadLaunchSites(const std::filesystem::path& path) {
  return ParseLaunchSites(GeoJsonText{ReadFile(path), path.string()});
}

Point DefaultLaunchPoint(const SearchArea& area) {
  Point centroid;
  bg::centroid(area.area, centroid);
  if (bg::covered_by(centroid, area.area)) return centroid;
  Point best = centroid;
  double best_m = std::numeric_limits<double>::infinity();
  for (const Polygon& polygon : area.area) {
    for (const Point& p : polygon.outer()) {
      const double d = std::hypot(p.x() - centroid.x(), p.y() - centroid.y());
      if (d < best_m) {
        best_m = d;
        best = p;
      }
    }
  }
  return best;
}

}  // namespace fireswarm::planner
