#include "sortie_flight.hpp"

#include <algorithm>
#include <boost/geometry.hpp>
#include <cmath>
#include <numbers>

#include "lanes.hpp"

namespace fireswarm::planner {
namespace bg = boost::geometry;

namespace {

using MultiPath = boost::geometry::model::multi_linestring<Path>;

class FlightBuilder {
 public:
  FlightBuilder(Point site, double speed_mps, const TransitPlanner& transit)
      : speed_mps_(speed_mps), transit_(transit) {
    flight_.points.push_back({site, false, false});
  }

  Point at() const { return flight_.points.back().point; }

  // Transit from where the drone is to `to`, around the zones.
  void TransitTo(Point to) {
    if (bg::distance(at(), to) == 0.0) return;
    const Path path = transit_.Plan(at(), to);
    for (std::size_t i = 1; i < path.size(); ++i) flight_.points.push_back({path[i], false, false});
    Add(LengthM(path), flight_.transit_s);
  }

  // A straight pass flown as a lane; the parts inside a no-fly zone are flown around.
  void Lane(Point from, Point to) {
    if (transit_.IsClear(from, to)) {
      TransitTo(from);
      flight_.points.back().starts_lane = true;
      flight_.points.push_back({to, false, false});
      Add(bg::distance(from, to), flight_.sweep_s);
      return;
    }
    MultiPath outside;
    bg::difference(Path{from, to}, transit_.NoFly(), outside);
    std::vector<std::pair<double, Path>> pieces;
    for (Path& piece : outside) {
      if (piece.size() < 2) continue;
      if (bg::distance(piece.front(), from) > bg::distance(piece.back(), from)) {
        std::reverse(piece.begin(), piece.end());
      }
      pieces.emplace_back(bg::distance(piece.front(), from), std::move(piece));
    }
    std::sort(pieces.begin(), pieces.end(),
              [](const auto& a, const auto& b) { return a.first < b.first; });
    for (const auto& [offset_m, piece] : pieces) {
      TransitTo(piece.front());
      flight_.points.back().starts_lane = true;
      flight_.points.push_back({piece.back(), false, false});
      Add(LengthM(piece), flight_.sweep_s);
    }
  }

  // A leg of a given path, not a lane.
  void Leg(Point to) {
    if (!transit_.IsClear(at(), to)) {
      TransitTo(to);
      return;
    }
    const double length_m = bg::distance(at(), to);
    flight_.points.push_back({to, false, false});
    Add(length_m, flight_.transit_s);
  }

  void Turn(double seconds) {
    flight_.time_s += seconds;
    flight_.turn_s += seconds;
    sortie_s_ += seconds;
  }

  // Home to `site`; a landing between sorties unless it is the last.
  void Home(Point site, bool last) {
    TransitTo(site);
    flight_.points.back().is_return = !last;
    ++flight_.sorties;
    flight_.longest_sortie_s = std::max(flight_.longest_sortie_s, sortie_s_);
    sortie_s_ = 0.0;
  }

  Flight Take() { return std::move(flight_); }

 private:
  void Add(double length_m, double& part_s) {
    flight_.length_m += length_m;
    flight_.time_s += length_m / speed_mps_;
    part_s += length_m / speed_mps_;
    sortie_s_ += length_m / speed_mps_;
  }

  double speed_mps_;
  const TransitPlanner& transit_;
  Flight flight_;
  double sortie_s_ = 0.0;
};

}  // namespace

Flight FlySorties(const std::vector<SortieUnit>& units, Point site, double speed_mps,
                  double turn_cost_s, const TransitPlanner& transit) {
  FlightBuilder builder(site, speed_mps, transit);
  for (std::size_t u = 0; u < units.size(); ++u) {
    bool first_pass = true;
    for (const std::vector<Pass>& block : units[u].passes) {
      for (const Pass& pass : block) {
        if (!first_pass) builder.Turn(turn_cost_s);
        first_pass = false;
        builder.Lane(pass.from, pass.to);
      }
    }
    builder.Home(site, u + 1 == units.size());
  }
  return builder.Take();
}

Flight FlyPaths(const std::vector<Path>& paths, Point site, double speed_mps, double turn_cost_s,
                double turn_angle_rad, const TransitPlanner& transit) {
  FlightBuilder builder(site, speed_mps, transit);
  for (std::size_t s = 0; s < paths.size(); ++s) {
    const Path& path = paths[s];
    for (std::size_t i = 0; i < path.size(); ++i) {
      if (i >= 2) {
        const double h0 =
            std::atan2(path[i - 1].y() - path[i - 2].y(), path[i - 1].x() - path[i - 2].x());
        const double h1 = std::atan2(path[i].y() - path[i - 1].y(), path[i].x() - path[i - 1].x());
        if (std::abs(std::remainder(h1 - h0, 2.0 * std::numbers::pi)) > turn_angle_rad) {
          builder.Turn(turn_cost_s);
        }
      }
      if (i == 0) {
        builder.TransitTo(path[i]);
      } else {
        builder.Leg(path[i]);
      }
    }
    builder.Home(site, s + 1 == paths.size());
  }
  return builder.Take();
}

}  // namespace fireswarm::planner
