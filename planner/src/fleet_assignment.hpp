// Which drone flies which sortie: drones spread over the launch sites, sortie
// units given to drones so that the fleet finishes together.
#pragma once

#include <optional>
#include <vector>

namespace fireswarm::planner {

struct Assignment {
  std::vector<std::size_t> drone_site;                ///< per drone: index of its site
  std::vector<std::vector<std::size_t>> drone_units;  ///< per drone: its units in flying order
  double makespan_s = 0.0;
};

/// Assigns `units` (unit_site_s[u][k]: the sortie time of unit u flown from site
/// k) to `drones` drones. The drones per site are `site_drones` when given, else
/// found by a local search that starts from the sites' shares of the work (each
/// unit counted at its quickest site). Units go to drones longest first, each to
/// the drone that would finish it earliest (a swap of `swap_s` before every sortie
/// but a drone's first; a site whose sortie exceeds `endurance_s` cannot take it),
/// then units move between drones while that lowers the makespan. Empty when some
/// unit fits no drone's site.
std::optional<Assignment> AssignUnits(const std::vector<std::vector<double>>& unit_site_s,
                                      std::size_t drones, const std::vector<int>& site_drones,
                                      double endurance_s, double swap_s);

}  // namespace fireswarm::planner
