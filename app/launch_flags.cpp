#include "launch_flags.hpp"

#include <optional>

#include "cli.hpp"
#include "fireswarm/common/local_frame.hpp"

namespace fireswarm::app {

void CheckLaunchFlags(const std::string& command, const std::vector<std::string>& launch,
                      const std::string& launch_file) {
  if (!launch.empty() && !launch_file.empty()) {
    ThrowBadFlag(command, "launch-file", "not given with --launch (both give launch sites)",
                 launch_file);
  }
  for (const std::string& text : launch) {
    if (!ParseLatLon(text)) {
      ThrowBadFlag(command, "launch", "'lat,lon' in degrees (lat in [-90, 90], lon in [-180, 180])",
                   text);
    }
  }
}

void SetLaunchSites(const std::string& command, const std::vector<std::string>& launch,
                    const std::string& launch_file, const planner::SearchArea& area,
                    planner::FleetSpec& fleet) {
  CheckLaunchFlags(command, launch, launch_file);
  const auto local = [&area](const common::LatLon& position) {
    const common::EastNorth en = area.frame.ToLocal(position);
    return planner::Point{en.east_m, en.north_m};
  };
  fleet.launch_points.clear();
  fleet.site_drones.clear();
  if (!launch_file.empty()) {
    const planner::LaunchSites sites = planner::LoadLaunchSites(launch_file);
    for (const common::LatLon& position : sites.positions) {
      fleet.launch_points.push_back(local(position));
    }
    fleet.site_drones = sites.drones;
    return;
  }
  for (const std::string& text : launch) fleet.launch_points.push_back(local(*ParseLatLon(text)));
  if (fleet.launch_points.empty()) fleet.launch_points.push_back(planner::DefaultLaunchPoint(area));
}

}  // namespace fireswarm::app
