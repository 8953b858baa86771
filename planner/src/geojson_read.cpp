#include "geojson_read.hpp"

#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>

namespace fireswarm::planner::geojson {
namespace {

using Json = nlohmann::json;

// A closed ring needs three distinct corners plus the repeated first one (RFC 7946 3.1.6).
constexpr std::size_t kMinRingPositions = 4;

struct Context {
  std::string_view source;
  std::string label;
  [[noreturn]] void Fail(const std::string& problem) const {
    throw std::invalid_argument(std::string(source) + ": " + label + ": " + problem);
  }
};

std::string RingName(std::size_t polygon, std::size_t ring, bool is_multi) {
  std::string name = is_multi ? "polygon " + std::to_string(polygon) + ", ring " : "ring ";
  name += std::to_string(ring);
  return name;
}

common::LatLon ReadPosition(const Json& position, const Context& context,
                            const std::string& where) {
  if (!position.is_array() || position.size() < 2 || !position[0].is_number() ||
      !position[1].is_number()) {
    context.Fail(where + " is not a [longitude, latitude] pair of numbers");
  }
  const common::LatLon point{position[1].get<double>(), position[0].get<double>()};
  if (!std::isfinite(point.lat_deg) || std::abs(point.lat_deg) > 90.0) {
    context.Fail(where + " has latitude " + std::to_string(point.lat_deg) +
                 " out of range [-90, 90] (GeoJSON positions are [longitude, latitude])");
  }
  if (!std::isfinite(point.lon_deg) || std::abs(point.lon_deg) > 180.0) {
    context.Fail(where + " has longitude " + std::to_string(point.lon_deg) +
                 " out of range [-180, 180]");
  }
  return point;
}

GeoPolygon ReadPolygon(const Json& rings, const Context& context, std::size_t polygon_index,
                       bool is_multi) {
  const std::string polygon_name =
      is_multi ? "polygon " + std::to_string(polygon_index) : std::string("polygon");
  if (!rings.is_array() || rings.empty()) {
    context.Fail(polygon_name + " has no rings (expected an array of linear rings)");
  }
  GeoPolygon polygon;
  for (std::size_t r = 0; r < rings.size(); ++r) {
    const std::string ring_name = RingName(polygon_index, r, is_multi);
    const Json& positions = rings[r];
    if (!positions.is_array()) context.Fail(ring_name + " is not an array of positions");
    GeoRing ring;
    ring.reserve(positions.size());
    for (std::size_t p = 0; p < positions.size(); ++p) {
      ring.push_back(
          ReadPosition(positions[p], context, ring_name + " position " + std::to_string(p)));
    }
    if (ring.size() < kMinRingPositions) {
      context.Fail(ring_name + " has " + std::to_string(ring.size()) +
                   " positions; a closed ring needs at least 4");
    }
    if (ring.front().lat_deg != ring.back().lat_deg ||
        ring.front().lon_deg != ring.back().lon_deg) {
      context.Fail(ring_name + " is not closed (its last position must repeat the first)");
    }
    polygon.rings.push_back(std::move(ring));
  }
  return polygon;
}

void ReadGeometry(const Json& geometry, const Context& context, GeoFeature& feature) {
  if (geometry.is_null()) context.Fail("has no geometry");
  if (!geometry.is_object() || !geometry.contains("type") || !geometry["type"].is_string()) {
    context.Fail("geometry is not an object with a \"type\"");
  }
  const std::string type = geometry["type"].get<std::string>();
  if (type != "Polygon" && type != "MultiPolygon") {
    context.Fail("geometry type " + type + " is not supported (expected Polygon or MultiPolygon)");
  }
  if (!geometry.contains("coordinates") || !geometry["coordinates"].is_array()) {
    context.Fail(type + " has no \"coordinates\" array");
  }
  const Json& coordinates = geometry["coordinates"];
  if (type == "Polygon") {
    feature.polygons.push_back(ReadPolygon(coordinates, context, 0, false));
    return;
  }
  feature.is_multi = true;
  if (coordinates.empty()) context.Fail("MultiPolygon has no polygons");
  for (std::size_t p = 0; p < coordinates.size(); ++p) {
    feature.polygons.push_back(ReadPolygon(coordinates[p], context, p, true));
  }
}

// The feature's "name" property as a JSON string, else `id <id>`, else empty.
std::string NameOf(const Json& feature) {
  const auto properties = feature.find("properties");
  if (properties != feature.end() && properties->is_object()) {
    const auto name = properties->find("name");
    if (name != properties->end() && name->is_string()) return Json(*name).dump();
  }
  const auto id = feature.find("id");
  if (id != feature.end() && (id->is_string() || id->is_number())) return "id " + id->dump();
  return {};
}

// True when `object`'s "type" member is the string `type`. Not Json::value:
// that throws a type_error when the member is there but not a string (found by
// fuzz/geojson_area: {"type": {...}} in a feature ended `plan` in std::terminate).
bool HasType(const Json& object, std::string_view type) {
  const auto member = object.find("type");
  return member != object.end() && member->is_string() && member->get<std::string>() == type;
}

bool IsNoFly(const Json& feature) {
  const auto properties = feature.find("properties");
  if (properties == feature.end() || !properties->is_object()) return false;
  const auto no_fly = properties->find("no_fly");
  return no_fly != properties->end() && no_fly->is_boolean() && no_fly->get<bool>();
}

GeoFeature ReadFeature(const Json& feature, std::string_view source, std::size_t index) {
  Context context{source, FeatureLabel(index, feature.is_object() ? NameOf(feature) : "")};
  if (!feature.is_object() || !HasType(feature, "Feature")) {
    context.Fail("is not a GeoJSON Feature object");
  }
  GeoFeature result;
  result.label = context.label;
  result.no_fly = IsNoFly(feature);
  if (!feature.contains("geometry")) context.Fail("has no \"geometry\" member");
  ReadGeometry(feature["geometry"], context, result);
  return result;
}

// "line L, column C" of byte `offset` in `text` (both counted from 1).
std::string LineAndColumn(std::string_view text, std::size_t offset) {
  std::size_t line = 1;
  std::size_t column = 1;
  for (std::size_t i = 0; i < offset && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

Json Parse(std::string_view text, std::string_view source) {
  try {
    return Json::parse(text.begin(), text.end());
  } catch (const Json::parse_error& e) {
    // e.what() reads "[json.exception.parse_error.101] parse error at line L, column C: ...".
    std::string what = e.what();
    const auto start = what.find("parse error");
    if (start != std::string::npos) what = what.substr(start);
    throw std::invalid_argument(std::string(source) + ": malformed JSON: " + what + " (byte " +
                                std::to_string(e.byte) + ")");
  } catch (const Json::out_of_range& e) {
    // A number beyond double's range (1e999): the library names only the token,
    // "[json.exception.out_of_range.406] number overflow parsing '1e999'".
    std::string what = e.what();
    const auto quote = what.find('\'');
    std::string where;
    if (quote != std::string::npos && what.size() > quote + 1) {
      const std::string token = what.substr(quote + 1, what.size() - quote - 2);
      const std::size_t at = text.find(token);
      if (at != std::string_view::npos) where = " at " + LineAndColumn(text, at);
      what = token;
    }
    throw std::invalid_argument(std::string(source) + ": number out of range" + where + ": " +
                                what + " is not a finite number");
  }
}

}  // namespace

std::string FeatureLabel(std::size_t index, const std::string& description) {
  const std::string label = "feature " + std::to_string(index);
  return description.empty() ? label : label + " (" + description + ")";
}

std::vector<GeoFeature> ReadPolygonFeatures(std::string_view text, std::string_view source) {
  const Json document = Parse(text, source);
  if (!document.is_object() || !document.contains("type") || !document["type"].is_string()) {
    throw std::invalid_argument(std::string(source) +
                                ": not a GeoJSON object (no \"type\" member)");
  }
  const std::string type = document["type"].get<std::string>();
  std::vector<GeoFeature> features;
  if (type == "FeatureCollection") {
    if (!document.contains("features") || !document["features"].is_array()) {
      throw std::invalid_argument(std::string(source) +
                                  ": FeatureCollection has no \"features\" array");
    }
    const Json& list = document["features"];
    for (std::size_t i = 0; i < list.size(); ++i) {
      features.push_back(ReadFeature(list[i], source, i));
    }
  } else if (type == "Feature") {
    features.push_back(ReadFeature(document, source, 0));
  } else {
    GeoFeature feature;
    feature.label = "geometry";
    ReadGeometry(document, Context{source, feature.label}, feature);
    features.push_back(std::move(feature));
  }
  if (features.empty()) {
    throw std::invalid_argument(std::string(source) + ": no Polygon or MultiPolygon feature");
  }
  return features;
}

namespace {

constexpr int kMaxSiteDrones = 254;

GeoPoint ReadPoint(const Json& object, std::string_view source, std::size_t index, bool bare) {
  Context context{source, bare ? std::string("geometry")
                               : FeatureLabel(index, object.is_object() ? NameOf(object) : "")};
  if (!object.is_object()) context.Fail("is not a GeoJSON object");
  const Json* geometry = &object;
  GeoPoint point;
  point.label = context.label;
  if (!bare) {
    if (!HasType(object, "Feature")) context.Fail("is not a GeoJSON Feature object");
    if (!object.contains("geometry") || !object["geometry"].is_object()) {
      context.Fail("has no \"geometry\" object");
    }
    geometry = &object["geometry"];
    const auto properties = object.find("properties");
    if (properties != object.end() && properties->is_object() && properties->contains("drones")) {
      const Json& drones = (*properties)["drones"];
      if (!drones.is_number_integer() || drones.get<long long>() < 0 ||
          drones.get<long long>() > kMaxSiteDrones) {
        context.Fail("properties.drones must be an integer in 0..254, got " + drones.dump());
      }
      point.drones = drones.get<int>();
    }
  }
  // Not value("type", ""): it throws when "type" is there but not a string.
  if (!HasType(*geometry, "Point")) {
    const auto type = geometry->find("type");
    const std::string found = type == geometry->end() ? std::string("missing")
                              : type->is_string()
                                  ? type->get<std::string>()
                                  : "a \"type\" that is " + std::string(type->type_name());
    context.Fail("geometry is " + found + ", expected a Point (a launch site)");
  }
  if (!geometry->contains("coordinates")) context.Fail("Point has no coordinates");
  point.position = ReadPosition((*geometry)["coordinates"], context, "the position");
  return point;
}

}  // namespace

std::vector<GeoPoint> ReadPointFeatures(std::string_view text, std::string_view source) {
  const Json document = Parse(text, source);
  if (!document.is_object() || !document.contains("type") || !document["type"].is_string()) {
    throw std::invalid_argument(std::string(source) +
                                ": not a GeoJSON object (no \"type\" member)");
  }
  const std::string type = document["type"].get<std::string>();
  std::vector<GeoPoint> points;
  if (type == "FeatureCollection") {
    if (!document.contains("features") || !document["features"].is_array()) {
      throw std::invalid_argument(std::string(source) +
                                  ": FeatureCollection has no \"features\" array");
    }
    const Json& list = document["features"];
    for (std::size_t i = 0; i < list.size(); ++i)
      points.push_back(ReadPoint(list[i], source, i, false));
  } else {
    points.push_back(ReadPoint(document, source, 0, type != "Feature"));
  }
  if (points.empty()) throw std::invalid_argument(std::string(source) + ": no Point feature");
  return points;
}

}  // namespace fireswarm::planner::geojson
