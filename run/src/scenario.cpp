// The scenario file's top level, fleet, radio, wind and expectations; the area is
// read in scenario_area.cpp, fires, distractors and faults in scenario_events.cpp.
#include "fireswarm/run/scenario.hpp"

#include <yaml-cpp/yaml.h>

#include <array>
#include <sstream>
#include <stdexcept>

#include "fireswarm/planner/area_io.hpp"
#include "scenario_parts.hpp"

namespace fireswarm::run {
namespace {

using internal::Field;
using internal::Mapping;
using internal::Range;

constexpr std::array<std::string_view, 2> kPlannerNames{"lawnmower", "ompl"};
constexpr std::array<planner::PlannerKind, 2> kPlannerKinds{planner::PlannerKind::kLawnmower,
                                                            planner::PlannerKind::kOmpl};

// The names of a radio enum, from the radio module's own ToString (one spelling).
template <typename Enum, std::size_t N>
std::array<std::string_view, N> RadioNames(const std::array<Enum, N>& values) {
  std::array<std::string_view, N> names{};
  for (std::size_t i = 0; i < N; ++i) names[i] = radio::ToString(values[i]);
  return names;
}
constexpr std::array<radio::ChecksumMode, 3> kChecksumModes{
    radio::ChecksumMode::kXor, radio::ChecksumMode::kCrc16, radio::ChecksumMode::kSecure};
constexpr std::array<radio::LinkMode, 2> kLinkModes{radio::LinkMode::kPoll,
                                                    radio::LinkMode::kSlots};

common::LatLon DefaultLaunch(const planner::SearchArea& area) {
  const planner::Point launch = planner::DefaultLaunchPoint(area);
  return area.frame.ToGeodetic({launch.x(), launch.y()});
}

void ReadFleetIds(const Mapping& fleet, FleetConfig& out) {
  out.count = static_cast<int>(fleet.Required("count").Integer(kMinReceiverId, kMaxReceiverId));
  out.first_id = fleet.Integer("first_id", out.first_id, kMinReceiverId, kMaxReceiverId);
  const int last_id = out.first_id + out.count - 1;
  if (last_id > kMaxReceiverId) {
    const Field at = fleet.Find("first_id").value_or(fleet.Required("count"));
    at.Fail("first_id + count - 1 = " + std::to_string(last_id) +
            " is beyond the largest receiver ID " + std::to_string(kMaxReceiverId) + " (first_id " +
            std::to_string(out.first_id) + ", count " + std::to_string(out.count) + ")");
  }
}

common::LatLon ReadSitePosition(const Field& at, const Mapping& site,
                                const planner::SearchArea& area) {
  const common::LatLon position = internal::ReadLatLon(site);
  internal::CheckNearArea(at, area, position);
  if (internal::InNoFly(area, position)) at.Fail("lies inside a no-fly zone");
  return position;
}

// `fleet.launch`: one {lat, lon}, or a list of sites {lat, lon, drones}.
void ReadLaunch(const Mapping& fleet, const planner::SearchArea& area, FleetConfig& out) {
  const std::optional<Field> launch = fleet.Find("launch");
  if (!launch) {
    out.launch = DefaultLaunch(area);
    out.launch_sites = {{out.launch, std::nullopt}};
    return;
  }
  out.launch_given = true;
  if (!launch->IsSequence()) {
    out.launch = ReadSitePosition(*launch, Mapping(*launch, {"lat", "lon"}), area);
    out.launch_sites = {{out.launch, std::nullopt}};
    return;
  }
  const std::vector<Field> sites = launch->Elements();
  if (sites.empty()) launch->Fail("lists no launch site (give one {lat, lon} at least)");
  int counted = 0;
  std::optional<Field> uncounted;
  std::optional<Field> last_count;
  for (const Field& site : sites) {
    const Mapping entry(site, {"lat", "lon", "drones"});
    LaunchSiteConfig config;
    config.position = ReadSitePosition(site, entry, area);
    if (const std::optional<Field> drones = entry.Find("drones")) {
      config.drones = static_cast<int>(drones->Integer(0, out.count));
      counted += *config.drones;
      last_count = drones;
    } else {
      uncounted = site;
    }
    out.launch_sites.push_back(config);
  }
  if (last_count && uncounted) {
    uncounted->Fail("has no drones while another site has: give drones on every site or on none");
  }
  if (last_count && counted != out.count) {
    last_count->Fail("the sites' drones sum to " + std::to_string(counted) + ", not fleet.count " +
                     std::to_string(out.count));
  }
  out.launch = out.launch_sites.front().position;
}

void ReadCamera(const Mapping& fleet, FleetConfig& out) {
  std::vector<std::string_view> names;
  for (const common::CameraModel& model : common::CameraModels()) names.push_back(model.name);
  const std::optional<Field> camera = fleet.Find("camera");
  out.camera = common::FindCameraModel(camera ? names[camera->OneOf(names)] : kDefaultCamera);
  // The planner needs a footprint: the camera must look below the horizon.
  const std::optional<Field> pitch = fleet.Find("camera_pitch_deg");
  if (pitch) out.camera_pitch_deg = pitch->Number(Range{-90.0, 0.0, false, true});
  try {
    common::ValidateCamera(*out.camera, out.camera_pitch_deg, "fleet");
  } catch (const std::invalid_argument& e) {
    (pitch ? *pitch : fleet.field()).Fail(e.what());
  }
}

FleetConfig ReadFleet(const Mapping& root, const planner::SearchArea& area) {
  const Mapping fleet(root.Required("fleet"),
                      {"count", "first_id", "launch", "camera", "camera_pitch_deg", "altitude_m",
                       "speed_mps", "endurance_s", "swap_s", "planner", "stand_spacing_m"});
  FleetConfig out;
  ReadFleetIds(fleet, out);
  ReadLaunch(fleet, area, out);
  ReadCamera(fleet, out);
  out.altitude_m =
      fleet.Number("altitude_m", out.altitude_m, Range{0.0, internal::kMaxAltitudeM, true});
  out.speed_mps =
      fleet.Number("speed_mps", out.speed_mps, Range{0.0, internal::kMaxSpeedMps, true});
  out.endurance_s =
      fleet.Number("endurance_s", out.endurance_s, Range{0.0, internal::kMaxEnduranceS, true});
  out.swap_s = fleet.Number("swap_s", out.swap_s, Range{0.0, internal::kMaxSwapS, true});
  if (const std::optional<Field> planner = fleet.Find("planner")) {
    out.planner = kPlannerKinds.at(planner->OneOf(kPlannerNames));
  }
  out.stand_spacing_m =
      fleet.Number("stand_spacing_m", out.stand_spacing_m,
                   Range{internal::kMinStandSpacingM, internal::kMaxStandSpacingM});
  return out;
}

RadioConfig ReadRadio(const Mapping& root) {
  RadioConfig out;
  const std::optional<Field> field = root.Find("radio");
  if (!field) return out;
  const Mapping radio(*field, {"baud", "turnaround_ms", "loss", "checksum", "mode", "channels",
                               "channel_overrides"});
  out.baud = radio.Integer("baud", out.baud, 1, internal::kMaxBaud);
  out.turnaround_ms =
      radio.Number("turnaround_ms", out.turnaround_ms, Range{0.0, internal::kMaxTurnaroundMs});
  out.loss = radio.Number("loss", out.loss, Range{0.0, 1.0});
  if (const std::optional<Field> checksum = radio.Find("checksum")) {
    const auto names = RadioNames(kChecksumModes);
    out.checksum = radio::ParseChecksumMode(names[checksum->OneOf(names)]).value();
  }
  if (const std::optional<Field> mode = radio.Find("mode")) {
    const auto names = RadioNames(kLinkModes);
    out.mode = radio::ParseLinkMode(names[mode->OneOf(names)]).value();
  }
  internal::ReadChannels(radio, out);
  return out;
}

server::SeparationConfig ReadSeparation(const Mapping& root) {
  server::SeparationConfig out;
  const std::optional<Field> field = root.Find("separation");
  if (!field) return out;
  const Mapping separation(*field, {"separation_m", "layer_m", "search_layers", "transit_sectors",
                                    "transit_min_m", "horizon_s", "resolve", "layers",
                                    "sequence_takeoffs", "max_altitude_m", "min_altitude_m"});
  const Range positive{0.0, 10'000.0, true};
  out.separation_m = separation.Number("separation_m", out.separation_m, positive);
  out.layer_m = separation.Number("layer_m", out.layer_m, positive);
  out.search_layers = separation.Integer("search_layers", out.search_layers, 1, 10);
  out.transit_sectors = separation.Integer("transit_sectors", out.transit_sectors, 1, 12);
  out.transit_min_m = separation.Number("transit_min_m", out.transit_min_m, positive);
  out.horizon_s = separation.Number("horizon_s", out.horizon_s, Range{0.0, 600.0, true});
  if (const auto f = separation.Find("resolve")) out.resolve = f->Bool();
  if (const auto f = separation.Find("layers")) out.layers = f->Bool();
  if (const auto f = separation.Find("sequence_takeoffs")) out.sequence_takeoffs = f->Bool();
  out.max_altitude_m = separation.Number("max_altitude_m", out.max_altitude_m, positive);
  out.min_altitude_m =
      separation.Number("min_altitude_m", out.min_altitude_m, Range{0.0, 10'000.0});
  if (!(out.min_altitude_m < out.max_altitude_m)) {
    field->Fail("min_altitude_m (" + std::to_string(out.min_altitude_m) +
                ") must be below max_altitude_m (" + std::to_string(out.max_altitude_m) + ")");
  }
  return out;
}

WindSpec ReadWind(const Mapping& root) {
  WindSpec out;
  const std::optional<Field> field = root.Find("wind");
  if (!field) return out;
  const Mapping wind(*field, {"speed_mps", "from_deg"});
  out.speed_mps = wind.Number("speed_mps", out.speed_mps, Range{0.0, internal::kMaxWindMps});
  out.from_deg =
      wind.Number("from_deg", out.from_deg, Range{0.0, internal::kFullCircleDeg, false, true});
  return out;
}

std::optional<PatrolSpec> ReadPatrol(const Mapping& root) {
  const std::optional<Field> field = root.Find("patrol");
  if (!field) return std::nullopt;
  const Mapping patrol(*field, {"every_s"});
  PatrolSpec out;
  out.every_s =
      patrol.Required("every_s").Number(Range{internal::kMinPatrolEveryS, internal::kMaxDurationS});
  return out;
}

double ReadMinCoverage(const Field& field) {
  const double value = field.Number();
  // A percentage is the likely mistake: say so.
  if (value > 1.0 && value <= 100.0) {
    std::ostringstream fraction;
    fraction << value / 100.0;
    field.Fail("is a fraction in [0, 1], got " + field.node().Scalar() + " (did you mean " +
               fraction.str() + "?)");
  }
  return field.Number(Range{0.0, 1.0});
}

Expectations ReadExpect(const Mapping& root) {
  Expectations out;
  const std::optional<Field> field = root.Find("expect");
  if (!field) return out;
  const Mapping expect(
      *field, {"all_fires_confirmed_within_s", "max_fused_error_m", "no_collisions", "min_coverage",
               "max_false_tracks", "min_separation_m", "max_reports_lost", "min_collisions"});
  const Range positive{0.0, internal::kUnbounded, true};
  if (const auto f = expect.Find("all_fires_confirmed_within_s")) {
    out.all_fires_confirmed_within_s = f->Number(positive);
  }
  if (const auto f = expect.Find("max_fused_error_m")) out.max_fused_error_m = f->Number(positive);
  if (const auto f = expect.Find("no_collisions")) out.no_collisions = f->Bool();
  if (const auto f = expect.Find("min_coverage")) out.min_coverage = ReadMinCoverage(*f);
  if (const auto f = expect.Find("max_false_tracks")) {
    out.max_false_tracks = static_cast<int>(f->Integer(0, internal::kMaxFalseTracks));
  }
  if (const auto f = expect.Find("min_separation_m")) out.min_separation_m = f->Number(positive);
  if (const auto f = expect.Find("max_reports_lost")) {
    out.max_reports_lost = static_cast<int>(f->Integer(0, internal::kMaxReportsLost));
  }
  // At least one: "at least 0 collisions" would check nothing.
  if (const auto f = expect.Find("min_collisions")) {
    out.min_collisions = static_cast<int>(f->Integer(1, internal::kMaxCollisions));
    if (out.no_collisions) f->Fail("contradicts no_collisions: true (both can never hold)");
  }
  return out;
}

}  // namespace

std::string_view ToString(planner::PlannerKind kind) {
  for (std::size_t i = 0; i < kPlannerKinds.size(); ++i) {
    if (kPlannerKinds[i] == kind) return kPlannerNames[i];
  }
  return "unknown";
}

std::vector<int> FleetConfig::ReceiverIds() const {
  std::vector<int> ids;
  for (int i = 0; i < count; ++i) ids.push_back(first_id + i);
  return ids;
}

Scenario ParseScenario(std::string_view text, const std::string& source_name,
                       const std::filesystem::path& base_dir) {
  const YAML::Node document = internal::LoadYaml(text, source_name);
  const Field top(source_name, document, "");
  if (!document.IsMap()) {
    throw ScenarioError(source_name +
                        ": the scenario must be a YAML mapping of keys (name, area, fleet, ...)");
  }
  const Mapping root(
      top, {"name", "seed", "duration_s", "area", "no_fly", "fleet", "radio", "separation", "fires",
            "random_fires", "distractors", "wind", "patrol", "faults", "expect"});
  Scenario scenario;
  scenario.source = source_name;
  const std::optional<Field> name = root.Find("name");
  scenario.name = name ? name->Text() : std::filesystem::path(source_name).stem().string();
  if (const std::optional<Field> seed = root.Find("seed")) scenario.seed = seed->Unsigned64();
  scenario.duration_s =
      root.Number("duration_s", scenario.duration_s, Range{0.0, internal::kMaxDurationS, true});
  internal::ReadArea(root, base_dir, scenario);
  scenario.fleet = ReadFleet(root, scenario.area);
  scenario.radio = ReadRadio(root);
  scenario.separation = ReadSeparation(root);
  scenario.wind = ReadWind(root);
  scenario.patrol = ReadPatrol(root);
  internal::ReadEvents(root, scenario);
  scenario.expect = ReadExpect(root);
  return scenario;
}

Scenario LoadScenario(const std::filesystem::path& path) {
  return ParseScenario(internal::ReadConfigFile(path, "scenario file"), path.string(),
                       path.parent_path());
}

planner::FleetSpec MakeFleetSpec(const Scenario& scenario) {
  const FleetConfig& fleet = scenario.fleet;
  planner::FleetSpec spec;
  spec.receiver_ids = fleet.ReceiverIds();
  for (const LaunchSiteConfig& site : fleet.launch_sites) {
    const common::EastNorth launch = scenario.area.frame.ToLocal(site.position);
    spec.launch_points.emplace_back(launch.east_m, launch.north_m);
    if (site.drones) spec.site_drones.push_back(*site.drones);
  }
  spec.altitude_m = fleet.altitude_m;
  spec.speed_mps = fleet.speed_mps;
  spec.endurance_s = fleet.endurance_s;
  spec.swap_s = fleet.swap_s;
  spec.camera = fleet.camera;
  spec.camera_pitch_deg = fleet.camera_pitch_deg;
  return spec;
}

}  // namespace fireswarm::run
