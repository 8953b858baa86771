// The launch-site flags that `plan` and `serve` share: --launch LAT,LON (each
// repeat one site) or --launch-file sites.geojson (Points, optional "drones").
#pragma once

#include <string>
#include <vector>

#include "fireswarm/planner/area_io.hpp"
#include "fireswarm/planner/plan.hpp"

namespace fireswarm::app {

/// Sets fleet.launch_points (local metres of `area`'s frame) and, when the file
/// gives them, fleet.site_drones from the flags; without either, the area's
/// default site (planner::DefaultLaunchPoint). Throws UsageError naming
/// `command` and the flag for a LAT,LON that is not one, or both flags given;
/// planner::LoadLaunchSites' errors name the file and feature.
void SetLaunchSites(const std::string& command, const std::vector<std::string>& launch,
                    const std::string& launch_file, const planner::SearchArea& area,
                    planner::FleetSpec& fleet);

/// Checks the flags' text before any file is read: every --launch a LAT,LON, and
/// not both flags. Throws UsageError as SetLaunchSites.
void CheckLaunchFlags(const std::string& command, const std::vector<std::string>& launch,
                      const std::string& launch_file);

}  // namespace fireswarm::app
