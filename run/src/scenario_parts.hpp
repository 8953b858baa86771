// The scenario loader's parts, shared by scenario.cpp (top level, fleet, radio,
// wind, expectations), scenario_area.cpp (area, no-fly zones, positions) and
// scenario_events.cpp (fires, distractors, faults). Private to the run library.
#pragma once

#include <filesystem>
#include <limits>

#include "fireswarm/run/scenario.hpp"
#include "yaml_field.hpp"

namespace fireswarm::run::internal {

/// Sanity limits: beyond them a value is more likely a unit mistake than a plan.
inline constexpr double kMaxDurationS = 86'400.0;  // one day of simulated time
/// A patrol round more often than once a minute could not even take off.
inline constexpr double kMinPatrolEveryS = 60.0;
/// A server down longer than this (server_restart's duration_s) is no longer a
/// restart: every vehicle has long returned for its lost link.
inline constexpr double kMaxServerDownS = 3'600.0;
/// The fleet's ranges are the planner's (planner/plan.hpp, docs/limits.md). A
/// battery swap longer than an hour is more likely minutes typed as seconds.
inline constexpr double kMaxAltitudeM = planner::kMaxAltitudeM;
inline constexpr double kMaxSpeedMps = planner::kMaxSpeedMps;
inline constexpr double kMaxEnduranceS = planner::kMaxEnduranceS;
inline constexpr double kMaxSwapS = planner::kMaxSwapS;
/// Stands closer than this would nearly put two parked vehicles' rotor discs
/// (sim2d: 0.25 m radius) into each other.
inline constexpr double kMinStandSpacingM = 1.0;
inline constexpr double kMaxStandSpacingM = 100.0;
inline constexpr int kMaxBaud = 10'000'000;
inline constexpr double kMaxTurnaroundMs = 1'000.0;
inline constexpr double kMaxFireRadiusM = 1'000.0;
inline constexpr double kMaxFireSpacingM = 10'000.0;
inline constexpr int kMaxRandomFires = 1'000;
inline constexpr double kMaxDistractorRadiusM = 1'000.0;
inline constexpr double kMinDistractorTempC = -50.0;
/// The simulator's distractors are sun-heated ground, not fire: it refuses one
/// above 200 °C (sim2d's temperature field), so the loader does, naming the key.
inline constexpr double kMaxDistractorTempC = 200.0;
inline constexpr double kMaxWindMps = 50.0;
inline constexpr double kFullCircleDeg = 360.0;
inline constexpr double kMaxNoiseFactor = 1'000.0;
inline constexpr double kMaxBallastOffsetM = 1.0;
/// A sensor bias beyond this (m, rad or V, per sensor) is no longer a bias: a
/// GPS offset past the area's sane extent (planner::kMaxDistanceFromOriginM).
inline constexpr double kMaxBias = 200'000.0;
inline constexpr int kMaxFalseTracks = 1'000'000;
inline constexpr int kMaxReportsLost = 1'000'000;
inline constexpr int kMaxCollisions = 1'000'000;

/// For open-ended ranges: Range{0.0, kUnbounded, true} is "> 0".
inline constexpr double kUnbounded = std::numeric_limits<double>::infinity();

inline constexpr Range kLatitudeRange{-90.0, 90.0};
inline constexpr Range kLongitudeRange{-180.0, 180.0};

/// Reads `channels` and `channel_overrides` of the `radio` mapping into `out`.
void ReadChannels(const Mapping& radio, RadioConfig& out);

/// `lat` and `lon` of `mapping`, both required, in range.
common::LatLon ReadLatLon(const Mapping& mapping);

/// Reads `area` (required) and `no_fly` of the top-level mapping into
/// scenario.area, area_geojson and no_fly_geojson, GeoJSON paths resolved against
/// `base_dir`, through planner::ParseSearchArea.
void ReadArea(const Mapping& root, const std::filesystem::path& base_dir, Scenario& scenario);

/// Fails at `field` when `position` is farther from the area's origin than the
/// planner accepts (planner::kMaxDistanceFromOriginM).
void CheckNearArea(const Field& field, const planner::SearchArea& area, common::LatLon position);
/// True when `position` lies in the search area (area minus no-fly zones, edges included).
bool InSearchArea(const planner::SearchArea& area, common::LatLon position);
/// True when `position` lies strictly inside a no-fly zone.
bool InNoFly(const planner::SearchArea& area, common::LatLon position);

/// `fires`, `random_fires`, `distractors` and `faults`; needs area, duration_s and fleet.
void ReadEvents(const Mapping& root, Scenario& scenario);

}  // namespace fireswarm::run::internal
