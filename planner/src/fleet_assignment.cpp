#include "fleet_assignment.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace fireswarm::planner {

namespace {

constexpr int kMaxMoveRounds = 10'000;
constexpr double kGainS = 1e-6;

struct Loads {
  std::vector<double> seconds;
  std::vector<std::size_t> sorties;
  double With(std::size_t d, double t_s, double swap_s) const {
    return seconds[d] + t_s + (sorties[d] > 0 ? swap_s : 0.0);
  }
};

// Swaps a unit of the slowest drone with a shorter one of another drone (same
// sortie counts, so no swap time changes) when that lowers the larger of the two.
bool SwapOffSlowest(const std::vector<std::vector<double>>& t,
                    const std::vector<std::size_t>& drone_site, std::size_t slowest,
                    double endurance_s, Loads& loads, std::vector<std::size_t>& owner) {
  const double top_s = loads.seconds[slowest];
  double best_top_s = top_s - kGainS;
  std::size_t best_a = owner.size(), best_b = owner.size();
  for (std::size_t a = 0; a < owner.size(); ++a) {
    if (owner[a] != slowest) continue;
    for (std::size_t b = 0; b < owner.size(); ++b) {
      const std::size_t other = owner[b];
      if (other == slowest) continue;
      const double a_there = t[a][drone_site[other]], b_here = t[b][drone_site[slowest]];
      if (a_there > endurance_s || b_here > endurance_s) continue;
      const double here_s = top_s - t[a][drone_site[slowest]] + b_here;
      const double there_s = loads.seconds[other] - t[b][drone_site[other]] + a_there;
      const double new_top_s = std::max(here_s, there_s);
      if (new_top_s < best_top_s) {
        best_top_s = new_top_s;
        best_a = a;
        best_b = b;
      }
    }
  }
  if (best_a == owner.size()) return false;
  const std::size_t other = owner[best_b];
  loads.seconds[slowest] += t[best_b][drone_site[slowest]] - t[best_a][drone_site[slowest]];
  loads.seconds[other] += t[best_a][drone_site[other]] - t[best_b][drone_site[other]];
  std::swap(owner[best_a], owner[best_b]);
  return true;
}

std::optional<Assignment> Greedy(const std::vector<std::vector<double>>& t,
                                 const std::vector<std::size_t>& drone_site, double endurance_s,
                                 double swap_s) {
  const std::size_t units = t.size(), drones = drone_site.size();
  std::vector<double> quickest(units, std::numeric_limits<double>::infinity());
  for (std::size_t u = 0; u < units; ++u) {
    for (const std::size_t k : drone_site) quickest[u] = std::min(quickest[u], t[u][k]);
  }
  std::vector<std::size_t> order(units);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return quickest[a] > quickest[b]; });
  Assignment out;
  out.drone_site = drone_site;
  out.drone_units.assign(drones, {});
  Loads loads{std::vector<double>(drones, 0.0), std::vector<std::size_t>(drones, 0)};
  std::vector<std::size_t> owner(units);
  for (const std::size_t u : order) {
    std::size_t best = drones;
    double best_s = std::numeric_limits<double>::infinity();
    for (std::size_t d = 0; d < drones; ++d) {
      const double unit_s = t[u][drone_site[d]];
      if (unit_s > endurance_s) continue;
      const double finish_s = loads.With(d, unit_s, swap_s);
      if (finish_s < best_s) {
        best_s = finish_s;
        best = d;
      }
    }
    if (best == drones) return std::nullopt;
    loads.seconds[best] = best_s;
    ++loads.sorties[best];
    owner[u] = best;
  }
  // Move units off the slowest drone while that lowers the makespan.
  for (int round = 0; round < kMaxMoveRounds; ++round) {
    const auto slowest = static_cast<std::size_t>(
        std::max_element(loads.seconds.begin(), loads.seconds.end()) - loads.seconds.begin());
    const double top_s = loads.seconds[slowest];
    double best_top_s = top_s - kGainS;
    std::size_t move_u = units, move_to = drones;
    for (std::size_t u = 0; u < units; ++u) {
      if (owner[u] != slowest) continue;
      const double left_s = loads.seconds[slowest] - t[u][drone_site[slowest]] -
                            (loads.sorties[slowest] > 1 ? swap_s : 0.0);
      for (std::size_t d = 0; d < drones; ++d) {
        if (d == slowest || t[u][drone_site[d]] > endurance_s) continue;
        const double new_top_s = std::max(left_s, loads.With(d, t[u][drone_site[d]], swap_s));
        if (new_top_s < best_top_s) {
          best_top_s = new_top_s;
          move_u = u;
          move_to = d;
        }
      }
    }
    if (move_u == units) {
      if (SwapOffSlowest(t, drone_site, slowest, endurance_s, loads, owner)) continue;
      break;
    }
    loads.seconds[slowest] -=
        t[move_u][drone_site[slowest]] + (loads.sorties[slowest] > 1 ? swap_s : 0.0);
    --loads.sorties[slowest];
    loads.seconds[move_to] = loads.With(move_to, t[move_u][drone_site[move_to]], swap_s);
    ++loads.sorties[move_to];
    owner[move_u] = move_to;
  }
  for (std::size_t u = 0; u < units; ++u) out.drone_units[owner[u]].push_back(u);
  out.makespan_s = *std::max_element(loads.seconds.begin(), loads.seconds.end());
  return out;
}

std::vector<std::size_t> DroneSites(const std::vector<std::size_t>& per_site) {
  std::vector<std::size_t> drone_site;
  for (std::size_t k = 0; k < per_site.size(); ++k)
    drone_site.insert(drone_site.end(), per_site[k], k);
  return drone_site;
}

// Drones per site in proportion to the work each site is quickest for.
std::vector<std::size_t> ShareBySite(const std::vector<std::vector<double>>& t, std::size_t drones,
                                     std::size_t sites) {
  std::vector<double> share(sites, 0.0);
  for (const auto& row : t) {
    const auto k = static_cast<std::size_t>(std::min_element(row.begin(), row.end()) - row.begin());
    share[k] += row[k];
  }
  const double total = std::accumulate(share.begin(), share.end(), 0.0);
  std::vector<std::size_t> counts(sites, 0);
  std::vector<std::pair<double, std::size_t>> remainders;
  std::size_t given = 0;
  for (std::size_t k = 0; k < sites; ++k) {
    const double exact = total > 0.0 ? share[k] / total * static_cast<double>(drones) : 0.0;
    counts[k] = static_cast<std::size_t>(std::floor(exact));
    given += counts[k];
    remainders.emplace_back(exact - std::floor(exact), k);
  }
  std::stable_sort(remainders.begin(), remainders.end(),
                   [](const auto& a, const auto& b) { return a.first > b.first; });
  for (std::size_t i = 0; given < drones; ++i, ++given) ++counts[remainders[i % sites].second];
  return counts;
}

}  // namespace

std::optional<Assignment> AssignUnits(const std::vector<std::vector<double>>& unit_site_s,
                                      std::size_t drones, const std::vector<int>& site_drones,
                                      double endurance_s, double swap_s) {
  if (unit_site_s.empty() || drones == 0) return std::nullopt;
  const std::size_t sites = unit_site_s.front().size();
  if (!site_drones.empty()) {
    std::vector<std::size_t> counts;
    for (const int c : site_drones) counts.push_back(static_cast<std::size_t>(c));
    return Greedy(unit_site_s, DroneSites(counts), endurance_s, swap_s);
  }
  std::vector<std::size_t> counts = ShareBySite(unit_site_s, drones, sites);
  std::optional<Assignment> best = Greedy(unit_site_s, DroneSites(counts), endurance_s, swap_s);
  // Move one drone at a time between sites while the makespan drops.
  for (bool improved = sites > 1; improved;) {
    improved = false;
    for (std::size_t from = 0; from < sites && !improved; ++from) {
      if (counts[from] == 0) continue;
      for (std::size_t to = 0; to < sites && !improved; ++to) {
        if (to == from) continue;
        std::vector<std::size_t> trial = counts;
        --trial[from];
        ++trial[to];
        std::optional<Assignment> candidate =
            Greedy(unit_site_s, DroneSites(trial), endurance_s, swap_s);
        if (candidate && (!best || candidate->makespan_s < best->makespan_s - kGainS)) {
          best = std::move(candidate);
          counts = trial;
          improved = true;
        }
      }
    }
  }
  return best;
}

}  // namespace fireswarm::planner
