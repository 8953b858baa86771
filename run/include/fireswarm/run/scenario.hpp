// The scenario file of `fireswarm run` (YAML): the area, the fleet, the radio, the
// fires and distractors, the wind, the faults and the expectations, read into one
// plain struct with every field typed and defaulted. docs/scenario.md is the
// reference for every key, its unit, default and valid range.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "fireswarm/common/camera_model.hpp"
#include "fireswarm/common/local_frame.hpp"
#include "fireswarm/planner/plan.hpp"
#include "fireswarm/radio/discipline.hpp"
#include "fireswarm/radio/frame.hpp"
#include "fireswarm/server/traffic.hpp"

namespace fireswarm::run {

/// Bad scenario input. The message is `<file>:<line>:<column>: <key path>: <problem>`
/// (line and column 1-based, from the YAML node at fault; left out when there is no
/// node, e.g. an unreadable file), e.g.
/// `demo.yaml:7:10: fleet.count: must be in [1, 254], got 300`.
/// `fireswarm run` turns it into exit code 2.
class ScenarioError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// What a fault does to one vehicle, to the server or to the radio. The first six
/// are sim2d's FaultKind (sim2d/faults.hpp), by the same names, and kGpsLoss is
/// sim2d's stream cut of the GPS; kRadioSilent has no sim2d counterpart: the
/// runner stops carrying the vehicle's radio bytes both ways for the window.
/// kServerRestart is the server's and kRadioBurst the radio channel's: they
/// concern no vehicle. kVehicleReboot restarts one vehicle's software.
enum class FaultKind : std::uint8_t {
  kStreamCut,    ///< "stream_cut": the sensor delivers nothing
  kFrozen,       ///< "frozen": the sensor repeats its last value
  kBias,         ///< "bias": `bias` is added to the sensor's values
  kExtraNoise,   ///< "extra_noise": the sensor's noise std is multiplied by `noise_factor`
  kBallast,      ///< "ballast": the centre of mass moves by `ballast_offset_m`
  kTotalLoss,    ///< "total_loss": the vehicle is gone for good at `at_s` (no duration)
  kRadioSilent,  ///< "radio_silent": the vehicle neither hears nor is heard
  /// "server_restart": the server dies at `at_s` and a new one takes over after
  /// `duration_s` (0: at once), restored from the old one's journal as
  /// `fireswarm serve --journal` would be
  kServerRestart,
  /// "vehicle_reboot": the vehicle's software restarts: down for `duration_s`
  /// (kDefaultRebootS), then a new Vehicle reloads its non-volatile storage
  kVehicleReboot,
  /// "gps_loss": the GPS delivers nothing for `duration_s` (sim2d's stream cut)
  kGpsLoss,
  /// "radio_burst": every reception on every radio channel is lost with
  /// probability `loss` for `duration_s`
  kRadioBurst,
};

/// The sensor a sensor fault (stream_cut, frozen, bias, extra_noise) acts on;
/// sim2d's SensorKind by name.
enum class FaultSensor : std::uint8_t { kGps, kBaro, kAttitude, kBattery };

/// The scenario names: "stream_cut", "gps", ...
std::string_view ToString(FaultKind kind);
std::string_view ToString(FaultSensor sensor);
/// "lawnmower" or "ompl".
std::string_view ToString(planner::PlannerKind kind);

/// Receiver IDs a fleet may use: 1..254 (0 is the server, 255 broadcast).
inline constexpr int kMinReceiverId = 1;
inline constexpr int kMaxReceiverId = radio::kBroadcastId - 1;

/// Defaults that have no owner elsewhere. The fleet's and the radio's below equal
/// planner::FleetSpec's and radio::ChannelConfig's / radio::SchedulerConfig's (a
/// test in tests/run/scenario_test.cpp keeps them equal).
inline constexpr std::uint64_t kDefaultSeed = 1;
inline constexpr double kDefaultDurationS = 3'600.0;
inline constexpr double kDefaultFireRadiusM = 10.0;
inline constexpr double kDefaultRandomFireSpacingM = 70.0;  ///< twice the fusion's 35 m gate
inline constexpr double kDefaultDistractorRadiusM = 5.0;    ///< sim2d::Distractor's
inline constexpr double kDefaultDistractorTempC = 55.0;     ///< sim2d::Distractor's
inline constexpr std::string_view kDefaultCamera = "seed";
/// Stands at the launch site are at least this far apart (centre to centre), m:
/// each vehicle holds its GPS position while it climbs and lands on the GPS
/// position it took off from, and its GPS bias (2.5 m CEP, agents::GeolocationSigmas)
/// has wandered by then: swarm20's vehicles landed up to 8.5 m off their stands
/// (3.2 m median, 16 seeds), so two neighbours landing together need ~20 m (10 m
/// let them close to 1.5 m; docs/scenario.md).
inline constexpr double kDefaultStandSpacingM = 20.0;
/// How long a rebooting vehicle's autopilot is down by default, s: a small
/// autopilot's boot to its first control step (a bootloader, the firmware's
/// start, the sensors' first samples).
inline constexpr double kDefaultRebootS = 2.0;
/// A reboot's down time may be at most this long, s: beyond it the vehicle,
/// its motors holding their last outputs, is falling out of the sky, not rebooting.
inline constexpr double kMaxRebootS = 10.0;

/// One launch site of the fleet.
struct LaunchSiteConfig {
  common::LatLon position;
  /// How many drones fly from it; nullopt: the planner shares the drones out.
  /// Given on every site or on none, summing to the fleet's count.
  std::optional<int> drones;
};

struct FleetConfig {
  int count = 0;     ///< drones, 1..254 (required)
  int first_id = 1;  ///< receiver IDs are first_id .. first_id + count - 1 <= 254
  /// The first launch site (vehicles stand a few metres apart around theirs).
  /// When the file gives none: planner::DefaultLaunchPoint of the area, and
  /// launch_given false.
  common::LatLon launch;
  bool launch_given = false;
  /// Every launch site, `launch` first; one at least after loading (`fleet.launch`
  /// is one {lat, lon} or a list of {lat, lon, drones}).
  std::vector<LaunchSiteConfig> launch_sites;
  /// On the ground between two sorties: landing, battery swap, take-off, s. The
  /// planner counts it; the simulator's ground crew puts a full pack in this long
  /// after each landing.
  double swap_s = 300.0;
  const common::CameraModel* camera = nullptr;  ///< never null after loading
  double camera_pitch_deg = -90.0;              ///< from the horizon, -90 straight down
  double altitude_m = 60.0;                     ///< above ground
  double speed_mps = 10.0;                      ///< cruise
  double endurance_s = 1'800.0;                 ///< flight time per sortie
  planner::PlannerKind planner = planner::PlannerKind::kLawnmower;
  /// Smallest distance between two vehicles' stands around the launch site, m.
  double stand_spacing_m = kDefaultStandSpacingM;

  /// first_id, first_id + 1, ..., first_id + count - 1.
  std::vector<int> ReceiverIds() const;
};

struct RadioConfig {
  int baud = 57'600;           ///< bits/s, 8N1 framing
  double turnaround_ms = 5.0;  ///< receive-to-transmit switch time of every radio
  double loss = 0.0;           ///< probability a transmission is lost for one receiver
  /// secure (default): AES-256-GCM under simulation keys derived from the seed
  /// (radio/simulation_keys.hpp); xor and crc16 as on the seed's board.
  radio::ChecksumMode checksum = radio::ChecksumMode::kSecure;
  radio::LinkMode mode = radio::LinkMode::kSlots;
  /// Radio channels (separate frequencies, one modem each at the server), 1..16.
  int channels = 1;
  /// One channel unlike the others: `channel` (0-based) with its own baud,
  /// turnaround or loss (unset: the radio's), and the vehicles fixed on it (the
  /// others are spread over the channels in balanced groups by the server).
  struct ChannelOverride {
    int channel = 0;
    std::optional<int> baud;
    std::optional<double> turnaround_ms;
    std::optional<double> loss;
    std::vector<int> vehicles;  ///< receiver IDs
  };
  std::vector<ChannelOverride> channel_overrides;
  /// Channel `channel`'s baud, turnaround and loss with its override applied.
  RadioConfig ChannelAt(int channel) const;
};

/// A fire that starts at a given place and time.
struct FireSpec {
  common::LatLon position;
  double start_s = 0.0;                   ///< simulated time of ignition
  double radius_m = kDefaultFireRadiusM;  ///< burning radius at ignition
};

/// `count` fires at t = 0, placed by the runner uniformly inside the search area
/// (area minus no-fly zones) from its own generator seeded with `seed`. Kept as a
/// spec: the loader does not expand it.
struct RandomFiresSpec {
  int count = 0;
  std::uint64_t seed = kDefaultSeed;  ///< defaults to the scenario's seed
  double radius_m = kDefaultFireRadiusM;
  /// Least distance between two fires' centres (random ones and those of
  /// `fires`), m: the server's fusion takes reports less than its 35 m gate
  /// apart for one fire (server::FireFusionConfig::min_gate_m), so closer fires
  /// would be scored as one found and one missed.
  double min_spacing_m = kDefaultRandomFireSpacingM;
};

/// A hot patch that is not fire (sun-heated rock): a disc at a fixed temperature.
struct DistractorSpec {
  common::LatLon position;
  double radius_m = kDefaultDistractorRadiusM;
  double temp_c = kDefaultDistractorTempC;
};

struct WindSpec {
  double speed_mps = 0.0;
  double from_deg = 0.0;  ///< where it blows from, clockwise from true north, [0, 360)
};

/// One fault of one vehicle (or of the server, or the radio), active for
/// at_s <= t < at_s + duration_s.
struct FaultSpec {
  int vehicle = 0;  ///< receiver ID, one of the fleet's; 0 for kServerRestart, kRadioBurst
  double at_s = 0.0;
  FaultKind kind = FaultKind::kStreamCut;
  /// inf: to the end. kServerRestart: its down time, 0 (at once) unless given;
  /// kVehicleReboot: kDefaultRebootS unless given.
  double duration_s = std::numeric_limits<double>::infinity();
  FaultSensor sensor = FaultSensor::kGps;  ///< sensor faults only
  /// kBias, per sensor: GPS (east_m, north_m, up_m); baro (altitude_m, -, -);
  /// attitude (roll_rad, pitch_rad, heading_rad); battery (voltage_v, -, -).
  std::array<double, 3> bias{0.0, 0.0, 0.0};
  double noise_factor = 1.0;                         ///< kExtraNoise: > 1
  std::array<double, 2> ballast_offset_m{0.0, 0.0};  ///< kBallast: (forward_m, right_m)
  double loss = 0.0;  ///< kRadioBurst: probability in (0, 1] a reception is lost
};

/// Assertions checked against the report; an absent one is not checked.
struct Expectations {
  std::optional<double> all_fires_confirmed_within_s;
  std::optional<double> max_fused_error_m;
  bool no_collisions = false;          ///< true: any collision fails the run
  std::optional<double> min_coverage;  ///< fraction 0..1 of the search area seen
  std::optional<int> max_false_tracks;
  /// The report's min_separation_m (3D, between two vehicles while one of them
  /// flies) is at least this, m; holds when none was measured (e.g. a single vehicle).
  std::optional<double> min_separation_m;
  /// Fire reports the vehicles queued that never reached the server (the
  /// report's radio.reports_lost) number at most this.
  std::optional<int> max_reports_lost;
  /// Collisions number at least this: for scenarios built to collide, which
  /// check that the collision is seen and reported.
  std::optional<int> min_collisions;
};

/// A whole scenario, checked and defaulted (see docs/scenario.md).
/// `patrol`: the search flown again and again (a watch over the forest).
struct PatrolSpec {
  /// The next round starts this long after the last one started, s, or as soon as
  /// that one is over when it took longer.
  double every_s = 0.0;
};

struct Scenario {
  std::string source;  ///< the file name errors carry
  std::string name;    ///< defaults to the file's stem
  std::uint64_t seed = kDefaultSeed;
  double duration_s = kDefaultDurationS;  ///< simulated-time limit of the run
  /// The area and no-fly zones, projected to the area's local frame.
  planner::SearchArea area;
  /// The GeoJSON files read, resolved against the scenario's directory (empty
  /// when given inline).
  std::optional<std::filesystem::path> area_geojson;
  std::optional<std::filesystem::path> no_fly_geojson;
  FleetConfig fleet;
  RadioConfig radio;
  /// `separation`: the limit, the altitude layers and the tactical watch
  /// (server::SeparationConfig; its defaults when absent).
  server::SeparationConfig separation;
  std::vector<FireSpec> fires;
  std::optional<RandomFiresSpec> random_fires;
  std::vector<DistractorSpec> distractors;
  WindSpec wind;
  /// Absent: one mission, and the run may end when it is over. Present: round
  /// after round until duration_s.
  std::optional<PatrolSpec> patrol;
  std::vector<FaultSpec> faults;
  Expectations expect;
};

/// Parses scenario YAML `text`. `source_name` prefixes every error message (normally
/// the file name); relative GeoJSON paths are resolved against `base_dir`.
/// Throws ScenarioError on malformed YAML, a missing required key (area,
/// fleet.count), a value of the wrong type or out of range, an unknown key (naming
/// the nearest valid one), an unknown name (listing the valid ones), a GeoJSON file
/// that is missing or invalid, or a fire outside the search area.
Scenario ParseScenario(std::string_view text, const std::string& source_name,
                       const std::filesystem::path& base_dir);

/// Reads and parses the scenario file at `path` (errors carry `path` as given).
/// Throws ScenarioError as ParseScenario, and when the file cannot be read.
Scenario LoadScenario(const std::filesystem::path& path);

/// The planner's view of the fleet: receiver IDs, the launch sites in the area's
/// local frame (with their drone counts when the file gives them), altitude,
/// speed, endurance, swap time and camera; the planner's own defaults for the rest.
planner::FleetSpec MakeFleetSpec(const Scenario& scenario);

}  // namespace fireswarm::run
