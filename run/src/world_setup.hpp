// The simulated world of a scenario: sim2d's configuration (origin, fire grid,
// fires, distractors, wind, faults, vehicles at their stands with their cameras)
// and the truth the scorer compares against. Private to the runner.
#pragma once

#include <map>
#include <vector>

#include "fireswarm/run/scenario.hpp"
#include "fireswarm/server/mission_manager.hpp"
#include "fireswarm/sim2d/simulation.hpp"

namespace fireswarm::run::internal {

/// The scenario's fires, explicit ones first, then `random_fires` placed uniformly
/// inside the search area (area minus no-fly zones) by rejection sampling with a
/// std::mt19937_64 seeded with its seed. Throws ScenarioError when the area is too
/// thin to place them (no point found after many draws).
std::vector<FireSpec> ExpandFires(const Scenario& scenario);

/// Where each vehicle stands at launch, local ENU metres (the area's frame): on a
/// ring around its own launch site (`sites`, the plan's DronePlan::launch by
/// receiver ID; a drone not in it stands at the fleet's first site), at least
/// fleet.stand_spacing_m apart (20 m by default) from the site's other drones,
/// each in the direction of its first waypoint so that climb-outs run radially
/// outward and never cross; a site's only drone stands on it. Keyed by receiver ID.
std::map<int, sim2d::Vec2> StandPositions(const Scenario& scenario,
                                          const std::vector<server::DroneMission>& missions,
                                          const std::map<std::uint8_t, common::EastNorth>& sites);

/// Altitude layers: the k-th drone (in mission order) flies every waypoint
/// kAltitudeLayerM * (k % kAltitudeLayers) above the fleet's altitude, so two
/// drones whose transits, investigations or returns cross never share an altitude
/// band (sim2d counts contacts only when bands overlap). Going higher only widens
/// the camera footprint, so the planner's lanes still overlap.
///
/// Each sortie then ends with a return waypoint over its last one at the drone's
/// own return altitude, kReturnLayerM * k above the fleet's altitude, so every
/// drone flies home at an altitude of its own: the sorties end together and the
/// returns converge on neighbouring stands (a vehicle returns at the altitude it
/// was flying to, agents' return to launch).
/// 5 m: a vehicle's altitude hold wanders about +-2 m around its target (sim2d's
/// baro noise and gusts; swarm20 showed drones of neighbouring 3 m layers 0.9 m
/// apart where two sorties met at a cut in their lanes).
inline constexpr int kAltitudeLayers = 3;
inline constexpr double kAltitudeLayerM = 5.0;
/// The spacing of the return altitudes (kReturnLayerM * k above the fleet's).
inline constexpr double kReturnLayerM = 3.0;
std::vector<server::DroneMission> InAltitudeLayers(std::vector<server::DroneMission> missions);

/// sim2d's configuration: world origin = the area frame's origin, the fire grid
/// over the area's bounding box plus a margin, `fires` as ignitions over their
/// radius, distractors, wind, sim2d faults (every kind but radio_silent, which the
/// runner applies to the radio), vehicles at `stands` with the fleet's camera.
sim2d::SimulationConfig MakeSimulationConfig(const Scenario& scenario,
                                             const std::vector<FireSpec>& fires,
                                             const std::map<int, sim2d::Vec2>& stands);

}  // namespace fireswarm::run::internal
