// The run's SVG map: a well-formed document that puts every drone's path, fire,
// fused fire with its covariance ellipse, false track and collision where the
// scale bar says, north up, with escaped text and the same bytes every time.
#include "fireswarm/run/svg_map.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "mini_xml.hpp"

namespace fireswarm::run {
namespace {

namespace fs = std::filesystem;
using test::ParseXml;
using test::XmlDocument;
using test::XmlElement;
using ::testing::HasSubstr;
using ::testing::Not;

// About 460 m x 330 m in the Laurentians, with a no-fly square inside it (cut out
// of the area as a hole) so the map is large enough to measure in pixels.
constexpr const char* kScenarioYaml = R"(name: svg test
area:
  polygon: [[-74.603, 46.1985], [-74.597, 46.1985], [-74.597, 46.2015], [-74.603, 46.2015]]
no_fly:
  - [[-74.6005, 46.1995], [-74.5995, 46.1995], [-74.5995, 46.2005], [-74.6005, 46.2005]]
fleet:
  count: 3
  launch: {lat: 46.1987, lon: -74.6028}
)";

Scenario TestScenario() {
  return ParseScenario(kScenarioYaml, "svg.yaml", fs::path("."));
}

common::LatLon At(const Scenario& scenario, double east_m, double north_m) {
  return scenario.area.frame.ToGeodetic({east_m, north_m});
}

double Number(const XmlElement& element, const std::string& key) {
  const std::string value = element.Attribute(key);
  EXPECT_FALSE(value.empty()) << element.name << " has no " << key;
  return value.empty() ? std::numeric_limits<double>::quiet_NaN() : std::stod(value);
}

XmlDocument ParsedSvg(const std::string& svg) {
  XmlDocument doc = ParseXml(svg);
  EXPECT_EQ(doc.error, "") << svg.substr(0, 2000);
  return doc;
}

// Pixels per metre as a reader measures it: the scale bar's length over its label.
double PxPerMetre(const XmlDocument& doc) {
  const XmlElement* line = doc.ById("scale-bar-line");
  const XmlElement* label = doc.ById("scale-bar-label");
  if (line == nullptr || label == nullptr) {
    ADD_FAILURE() << "no scale bar";
    return std::numeric_limits<double>::quiet_NaN();
  }
  std::istringstream text(label->text);
  double length = 0.0;
  std::string unit;
  text >> length >> unit;
  const double length_m = unit == "km" ? length * 1'000.0 : length;
  EXPECT_TRUE(unit == "m" || unit == "km") << label->text;
  return (Number(*line, "x2") - Number(*line, "x1")) / length_m;
}

// The number of subpaths ("M" commands) of a path.
std::size_t Subpaths(const XmlElement& path) {
  const std::string d = path.Attribute("d");
  return static_cast<std::size_t>(std::count(d.begin(), d.end(), 'M'));
}

// Three drones flying lanes, two fires (one confirmed), a false track, a collision.
Report TestReport(const Scenario& scenario) {
  Report report;
  report.scenario = scenario.name;
  report.seed = 7;
  report.coverage = 0.875;
  report.sim_seconds = 900.0;
  for (int id = 1; id <= 3; ++id) {
    VehicleOutcome& vehicle = report.vehicles[id];
    const double east_m = -150.0 + 100.0 * id;
    for (int step = 0; step <= 100; ++step) {
      vehicle.track.push_back(At(scenario, east_m, -150.0 + 3.0 * step));
    }
  }
  FireOutcome confirmed;
  confirmed.truth = At(scenario, -100.0, 80.0);
  confirmed.fused = At(scenario, -100.0, 90.0);  // 10 m north of the truth
  confirmed.covariance_ne_m2 = std::array<double, 3>{16.0, 0.0, 4.0};
  report.fires.push_back(confirmed);
  FireOutcome missed;
  missed.truth = At(scenario, 150.0, -100.0);
  report.fires.push_back(missed);
  FalseTrack false_track;
  false_track.track_id = 12;
  false_track.position = At(scenario, 0.0, 120.0);
  report.false_tracks.push_back(false_track);
  Collision collision;
  collision.t_s = 83.04;
  collision.vehicle_a = 1;
  collision.vehicle_b = 2;
  collision.position = At(scenario, -80.0, -100.0);
  report.collisions.push_back(collision);
  return report;
}

TEST(SvgMap, IsAWellFormedSvgDocument) {
  const Scenario scenario = TestScenario();
  const std::string svg = SvgMap(TestReport(scenario), scenario);
  const XmlDocument doc = ParsedSvg(svg);
  ASSERT_FALSE(doc.elements.empty());
  EXPECT_EQ(doc.elements[0].name, "svg");
  EXPECT_EQ(doc.elements[0].Attribute("xmlns"), "http://www.w3.org/2000/svg");
  EXPECT_GT(Number(doc.elements[0], "width"), 900.0);
  // Every url(#id) it uses is defined in it.
  for (const std::string id : {"no-fly-hatch", "map-clip"}) {
    EXPECT_THAT(svg, HasSubstr("url(#" + id + ")"));
    EXPECT_NE(doc.ById(id), nullptr) << id;
  }
}

TEST(SvgMap, DrawsOnePathPerDroneInItsOwnColourNamedInTheLegend) {
  const Scenario scenario = TestScenario();
  const XmlDocument doc = ParsedSvg(SvgMap(TestReport(scenario), scenario));
  const auto paths = doc.Find("path", "tracks");
  ASSERT_EQ(paths.size(), 3U);
  std::set<std::string> colours;
  for (int id = 1; id <= 3; ++id) {
    const XmlElement* path = doc.ById("track-" + std::to_string(id));
    ASSERT_NE(path, nullptr) << id;
    EXPECT_THAT(path->Attribute("stroke"), testing::MatchesRegex("#[0-9a-f]{6}"));
    colours.insert(path->Attribute("stroke"));
    // A straight lane thins to its two ends.
    EXPECT_EQ(path->Attribute("d").find('L'), path->Attribute("d").rfind('L'));
  }
  EXPECT_EQ(colours.size(), 3U);
  // The legend shows each drone's colour beside its receiver ID.
  std::set<std::string> legend_colours;
  std::set<std::string> legend_texts;
  for (const XmlElement* path : doc.Find("path", "legend")) {
    legend_colours.insert(path->Attribute("stroke"));
  }
  for (const XmlElement* text : doc.Find("text", "legend")) legend_texts.insert(text->text);
  for (const std::string& colour : colours) EXPECT_TRUE(legend_colours.contains(colour));
  for (const std::string id : {"1", "2", "3"}) EXPECT_TRUE(legend_texts.contains(id)) << id;
}

TEST(SvgMap, MarksEveryLaunchSiteAndEachDronesSortiesInTheLegend) {
  const Scenario scenario = ParseScenario(
      std::string(kScenarioYaml)
          .replace(std::string(kScenarioYaml).find("  launch: {"), std::string::npos,
                   "  launch: [{lat: 46.1987, lon: -74.6028}, {lat: 46.2013, lon: -74.5972}]\n"),
      "svg.yaml", fs::path("."));
  Report report = TestReport(scenario);
  report.vehicles[1].sorties_planned = 3;
  report.vehicles[1].sorties_flown = 2;
  report.vehicles[2].sorties_planned = 1;
  report.vehicles[2].sorties_flown = 1;
  const XmlDocument doc = ParsedSvg(SvgMap(report, scenario));
  EXPECT_EQ(doc.Find("rect", "launch").size(), 2U);
  std::set<std::string> legend_texts;
  for (const XmlElement* text : doc.Find("text", "legend")) legend_texts.insert(text->text);
  EXPECT_TRUE(legend_texts.contains("1: 2/3"));
  EXPECT_TRUE(legend_texts.contains("2: 1/1"));
  EXPECT_TRUE(legend_texts.contains("Drones (receiver ID: sorties flown/planned)"));
}

TEST(SvgMap, NorthIsUpEastIsRightAtTheScaleBarsScale) {
  const Scenario scenario = TestScenario();
  const XmlDocument doc = ParsedSvg(SvgMap(TestReport(scenario), scenario));
  const double px_per_m = PxPerMetre(doc);
  EXPECT_GT(px_per_m, 1.0);
  // The fused fire lies 10 m north of the true one: straight up on the picture.
  const auto fires = doc.Find("circle", "fires");
  const auto ellipses = doc.Find("ellipse", "fused-ellipses");
  ASSERT_EQ(fires.size(), 2U);
  ASSERT_EQ(ellipses.size(), 1U);
  EXPECT_NEAR(Number(*ellipses[0], "cx"), Number(*fires[0], "cx"), 0.11);
  EXPECT_NEAR(Number(*fires[0], "cy") - Number(*ellipses[0], "cy"), 10.0 * px_per_m, 0.15);
  // The second fire lies 250 m east and 180 m south of the first.
  // (The scale bar's own tenth-of-a-pixel rounding grows with the distance.)
  EXPECT_NEAR(Number(*fires[1], "cx") - Number(*fires[0], "cx"), 250.0 * px_per_m, 0.5);
  EXPECT_NEAR(Number(*fires[1], "cy") - Number(*fires[0], "cy"), 180.0 * px_per_m, 0.5);
}

TEST(SvgMap, FusedEllipseHasTheCovariancesTwoSigmaAxesAndOrientation) {
  const Scenario scenario = TestScenario();
  Report report = TestReport(scenario);
  // var north 16 m^2, var east 4 m^2: 2-sigma semi-axes 8 m north-south, 4 m east-west.
  // Correlated: var 10 both ways, cov 6: variances 16 along north-east, 4 across.
  FireOutcome correlated = report.fires[0];
  correlated.truth = At(scenario, 100.0, 100.0);
  correlated.fused = At(scenario, 100.0, 100.0);
  correlated.covariance_ne_m2 = std::array<double, 3>{10.0, 6.0, 10.0};
  report.fires.push_back(correlated);
  const XmlDocument doc = ParsedSvg(SvgMap(report, scenario));
  const double px_per_m = PxPerMetre(doc);
  const auto ellipses = doc.Find("ellipse", "fused-ellipses");
  ASSERT_EQ(ellipses.size(), 2U);
  for (const XmlElement* ellipse : ellipses) {
    EXPECT_NEAR(Number(*ellipse, "rx"), 8.0 * px_per_m, 0.08);
    EXPECT_NEAR(Number(*ellipse, "ry"), 4.0 * px_per_m, 0.08);
  }
  // The long axis points north (rotate 90 deg from east) for the first, north-east
  // (45 deg counter-clockwise on a y-down picture) for the second.
  EXPECT_THAT(ellipses[0]->Attribute("transform"), testing::StartsWith("rotate(90.0 "));
  EXPECT_THAT(ellipses[1]->Attribute("transform"), testing::StartsWith("rotate(-45.0 "));
}

TEST(SvgMap, AreaHolesStayOpenAndNoFlyZonesAreHatched) {
  const Scenario scenario = TestScenario();
  const XmlDocument doc = ParsedSvg(SvgMap(TestReport(scenario), scenario));
  const XmlElement* area = doc.ById("area");
  ASSERT_NE(area, nullptr);
  EXPECT_EQ(area->Attribute("fill-rule"), "evenodd");
  const auto area_paths = doc.Find("path", "area");
  ASSERT_EQ(area_paths.size(), 1U);
  EXPECT_EQ(Subpaths(*area_paths[0]), 2U);  // the outer ring and the no-fly hole
  const XmlElement* no_fly = doc.ById("no-fly");
  ASSERT_NE(no_fly, nullptr);
  EXPECT_EQ(no_fly->Attribute("fill"), "url(#no-fly-hatch)");
  EXPECT_EQ(doc.Find("path", "no-fly").size(), 1U);
  EXPECT_EQ(doc.Find("rect", "launch").size(), 1U);
}

TEST(SvgMap, MarksCollisionsFalseTracksAndMissedFires) {
  const Scenario scenario = TestScenario();
  const XmlDocument doc = ParsedSvg(SvgMap(TestReport(scenario), scenario));
  EXPECT_EQ(doc.Find("g", "collisions").size(), 1U);
  EXPECT_EQ(doc.Find("path", "false-tracks").size(), 1U);
  EXPECT_EQ(doc.Find("path", "fused-fires").size(), 1U);  // one cross: one confirmed fire
  std::set<std::string> labels;
  for (const XmlElement* text : doc.Find("text", "labels")) labels.insert(text->text);
  EXPECT_TRUE(labels.contains("t=83.0 s (1\u00d72)"));
  EXPECT_TRUE(labels.contains("track 12"));
  EXPECT_TRUE(labels.contains("F1"));
  EXPECT_TRUE(labels.contains("F2 not confirmed"));
}

TEST(SvgMap, TitleNamesTheScenarioWithFiresConfirmedAndCoverage) {
  const Scenario scenario = TestScenario();
  const XmlDocument doc = ParsedSvg(SvgMap(TestReport(scenario), scenario));
  ASSERT_NE(doc.ById("title"), nullptr);
  EXPECT_EQ(doc.ById("title")->text, "fireswarm run: svg test");
  ASSERT_NE(doc.ById("summary"), nullptr);
  EXPECT_THAT(doc.ById("summary")->text, HasSubstr("fires confirmed 1/2"));
  EXPECT_THAT(doc.ById("summary")->text, HasSubstr("coverage 87.5 %"));
  EXPECT_THAT(doc.ById("summary")->text, HasSubstr("collisions 1"));
}

TEST(SvgMap, EscapesTheScenarioName) {
  const Scenario scenario = TestScenario();
  Report report = TestReport(scenario);
  report.scenario = "a<b & \"c\"";
  const std::string svg = SvgMap(report, scenario);
  EXPECT_THAT(svg, Not(HasSubstr("a<b")));
  const XmlDocument doc = ParsedSvg(svg);
  ASSERT_NE(doc.ById("title"), nullptr);
  EXPECT_EQ(doc.ById("title")->text, "fireswarm run: a<b & \"c\"");
  EXPECT_EQ(doc.Find("title").at(0)->text, "fireswarm run: a<b & \"c\"");
}

TEST(SvgMap, IsDeterministicAndSmallForLongTracks) {
  const Scenario scenario = TestScenario();
  Report report = TestReport(scenario);
  // An hour of lawnmower lanes sampled every second, with centimetre jitter: the
  // drawn path keeps the turns and drops what does not show.
  VehicleOutcome& long_flight = report.vehicles[4];
  for (int second = 0; second < 3'600; ++second) {
    const int lane = second / 300;
    const double along_m = (second % 300) - 150.0;
    const double jitter_m = 0.01 * ((second * 7) % 5);
    const double east_m = -200.0 + 30.0 * lane + jitter_m;
    const double north_m = lane % 2 == 0 ? along_m : -along_m;
    long_flight.track.push_back(At(scenario, east_m, north_m));
  }
  const std::string svg = SvgMap(report, scenario);
  EXPECT_EQ(svg, SvgMap(report, scenario));
  const XmlDocument doc = ParsedSvg(svg);
  const XmlElement* path = doc.ById("track-4");
  ASSERT_NE(path, nullptr);
  const std::string d = path->Attribute("d");
  // "M x yL x y x y ...": one space inside each pair, one between pairs after the first two.
  const auto points = (std::count(d.begin(), d.end(), ' ') + 2) / 2;
  EXPECT_GE(points, 2 * 12 - 2);  // 12 lanes: two ends each
  EXPECT_LE(points, 2 * 12 + 4);
  EXPECT_LT(svg.size(), 20'000U);
}

TEST(SvgMap, LeavesOutPositionsItCannotPlace) {
  const Scenario scenario = TestScenario();
  const Report report = TestReport(scenario);
  Report broken = report;
  broken.vehicles[1].track.push_back({std::numeric_limits<double>::quiet_NaN(), 0.0});
  broken.vehicles[1].track.push_back({-46.2, 105.4});  // the antipode
  FireOutcome nowhere;
  nowhere.truth = {0.0, 0.0};  // an unset position, thousands of km away
  broken.fires.push_back(nowhere);
  const XmlDocument doc = ParsedSvg(SvgMap(broken, scenario));
  EXPECT_DOUBLE_EQ(PxPerMetre(doc), PxPerMetre(ParsedSvg(SvgMap(report, scenario))));
  EXPECT_EQ(doc.Find("circle", "fires").size(), 2U);
}

TEST(SvgMap, ManyDronesGetDistinctColoursAndLegendColumns) {
  const Scenario scenario = TestScenario();
  Report report = TestReport(scenario);
  for (int id = kMinReceiverId; id <= kMaxReceiverId; ++id) {
    report.vehicles[id].track = {At(scenario, id, 0.0), At(scenario, id, 50.0)};
  }
  const XmlDocument doc = ParsedSvg(SvgMap(report, scenario));
  std::set<std::string> colours;
  for (const XmlElement* path : doc.Find("path", "tracks"))
    colours.insert(path->Attribute("stroke"));
  EXPECT_EQ(colours.size(), static_cast<std::size_t>(kMaxReceiverId - kMinReceiverId + 1));
  // Every legend entry lies inside the picture.
  const double width = Number(doc.elements[0], "width");
  const double height = Number(doc.elements[0], "height");
  for (const XmlElement* text : doc.Find("text", "legend")) {
    EXPECT_LT(Number(*text, "x"), width - 10.0) << text->text;
    EXPECT_LT(Number(*text, "y"), height) << text->text;
  }
}

TEST(SvgMap, WriteSvgMapWritesTheSameDocument) {
  const Scenario scenario = TestScenario();
  const Report report = TestReport(scenario);
  const fs::path dir = fs::temp_directory_path() / ("svg_map_test_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const fs::path path = dir / "map.svg";
  WriteSvgMap(report, scenario, path);
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(), SvgMap(report, scenario));
  fs::remove_all(dir);
}

TEST(SvgMap, DrawsNoEllipseForWhatIsNoCovariance) {
  const Scenario scenario = TestScenario();
  Report report = TestReport(scenario);
  report.fires[0].covariance_ne_m2 = std::array<double, 3>{1.0, 2.0, 1.0};  // eigenvalue -1
  EXPECT_TRUE(ParsedSvg(SvgMap(report, scenario)).Find("ellipse", "fused-ellipses").empty());
  report.fires[0].covariance_ne_m2 =
      std::array<double, 3>{std::numeric_limits<double>::quiet_NaN(), 0.0, 1.0};
  EXPECT_TRUE(ParsedSvg(SvgMap(report, scenario)).Find("ellipse", "fused-ellipses").empty());
  // A round one is a circle: no rotation.
  report.fires[0].covariance_ne_m2 = std::array<double, 3>{9.0, 0.0, 9.0};
  const XmlDocument doc = ParsedSvg(SvgMap(report, scenario));
  const auto ellipses = doc.Find("ellipse", "fused-ellipses");
  ASSERT_EQ(ellipses.size(), 1U);
  EXPECT_EQ(ellipses[0]->Attribute("rx"), ellipses[0]->Attribute("ry"));
  EXPECT_NEAR(Number(*ellipses[0], "rx"), 6.0 * PxPerMetre(doc), 0.08);
  EXPECT_EQ(ellipses[0]->Attribute("transform"), "");
}

TEST(SvgMap, TrackThatTurnsBackKeepsItsFarEnd) {
  const Scenario scenario = TestScenario();
  Report report = TestReport(scenario);
  // Out 200 m east and back along the same line, then hovering at the start.
  std::vector<common::LatLon>& track = report.vehicles[1].track;
  track.clear();
  for (int m = 0; m <= 200; m += 10) track.push_back(At(scenario, -100.0 + m, -120.0));
  for (int m = 200; m >= 0; m -= 10) track.push_back(At(scenario, -100.0 + m, -120.0));
  for (int i = 0; i < 10; ++i) track.push_back(At(scenario, -100.0 + 0.01 * i, -120.0));
  const XmlDocument doc = ParsedSvg(SvgMap(report, scenario));
  const XmlElement* path = doc.ById("track-1");
  ASSERT_NE(path, nullptr);
  std::string d = path->Attribute("d");
  std::replace_if(
      d.begin(), d.end(), [](char c) { return c == 'M' || c == 'L'; }, ' ');
  std::istringstream numbers(d);
  std::vector<double> xs;
  double x = 0.0;
  double y = 0.0;
  while (numbers >> x >> y) xs.push_back(x);
  ASSERT_EQ(xs.size(), 3U) << path->Attribute("d");
  EXPECT_NEAR(xs[1] - xs[0], 200.0 * PxPerMetre(doc), 0.5);
  EXPECT_NEAR(xs[2], xs[0], 0.11);
}

TEST(SvgMap, ScaleBarIsARoundLength) {
  const Scenario scenario = TestScenario();
  const XmlDocument doc = ParsedSvg(SvgMap(TestReport(scenario), scenario));
  ASSERT_NE(doc.ById("scale-bar-label"), nullptr);
  const std::string label = doc.ById("scale-bar-label")->text;
  EXPECT_THAT(label, testing::MatchesRegex("[125]0* k?m"));
  // At most a quarter of the map's width, at least a tenth.
  const double bar_px = PxPerMetre(doc) * std::stod(label);
  const XmlElement* frame = doc.ById("map-frame");
  ASSERT_NE(frame, nullptr);
  EXPECT_LE(bar_px, 0.25 * Number(*frame, "width") + 0.1);
  EXPECT_GE(bar_px, 0.1 * Number(*frame, "width"));
}

}  // namespace
}  // namespace fireswarm::run
