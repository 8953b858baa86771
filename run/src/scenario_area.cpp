// The scenario's `area` and `no_fly`: GeoJSON files (resolved against the scenario's
// directory) or inline [lon, lat] rings turned into GeoJSON text, all read by the
// planner's one GeoJSON reader (planner::ParseSearchArea).
#include <array>
#include <boost/geometry/algorithms/covered_by.hpp>
#include <boost/geometry/algorithms/within.hpp>
#include <charconv>
#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include "fireswarm/planner/area_io.hpp"
#include "scenario_parts.hpp"

namespace fireswarm::run::internal {
namespace {

namespace bg = boost::geometry;
namespace fs = std::filesystem;

// A ring needs 3 distinct corners; GeoJSON then repeats the first as the last.
constexpr std::size_t kMinRingCorners = 3;

// One GeoJSON document to read, where it came from, and the scenario key naming it.
struct AreaSource {
  planner::GeoJsonText geojson;
  std::optional<fs::path> file;  // set when read from a file
  Field field;                   // the scenario key (area.geojson, no_fly, ...)
  std::vector<Field> polygons;   // inline: each polygon, named by its key path in the GeoJSON
};

// Shortest text that reads back as the same double.
std::string JsonNumber(double value) {
  std::array<char, 32> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  return std::string(buffer.data(), result.ptr);
}

// `[[lon, lat], ...]` checked position by position and closed when open.
std::string RingJson(const Field& ring) {
  const std::vector<Field> positions = ring.Elements();
  std::vector<std::pair<double, double>> lon_lat;
  for (const Field& position : positions) {
    const std::vector<Field> pair = position.Elements();
    if (pair.size() != 2) {
      position.Fail("must be a [longitude, latitude] pair, got " + std::to_string(pair.size()) +
                    " values");
    }
    const double lon = pair[0].Number();
    const double lat = pair[1].Number();
    if (!kLongitudeRange.Contains(lon)) {
      position.Fail("longitude must be " + kLongitudeRange.Describe() + ", got " +
                    pair[0].node().Scalar() + " (positions are [lon, lat])");
    }
    if (!kLatitudeRange.Contains(lat)) {
      position.Fail("latitude must be " + kLatitudeRange.Describe() + ", got " +
                    pair[1].node().Scalar() + " (positions are [lon, lat])");
    }
    lon_lat.emplace_back(lon, lat);
  }
  const bool closed = lon_lat.size() > 1 && lon_lat.front() == lon_lat.back();
  if (lon_lat.size() - (closed ? 1 : 0) < kMinRingCorners) {
    ring.Fail("a polygon needs at least 3 corners [lon, lat]");
  }
  if (!closed) lon_lat.push_back(lon_lat.front());
  std::string json = "[";
  for (std::size_t i = 0; i < lon_lat.size(); ++i) {
    if (i > 0) json += ",";
    json += "[" + JsonNumber(lon_lat[i].first) + "," + JsonNumber(lon_lat[i].second) + "]";
  }
  return json + "]";
}

// A GeoJSON Feature holding one inline polygon; `name` labels the planner's errors.
std::string PolygonFeature(const Field& ring, const std::string& name) {
  return R"({"type":"Feature","properties":{"name":")" + name +
         R"("},"geometry":{"type":"Polygon","coordinates":[)" + RingJson(ring) + "]}}";
}

AreaSource ReadGeoJsonFile(const Field& path_field, const fs::path& base_dir) {
  const fs::path given(path_field.Text());
  const fs::path resolved = (given.is_absolute() ? given : base_dir / given).lexically_normal();
  // The overload without an error code throws for a path the system cannot look up
  // (a name too long, a loop of links): that is this key's error too.
  std::error_code error;
  if (!fs::is_regular_file(resolved, error)) {
    const bool lookup_failed = error && error != std::errc::no_such_file_or_directory &&
                               error != std::errc::not_a_directory;
    path_field.Fail((lookup_failed ? "cannot look up the GeoJSON file (" + error.message() + "): "
                                   : std::string("GeoJSON file not found: ")) +
                    resolved.string() +
                    (given.is_absolute() ? "" : " (relative to the scenario file's directory)"));
  }
  std::ifstream in(resolved, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in || in.bad()) path_field.Fail("cannot read the GeoJSON file " + resolved.string());
  return {{text.str(), resolved.string()}, resolved, path_field, {}};
}

AreaSource ReadAreaSource(const Field& field, const fs::path& base_dir) {
  const Mapping area(field, {"geojson", "polygon"});
  const std::optional<Field> geojson = area.Find("geojson");
  const std::optional<Field> polygon = area.Find("polygon");
  if (geojson && polygon) field.Fail("give either geojson or polygon, not both");
  if (geojson) return ReadGeoJsonFile(*geojson, base_dir);
  if (!polygon) field.Fail("missing geojson (a file) or polygon ([[lon, lat], ...])");
  return {{PolygonFeature(*polygon, polygon->path()), polygon->path()},
          std::nullopt,
          *polygon,
          {*polygon}};
}

// `no_fly`: a GeoJSON path, or a list of inline polygons; nullopt for an empty list.
std::optional<AreaSource> ReadNoFlySource(const Field& field, const fs::path& base_dir) {
  if (field.IsScalar()) return ReadGeoJsonFile(field, base_dir);
  if (!field.IsSequence()) {
    field.Fail("must be a GeoJSON file name or a list of polygons [[lon, lat], ...]");
  }
  const std::vector<Field> polygons = field.Elements();
  if (polygons.empty()) return std::nullopt;
  std::string json = R"({"type":"FeatureCollection","features":[)";
  for (std::size_t i = 0; i < polygons.size(); ++i) {
    if (i > 0) json += ",";
    json += PolygonFeature(polygons[i], polygons[i].path());
  }
  json += "]}";
  return AreaSource{{json, field.path()}, std::nullopt, field, polygons};
}

// The planner's message is "<source>: <feature label>: <problem>". For a file it is
// kept whole (it names the file and the feature); for inline polygons the source is
// the key and each feature's label holds the polygon's key path (`feature 2
// ("no_fly[2]")`), so the error names that polygon's key and place instead.
[[noreturn]] void FailFromPlanner(const AreaSource& source, std::string message) {
  const std::string prefix = source.geojson.source + ": ";
  if (source.file || !message.starts_with(prefix)) source.field.Fail(message);
  message.erase(0, prefix.size());
  for (const Field& polygon : source.polygons) {
    const std::string label = "(\"" + polygon.path() + "\"): ";
    const std::size_t at = message.find(label);
    if (at != std::string::npos) polygon.Fail(message.substr(at + label.size()));
  }
  source.field.Fail(message);
}

}  // namespace

common::LatLon ReadLatLon(const Mapping& mapping) {
  const double lat = mapping.Required("lat").Number(kLatitudeRange);
  const double lon = mapping.Required("lon").Number(kLongitudeRange);
  return {lat, lon};
}

void ReadArea(const Mapping& root, const fs::path& base_dir, Scenario& scenario) {
  const AreaSource area = ReadAreaSource(root.Required("area"), base_dir);
  std::optional<AreaSource> no_fly;
  if (const std::optional<Field> field = root.Find("no_fly")) {
    no_fly = ReadNoFlySource(*field, base_dir);
  }
  try {
    scenario.area = planner::ParseSearchArea(
        area.geojson, no_fly ? std::optional(no_fly->geojson) : std::nullopt);
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    if (no_fly && message.starts_with(no_fly->geojson.source + ": ")) {
      FailFromPlanner(*no_fly, message);
    }
    FailFromPlanner(area, message);
  }
  scenario.area_geojson = area.file;
  if (no_fly) scenario.no_fly_geojson = no_fly->file;
}

void CheckNearArea(const Field& field, const planner::SearchArea& area, common::LatLon position) {
  const common::EastNorth local = area.frame.ToLocal(position);
  const double distance_m = std::hypot(local.east_m, local.north_m);
  if (distance_m > planner::kMaxDistanceFromOriginM) {
    field.Fail("lies " + std::to_string(std::lround(distance_m / 1e3)) +
               " km from the area's centre, beyond the sane " +
               std::to_string(std::lround(planner::kMaxDistanceFromOriginM / 1e3)) + " km");
  }
}

bool InSearchArea(const planner::SearchArea& area, common::LatLon position) {
  const common::EastNorth local = area.frame.ToLocal(position);
  return bg::covered_by(planner::Point(local.east_m, local.north_m), area.area);
}

bool InNoFly(const planner::SearchArea& area, common::LatLon position) {
  const common::EastNorth local = area.frame.ToLocal(position);
  return bg::within(planner::Point(local.east_m, local.north_m), area.no_fly);
}

}  // namespace fireswarm::run::internal
