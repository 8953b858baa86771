// Reading search areas from GeoJSON: projection, holes, no-fly zones, and an
// error that names the file, the feature and the problem for each bad input.
#include "fireswarm/planner/area_io.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <boost/geometry/algorithms/area.hpp>
#include <boost/geometry/algorithms/covered_by.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <string>

namespace fireswarm::planner {
namespace {

namespace bg = boost::geometry;
using ::testing::HasSubstr;

constexpr double kLat = 46.2;  // the Laurentians, Quebec
constexpr double kLon = -74.6;
constexpr double kMetresPerDegreeLat = 111'150.0;  // near 46 deg, to size test shapes only

// A closed [lon, lat] ring of the box [lon0, lon1] x [lat0, lat1], counter-clockwise.
std::string BoxRing(double lon0, double lat0, double lon1, double lat1) {
  const auto p = [](double lon, double lat) {
    std::ostringstream out;
    out << std::setprecision(17) << "[" << lon << "," << lat << "]";
    return out.str();
  };
  return "[" + p(lon0, lat0) + "," + p(lon1, lat0) + "," + p(lon1, lat1) + "," + p(lon0, lat1) +
         "," + p(lon0, lat0) + "]";
}

std::string Feature(const std::string& name, const std::string& geometry,
                    const std::string& extra_properties = "") {
  return R"({"type":"Feature","properties":{"name":")" + name + "\"" + extra_properties +
         "},\"geometry\":" + geometry + "}";
}

std::string Collection(const std::string& features) {
  return R"({"type":"FeatureCollection","features":[)" + features + "]}";
}

std::string PolygonOf(const std::string& rings) {
  return R"({"type":"Polygon","coordinates":[)" + rings + "]}";
}

// About 2.2 km x 1.5 km around (kLat, kLon) with a 0.02 x 0.01 degree hole.
const std::string kSquare = BoxRing(kLon - 0.01, kLat - 0.01, kLon + 0.01, kLat + 0.01);
const std::string kHole = BoxRing(kLon - 0.005, kLat - 0.005, kLon + 0.005, kLat);

std::string ErrorOf(const std::string& area, const std::optional<std::string>& no_fly = {}) {
  try {
    std::optional<GeoJsonText> zones;
    if (no_fly) zones = GeoJsonText{*no_fly, "nofly.geojson"};
    ParseSearchArea({area, "area.geojson"}, zones);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(LoadSearchArea, ProjectionRoundTripsAtMillimetresOver20Km) {
  // A 20 km x 20 km square: its corners are 14 km from the origin.
  const double half_lat = 10'000.0 / kMetresPerDegreeLat;
  const double half_lon = half_lat / std::cos(kLat * M_PI / 180.0);
  const std::string text =
      PolygonOf(BoxRing(kLon - half_lon, kLat - half_lat, kLon + half_lon, kLat + half_lat));
  const SearchArea area = ParseSearchArea({text, "big.geojson"});
  EXPECT_NEAR(area.frame.origin().lat_deg, kLat, 1e-9);
  EXPECT_NEAR(area.frame.origin().lon_deg, kLon, 1e-9);
  ASSERT_EQ(area.area.size(), 1U);
  EXPECT_NEAR(bg::area(area.area) / 1e6, 400.0, 2.0);
  for (const Point& corner : area.area.front().outer()) {
    EXPECT_NEAR(std::abs(corner.x()), 10'000.0, 60.0);  // cos(lat) varies over the box
    const common::LatLon back = area.frame.ToGeodetic({corner.x(), corner.y()});
    EXPECT_NEAR(std::abs(back.lat_deg - kLat), half_lat, 1e-3 / kMetresPerDegreeLat);
    EXPECT_NEAR(std::abs(back.lon_deg - kLon), half_lon, 2e-3 / kMetresPerDegreeLat);
  }
  // Any point 20 km out goes there and back within a millimetre.
  for (double bearing_deg = 0.0; bearing_deg < 360.0; bearing_deg += 45.0) {
    const double east_m = 20'000.0 * std::sin(bearing_deg * M_PI / 180.0);
    const double north_m = 20'000.0 * std::cos(bearing_deg * M_PI / 180.0);
    const common::EastNorth there = area.frame.ToLocal(area.frame.ToGeodetic({east_m, north_m}));
    EXPECT_NEAR(there.east_m, east_m, 1e-3);
    EXPECT_NEAR(there.north_m, north_m, 1e-3);
  }
}

TEST(LoadSearchArea, ReadsAPolygonWithAHole) {
  const SearchArea area = ParseSearchArea({PolygonOf(kSquare + "," + kHole), "area.geojson"});
  ASSERT_EQ(area.area.size(), 1U);
  EXPECT_EQ(area.area.front().inners().size(), 1U);
  EXPECT_TRUE(area.no_fly.empty());
  EXPECT_FALSE(bg::covered_by(Point(0.0, -200.0), area.area));  // inside the hole
  EXPECT_TRUE(bg::covered_by(Point(0.0, 800.0), area.area));
  // 0.02 x 0.02 deg minus 0.01 x 0.005 deg: 7/8 of the square.
  const double square_m2 =
      (0.02 * kMetresPerDegreeLat) * (0.02 * kMetresPerDegreeLat * std::cos(kLat * M_PI / 180.0));
  EXPECT_NEAR(bg::area(area.area) / square_m2, 0.875, 0.005);
}

TEST(LoadSearchArea, ReadsAMultiPolygonWithHolesAndUnitesFeatures) {
  const std::string east = BoxRing(kLon + 0.02, kLat - 0.01, kLon + 0.04, kLat + 0.01);
  const std::string multi =
      R"({"type":"MultiPolygon","coordinates":[[)" + kSquare + "," + kHole + "],[" + east + "]]}";
  const SearchArea area = ParseSearchArea({Collection(Feature("two blocks", multi)), "a.geojson"});
  ASSERT_EQ(area.area.size(), 2U);
  std::size_t holes = 0;
  for (const Polygon& p : area.area) holes += p.inners().size();
  EXPECT_EQ(holes, 1U);
  // A bare Feature is accepted too.
  EXPECT_EQ(ParseSearchArea({Feature("one", PolygonOf(kSquare)), "f.geojson"}).area.size(), 1U);
}

TEST(LoadSearchArea, SubtractsNoFlyZonesFromBothSources) {
  const std::string zone = BoxRing(kLon + 0.005, kLat + 0.005, kLon + 0.015, kLat + 0.015);
  const std::string inline_zone =
      Feature("tower", PolygonOf(BoxRing(kLon - 0.01, kLat - 0.01, kLon - 0.008, kLat - 0.008)),
              R"(,"no_fly":true)");
  const SearchArea area = ParseSearchArea(
      {Collection(Feature("forest", PolygonOf(kSquare)) + "," + inline_zone), "area.geojson"},
      GeoJsonText{Collection(Feature("airstrip", PolygonOf(zone))), "nofly.geojson"});
  EXPECT_EQ(area.no_fly.size(), 2U);
  // The airstrip zone reaches beyond the area and is kept whole for transit.
  EXPECT_GT(bg::area(area.no_fly), 0.0);
  const SearchArea without = ParseSearchArea({PolygonOf(kSquare), "area.geojson"});
  const double cut_m2 = bg::area(without.area) - bg::area(area.area);
  const double cell_m2 = 0.001 * 0.001 * kMetresPerDegreeLat * kMetresPerDegreeLat *
                         std::cos(kLat * M_PI / 180.0);  // 0.001 deg squared
  EXPECT_NEAR(cut_m2 / cell_m2, 25.0 + 4.0, 0.3);        // 5x5 + 2x2 thousandths of a degree
}

TEST(LoadSearchArea, ReadsFilesAndNamesAMissingOne) {
  const auto path = std::filesystem::temp_directory_path() /
                    ("fireswarm_area_io_" + std::to_string(getpid()) + ".geojson");
  std::ofstream(path) << PolygonOf(kSquare);
  EXPECT_EQ(LoadSearchArea(path).area.size(), 1U);
  std::filesystem::remove(path);
  try {
    LoadSearchArea(path);
    FAIL() << "no error for a missing file";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr(path.string() + ": cannot open"));
  }
}

TEST(LoadSearchAreaErrors, SelfIntersection) {
  // A bow tie: the ring crosses itself at the centre.
  const std::string bow_tie = "[[" + std::to_string(kLon) + "," + std::to_string(kLat) + "],[" +
                              std::to_string(kLon + 0.01) + "," + std::to_string(kLat + 0.01) +
                              "],[" + std::to_string(kLon + 0.01) + "," + std::to_string(kLat) +
                              "],[" + std::to_string(kLon) + "," + std::to_string(kLat + 0.01) +
                              "],[" + std::to_string(kLon) + "," + std::to_string(kLat) + "]]";
  const std::string text = Collection(Feature("ok", PolygonOf(kSquare)) + "," +
                                      Feature("north block", PolygonOf(bow_tie)));
  EXPECT_EQ(ErrorOf(text),
            "area.geojson: feature 1 (\"north block\"): polygon is self-intersecting (edges cross "
            "or touch)");
}

// Issue 19: an uneven bow tie (one lobe larger) was called "wrong orientation";
// a hole that crosses itself is named as the hole.
TEST(LoadSearchAreaErrors, UnevenBowTieAndCrossedHoleAreSelfIntersecting) {
  const auto at = [](double east_deg, double north_deg) {
    return "[" + std::to_string(kLon + east_deg) + "," + std::to_string(kLat + north_deg) + "]";
  };
  const std::string uneven = "[" + at(0, 0) + "," + at(0.02, 0.02) + "," + at(0.02, 0) + "," +
                             at(0.01, 0.015) + "," + at(0, 0) + "]";
  EXPECT_EQ(ErrorOf(Collection(Feature("uneven", PolygonOf(uneven)))),
            "area.geojson: feature 0 (\"uneven\"): polygon is self-intersecting (edges cross or "
            "touch)");
  const std::string crossed_hole = "[" + at(-0.005, -0.005) + "," + at(0.005, 0.005) + "," +
                                   at(0.005, -0.005) + "," + at(-0.005, 0.005) + "," +
                                   at(-0.005, -0.005) + "]";
  EXPECT_EQ(ErrorOf(PolygonOf(kSquare + "," + crossed_hole)),
            "area.geojson: geometry: polygon hole 1 is self-intersecting (edges cross or touch)");
}

// Issue 19: a flat polygon (corners on one line, to a nanodegree) beside a real
// one was planned: the union hid it.
TEST(LoadSearchAreaErrors, FlatPolygonHasNearZeroArea) {
  std::ostringstream flat;
  const double north = kLat + 0.02;
  flat << std::setprecision(12) << "[[" << kLon << "," << north << "],[" << kLon + 0.01 << ","
       << north << "],[" << kLon + 0.02 << "," << north + 1e-9 << "],[" << kLon << "," << north
       << "]]";
  const std::string error = ErrorOf(Collection(Feature("block", PolygonOf(kSquare)) + "," +
                                               Feature("strip", PolygonOf(flat.str()))));
  EXPECT_THAT(error, HasSubstr("area.geojson: feature 1 (\"strip\"): polygon has (near-)zero "
                               "area"));
}

// Issue 19: 1e999 overflows a double; the library's message named no file.
TEST(LoadSearchAreaErrors, ANumberBeyondDoubleNamesFileLineAndColumn) {
  const std::string text = "{\"type\":\"Polygon\",\n\"coordinates\":[[[1e999,0],[1,0],[1,1],[1e999,0]]]}";
  EXPECT_EQ(ErrorOf(text),
            "area.geojson: number out of range at line 2, column 18: 1e999 is not a finite number");
}

TEST(LoadSearchAreaErrors, UnclosedRing) {
  std::string open = kSquare;
  open = open.substr(0, open.rfind(",[")) + "]";  // drop the closing position
  const std::string text =
      Collection(Feature("a", PolygonOf(kSquare)) + "," + Feature("b", PolygonOf(kSquare)) + "," +
                 Feature("north block", PolygonOf(kSquare + "," + open)));
  EXPECT_EQ(ErrorOf(text),
            "area.geojson: feature 2 (\"north block\"): ring 1 is not closed (its last position "
            "must repeat the first)");
}

TEST(LoadSearchAreaErrors, LatitudeAndLongitudeOutOfRange) {
  // Latitude and longitude swapped: 46 becomes a longitude, -74.6 a latitude (still valid),
  // so use a clearly wrong latitude instead.
  EXPECT_THAT(ErrorOf(PolygonOf(BoxRing(kLon, 91.0, kLon + 0.01, 91.5))),
              HasSubstr("area.geojson: geometry: ring 0 position 0 has latitude 91.000000 out of "
                        "range [-90, 90]"));
  EXPECT_THAT(
      ErrorOf(Collection(Feature("far east", PolygonOf(BoxRing(181.0, kLat, 182.0, kLat + 0.01))))),
      HasSubstr("area.geojson: feature 0 (\"far east\"): ring 0 position 0 has longitude "
                "181.000000 out of range [-180, 180]"));
}

TEST(LoadSearchAreaErrors, NoAreaLeftAfterNoFlyZones) {
  const std::string zone = BoxRing(kLon - 0.02, kLat - 0.02, kLon + 0.02, kLat + 0.02);
  EXPECT_EQ(ErrorOf(PolygonOf(kSquare), Collection(Feature("everything", PolygonOf(zone)))),
            "area.geojson: no area left after subtracting the no-fly zones (nofly.geojson)");
}

TEST(LoadSearchAreaErrors, AreaTooLarge) {
  // 1.5 x 1.5 degrees: about 167 km x 116 km, some 19,000 km2.
  EXPECT_THAT(
      ErrorOf(Collection(Feature(
          "province", PolygonOf(BoxRing(kLon - 0.75, kLat - 0.75, kLon + 0.75, kLat + 0.75))))),
      HasSubstr("area.geojson: feature 0 (\"province\"): polygon covers"));
  EXPECT_THAT(ErrorOf(PolygonOf(BoxRing(kLon - 0.75, kLat - 0.75, kLon + 0.75, kLat + 0.75))),
              HasSubstr("km2, more than the sane maximum of 10000 km2"));
  // Two small features 6 degrees (some 460 km) apart: each far from the common origin.
  const std::string far =
      Collection(Feature("west", PolygonOf(kSquare)) + "," +
                 Feature("east", PolygonOf(BoxRing(kLon + 6.0, kLat, kLon + 6.01, kLat + 0.01))));
  EXPECT_THAT(ErrorOf(far), HasSubstr("area.geojson: feature 0 (\"west\"): polygon reaches"));
}

TEST(LoadSearchAreaErrors, MalformedJson) {
  const std::string error = ErrorOf("{\"type\": \"Polygon\",\n \"coordinates\": [[1, 2]");
  EXPECT_THAT(error, HasSubstr("area.geojson: malformed JSON: parse error at line 2, column"));
}

TEST(LoadSearchAreaErrors, WrongGeometryType) {
  const std::string line = R"({"type":"LineString","coordinates":[[-74.6,46.2],[-74.5,46.3]]})";
  EXPECT_EQ(ErrorOf(Collection(Feature("road", line))),
            "area.geojson: feature 0 (\"road\"): geometry type LineString is not supported "
            "(expected Polygon or MultiPolygon)");
  EXPECT_EQ(ErrorOf(R"({"type":"Feature","id":7,"properties":null,"geometry":null})"),
            "area.geojson: feature 0 (id 7): has no geometry");
  EXPECT_EQ(ErrorOf(R"({"type":"FeatureCollection","features":[]})"),
            "area.geojson: no Polygon or MultiPolygon feature");
}

// A "type" that is there but not a string: named like any other non-Feature
// (nlohmann's value() threw a type_error past the reader: found by
// fuzz/geojson_area, whose corpus keeps the input).
TEST(LoadSearchAreaErrors, ATypeThatIsNotAStringIsNotAFeature) {
  EXPECT_EQ(ErrorOf(R"({"type":"FeatureCollection","features":[{"type":{"type":"Point"}}]})"),
            "area.geojson: feature 0: is not a GeoJSON Feature object");
  EXPECT_THAT(ErrorOf(R"({"type":"FeatureCollection","features":[{"type":7}]})"),
              HasSubstr("feature 0: is not a GeoJSON Feature object"));
  try {
    ParseLaunchSites({R"({"type":"FeatureCollection","features":[{"type":[]}]})", "sites.geojson"});
    FAIL() << "accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), HasSubstr("sites.geojson: feature 0"));
    EXPECT_THAT(e.what(), HasSubstr("is not a GeoJSON Feature object"));
  }
}

// The launch-site reader's geometry "type" that is not a string (found by the
// geojson_area fuzz target: nlohmann's value("type", "") threw type_error).
TEST(ParseLaunchSitesErrors, AGeometryTypeThatIsNotAStringIsNamed) {
  for (const std::string type : {"[[6.6, 46.5]]", "7", "{}", "null"}) {
    try {
      ParseLaunchSites({R"({"type":"FeatureCollection","features":[{"type":"Feature",)"
                        R"("geometry":{"type":)" +
                            type + R"(,"coordinates":[6.6,46.5]}}]})",
                        "sites.geojson"});
      FAIL() << "accepted a geometry type of " << type;
    } catch (const std::invalid_argument& e) {
      EXPECT_THAT(e.what(), HasSubstr("sites.geojson: feature 0"));
      EXPECT_THAT(e.what(), HasSubstr("geometry is a \"type\" that is "));
      EXPECT_THAT(e.what(), HasSubstr("expected a Point (a launch site)"));
    }
  }
}

TEST(LoadSearchAreaErrors, TooFewPositionsAndBadPositions) {
  const std::string two = "[[-74.6,46.2],[-74.5,46.2],[-74.6,46.2]]";
  EXPECT_EQ(ErrorOf(PolygonOf(two)),
            "area.geojson: geometry: ring 0 has 3 positions; a closed ring needs at least 4");
  EXPECT_EQ(ErrorOf(PolygonOf(R"([[-74.6,46.2],["x",46.2],[-74.5,46.3],[-74.6,46.2]])")),
            "area.geojson: geometry: ring 0 position 1 is not a [longitude, latitude] pair of "
            "numbers");
  EXPECT_EQ(ErrorOf(Collection(R"({"type":"Feature","properties":{"no_fly":true},"geometry":)" +
                               PolygonOf(kSquare) + "}")),
            "area.geojson: every feature is a no-fly zone; there is no area to search");
}

}  // namespace
}  // namespace fireswarm::planner
