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

/// sim2d's configuration: world origin = the area frame's origin, the fire grid
/// over the area's bounding box plus a margin, `fires` as ignitions over their
/// radius, distractors, wind, sim2d faults (every kind but radio_silent, which the
/// runner applies to the radio), vehicles at `stands` with the fleet's camera.
sim2d::SimulationConfig MakeSimulationConfig(const Scenario& scenario,
                                             const std::vector<FireSpec>& fires,
                                             const std::map<int, sim2d::Vec2>& stands);

}  // namespace fireswarm::run::internal
