// The server's side of the no-fly zones for investigations: which circle may be
// flown and which vehicle may be sent to it. A vehicle ordered to investigate
// flies straight from where it is to the circle's nearest point, circles, and
// flies straight back to where it left its lane (agents' investigate
// behaviour); all of it must stay out of every zone. The joins of
// handed-over lanes are routed in handover.cpp with the same transit planner.
#include <algorithm>
#include <boost/geometry.hpp>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include "fireswarm/server/server.hpp"
#include "local_point.hpp"

namespace fireswarm::server {

namespace {

// The vehicle's own loiter radius parameter (agents' investigate.radius_m) is
// 20 m by default; the server does not read it back, so it checks that radius
// when neither the order nor ServerConfig::investigate_radius_m gives one, m.
constexpr double kVehicleLoiterRadiusM = 20.0;
// Room the transit planner keeps around the zones for its sampling, m (it grows
// its box to each query's endpoints as well).
constexpr double kTransitMarginM = 1'000.0;

std::string Metres(double value_m) {
  return std::to_string(static_cast<long>(std::lround(value_m))) + " m";
}

// Sides of the polygon that stands for a circle, drawn around it.
constexpr int kCircleSides = 32;

// The ground a vehicle may cross on an investigation: straight from `from` to
// the circle, around it, and, when it is done, straight back from wherever it
// is on the circle to where it left its lane (`from`, give or take the metres
// flown before the order arrived): the convex hull of `from` and the circle.
planner::Polygon InvestigationHull(const planner::Point& from, const planner::Point& centre,
                                   double radius_m) {
  boost::geometry::model::multi_point<planner::Point> points;
  points.push_back(from);
  // Circumscribed: every side lies outside the circle.
  const double outer_m = radius_m / std::cos(std::numbers::pi / kCircleSides);
  for (int k = 0; k < kCircleSides; ++k) {
    const double angle = 2.0 * std::numbers::pi * k / kCircleSides;
    points.emplace_back(centre.x() + outer_m * std::cos(angle),
                        centre.y() + outer_m * std::sin(angle));
  }
  planner::Polygon hull;
  boost::geometry::convex_hull(points, hull);
  return hull;
}

}  // namespace

std::unique_ptr<const planner::TransitPlanner> Server::TransitFor(const ServerConfig& config) {
  if (config.no_fly.empty()) return nullptr;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  planner::Point low{kInf, kInf};
  planner::Point high{-kInf, -kInf};
  for (const planner::Polygon& zone : config.no_fly) {
    for (const planner::Point& p : zone.outer()) {
      low = {std::min(low.x(), p.x()), std::min(low.y(), p.y())};
      high = {std::max(high.x(), p.x()), std::max(high.y(), p.y())};
    }
  }
  const planner::Box bounds{{low.x() - kTransitMarginM, low.y() - kTransitMarginM},
                            {high.x() + kTransitMarginM, high.y() + kTransitMarginM}};
  return std::make_unique<const planner::TransitPlanner>(config.no_fly, bounds, config.no_fly_seed);
}

double Server::InvestigateRadiusM(double ordered_radius_m) const {
  if (ordered_radius_m > 0.0) return ordered_radius_m;
  return config_.investigate_radius_m > 0.0 ? config_.investigate_radius_m : kVehicleLoiterRadiusM;
}

std::optional<std::string> Server::CircleRefusal(const Eigen::Vector2d& point_ne_m,
                                                 double radius_m) const {
  if (!transit_) return std::nullopt;
  if (transit_->IsInside(PlannerPoint(point_ne_m))) return "the point is inside a no-fly zone";
  if (!transit_->IsCircleClear(PlannerPoint(point_ne_m), radius_m)) {
    return "the " + Metres(radius_m) + " circle around the point enters a no-fly zone";
  }
  return std::nullopt;
}

std::optional<std::string> Server::ApproachRefusal(std::uint8_t vehicle,
                                                   const Eigen::Vector2d& point_ne_m,
                                                   double radius_m) const {
  if (!transit_) return std::nullopt;
  const std::string name = "vehicle " + std::to_string(vehicle);
  const std::optional<radio::Telemetry>& telemetry = registry_.state(vehicle).telemetry;
  if (!telemetry) {
    return name + " has sent no position: its approach cannot be checked against the no-fly zones";
  }
  const Eigen::Vector2d from_ne_m = NorthEast(frame_, {telemetry->lat_deg, telemetry->lon_deg});
  const planner::Polygon hull =
      InvestigationHull(PlannerPoint(from_ne_m), PlannerPoint(point_ne_m), radius_m);
  if (boost::geometry::intersects(hull, config_.no_fly)) {
    return name + "'s straight way to the circle or back to its lane crosses a no-fly zone";
  }
  return std::nullopt;
}

std::optional<std::uint8_t> Server::BestPlacedFor(const Eigen::Vector2d& point_ne_m,
                                                  double radius_m, std::uint8_t reporter,
                                                  double now_s, std::string* why_none) const {
  std::optional<std::uint8_t> best;
  double best_m = std::numeric_limits<double>::infinity();
  bool best_is_reporter = true;
  int blocked = 0;  // candidates whose approach would cross a no-fly zone
  for (const std::uint8_t id : registry_.ids()) {
    const VehicleState& vehicle = registry_.state(id);
    if (!vehicle.telemetry || registry_.LinkAt(id, now_s) != LinkState::kOk) continue;
    if (vehicle.telemetry->mode != radio::FlightMode::kSearch) continue;
    if ((vehicle.telemetry->flags & radio::telemetry_flags::kLowBattery) != 0) continue;
    const bool busy = std::ranges::any_of(investigations_, [&](const Investigation& i) {
      return i.vehicle == id && i.until_s > now_s;
    });
    if (busy) continue;
    if (ApproachRefusal(id, point_ne_m, radius_m)) {
      ++blocked;
      continue;
    }
    const double distance_m =
        (NorthEast(frame_, {vehicle.telemetry->lat_deg, vehicle.telemetry->lon_deg}) - point_ne_m)
            .norm();
    const bool is_reporter = id == reporter;
    // Another vehicle than the reporter wins: its view is independent.
    if ((best_is_reporter && !is_reporter) ||
        (best_is_reporter == is_reporter && distance_m < best_m)) {
      best = id;
      best_m = distance_m;
      best_is_reporter = is_reporter;
    }
  }
  if (!best && why_none != nullptr) {
    *why_none = blocked > 0 ? "no searching vehicle has a straight way there and back clear of "
                              "the no-fly zones (" +
                                  std::to_string(blocked) + " would cross one)"
                            : "no searching vehicle with a working link";
  }
  return best;
}

}  // namespace fireswarm::server
