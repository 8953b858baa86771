#include "sorties.hpp"

#include <algorithm>
#include <boost/geometry.hpp>
#include <cmath>
#include <stdexcept>
#include <string>

#include "lanes.hpp"

namespace fireswarm::planner {
namespace bg = boost::geometry;

namespace {

// Whole seconds, for messages.
std::string Seconds(double seconds) {
  return std::to_string(std::llround(seconds)) + " s";
}

std::string Where(Point p) {
  return "(" + std::to_string(static_cast<long long>(p.x())) + " m E, " +
         std::to_string(static_cast<long long>(p.y())) + " m N)";
}

class FlightBuilder {
 public:
  FlightBuilder(Point launch, double speed_mps) : speed_mps_(speed_mps) {
    flight_.points.push_back({launch, false, false});
  }

  // Transit from the current point to `to`; the last point may be a return.
  void Transit(const Path& path, bool is_return) {
    for (std::size_t i = 1; i < path.size(); ++i) {
      flight_.points.push_back({path[i], is_return && i + 1 == path.size(), false});
    }
    const double length_m = LengthM(path);
    flight_.length_m += length_m;
    flight_.time_s += length_m / speed_mps_;
    flight_.transit_s += length_m / speed_mps_;
  }

  // The route from route time t0 to t1 (within one segment), ending at `to`.
  void Fly(const Route& route, double t0_s, double t1_s, Point to) {
    flight_.length_m += bg::distance(flight_.points.back().point, to);
    flight_.time_s += t1_s - t0_s;
    if (route.points.size() < 2) {
      flight_.transit_s += t1_s - t0_s;
      flight_.points.push_back({to, false, false});
      return;
    }
    const std::size_t i = route.SegmentAt((t0_s + t1_s) / 2.0);
    const double turn_end_s = route.time_s[i] + route.turn_s[i];
    const double turn_s =
        std::max(0.0, std::min(t1_s, turn_end_s) - std::max(t0_s, route.time_s[i]));
    flight_.turn_s += turn_s;
    const bool on_lane = route.segment_lane[i] >= 0;
    (on_lane ? flight_.sweep_s : flight_.transit_s) += t1_s - t0_s - turn_s;
    if (on_lane) flight_.points.back().starts_lane = true;
    flight_.points.push_back({to, false, false});
  }

  Flight Take() { return std::move(flight_); }

 private:
  double speed_mps_;
  Flight flight_;
};

}  // namespace

Flight FlyShare(const Route& route, const Share& share, Point launch, double endurance_s,
                const TransitPlanner& transit) {
  if (share.end_s <= share.begin_s) return Flight{{{launch, false, false}}, 0, 0.0, 0.0};
  // The share's vertices and their route times.
  std::vector<Point> points{route.At(share.begin_s)};
  std::vector<double> times{share.begin_s};
  for (std::size_t i = route.SegmentAt(share.begin_s) + 1;
       i < route.points.size() && route.time_s[i] < share.end_s; ++i) {
    if (route.time_s[i] <= share.begin_s) continue;
    points.push_back(route.points[i]);
    times.push_back(route.time_s[i]);
  }
  points.push_back(route.At(share.end_s));
  times.push_back(share.end_s);

  const double v = route.speed_mps;
  auto home_s = [&](Point p) { return LengthM(transit.Plan(p, launch)) / v; };
  FlightBuilder builder(launch, v);
  int sorties = 1;
  std::size_t k = 0;
  Path out = transit.Plan(launch, points[0]);
  double sortie_s = LengthM(out) / v;
  builder.Transit(out, false);
  std::size_t sortie_first = 0;
  while (k + 1 < points.size()) {
    const double next_s = sortie_s + (times[k + 1] - times[k]);
    if (next_s + home_s(points[k + 1]) <= endurance_s) {
      builder.Fly(route, times[k], times[k + 1], points[k + 1]);
      sortie_s = next_s;
      ++k;
      continue;
    }
    if (k == sortie_first) {
      throw std::runtime_error("endurance_s " + Seconds(endurance_s) +
                               " is too short: flying from launch to " + Where(points[k]) +
                               ", on to " + Where(points[k + 1]) + " and back takes " +
                               Seconds(next_s + home_s(points[k + 1])) +
                               " even in a sortie of its own (lanes are not "
                               "split between sorties)");
    }
    builder.Transit(transit.Plan(points[k], launch), true);
    out = transit.Plan(launch, points[k]);
    builder.Transit(out, false);
    sortie_s = LengthM(out) / v;
    sortie_first = k;
    ++sorties;
  }
  builder.Transit(transit.Plan(points.back(), launch), false);
  Flight flight = builder.Take();
  flight.sorties = sorties;
  return flight;
}

}  // namespace fireswarm::planner
