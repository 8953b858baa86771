// Investigations: choosing the investigator, checking its way past the no-fly
// zones, and the verdicts (investigations.hpp says what each means).
#include "fireswarm/server/investigations.hpp"

#include <algorithm>
#include <boost/geometry.hpp>
#include <cmath>
#include <numbers>
#include <utility>

#include "fireswarm/common/time.hpp"
#include "fireswarm/radio/params.hpp"
#include "local_point.hpp"

namespace fireswarm::server {

namespace {

// The radius the vehicle circles at when the order gives none: its loiter radius
// parameter (investigate.radius_m). The server does not read a vehicle's value
// back, so it checks the parameter's default, m.
double VehicleLoiterRadiusM() {
  return radio::SpecOf(radio::ParamId::kLoiterRadiusM).default_value;
}
// Sides of the polygon that stands for a circle, drawn around it.
constexpr int kCircleSides = 32;

std::string Metres(double value_m) {
  return std::to_string(static_cast<long>(std::lround(value_m))) + " m";
}

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

Investigations::Investigations(InvestigationsConfig config, const common::LocalFrame& frame,
                               const planner::TransitPlanner* transit)
    : config_(std::move(config)), frame_(frame), transit_(transit) {}

double Investigations::RadiusM(double ordered_radius_m) const {
  if (ordered_radius_m > 0.0) return ordered_radius_m;
  return config_.investigate_radius_m > 0.0 ? config_.investigate_radius_m : VehicleLoiterRadiusM();
}

std::optional<std::string> Investigations::CircleRefusal(const Eigen::Vector2d& point_en_m,
                                                         double radius_m) const {
  if (transit_ == nullptr) return std::nullopt;
  if (transit_->IsInside(PlannerPoint(point_en_m))) return "the point is inside a no-fly zone";
  if (!transit_->IsCircleClear(PlannerPoint(point_en_m), radius_m)) {
    return "the " + Metres(radius_m) + " circle around the point enters a no-fly zone";
  }
  return std::nullopt;
}

std::optional<std::string> Investigations::ApproachRefusal(const VehicleRegistry& registry,
                                                           std::uint8_t vehicle,
                                                           const Eigen::Vector2d& point_en_m,
                                                           double radius_m) const {
  if (transit_ == nullptr) return std::nullopt;
  const std::string name = "vehicle " + std::to_string(vehicle);
  const std::optional<radio::Telemetry>& telemetry = registry.state(vehicle).telemetry;
  if (!telemetry) {
    return name + " has sent no position: its approach cannot be checked against the no-fly zones";
  }
  const Eigen::Vector2d from_en_m = LocalM(frame_, {telemetry->lat_deg, telemetry->lon_deg});
  const planner::Polygon hull =
      InvestigationHull(PlannerPoint(from_en_m), PlannerPoint(point_en_m), radius_m);
  if (boost::geometry::intersects(hull, config_.no_fly)) {
    return name + "'s straight way to the circle or back to its lane crosses a no-fly zone";
  }
  return std::nullopt;
}

std::optional<std::uint8_t> Investigations::BestPlacedFor(const VehicleRegistry& registry,
                                                          const Eigen::Vector2d& point_en_m,
                                                          double radius_m, std::uint8_t reporter,
                                                          double now_s,
                                                          std::string* why_none) const {
  std::optional<std::uint8_t> best;
  double best_m = std::numeric_limits<double>::infinity();
  bool best_is_reporter = true;
  int blocked = 0;  // candidates whose approach would cross a no-fly zone
  for (const std::uint8_t id : registry.ids()) {
    const VehicleState& vehicle = registry.state(id);
    if (!vehicle.telemetry || registry.LinkAt(id, now_s) != LinkState::kOk) continue;
    if (vehicle.telemetry->mode != radio::FlightMode::kSearch) continue;
    if ((vehicle.telemetry->flags & radio::telemetry_flags::kLowBattery) != 0) continue;
    const bool busy = std::ranges::any_of(investigations_, [&](const Investigation& i) {
      return i.vehicle == id && i.until_s > now_s;
    });
    if (busy) continue;
    if (ApproachRefusal(registry, id, point_en_m, radius_m)) {
      ++blocked;
      continue;
    }
    const double distance_m =
        (LocalM(frame_, {vehicle.telemetry->lat_deg, vehicle.telemetry->lon_deg}) - point_en_m)
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

InvestigationOrder Investigations::Open(const VehicleRegistry& registry, std::uint8_t vehicle,
                                        common::LatLon point, double radius_m,
                                        std::int32_t track_id, double now_s) {
  const Eigen::Vector2d point_en_m = LocalM(frame_, point);
  // The vehicle counts the duration from the order: add its transit to the point.
  double transit_s = 0.0;
  if (const std::optional<radio::Telemetry>& t = registry.state(vehicle).telemetry) {
    transit_s = (LocalM(frame_, {t->lat_deg, t->lon_deg}) - point_en_m).norm() /
                config_.investigate_transit_mps;
  }
  const double duration_s = std::min(kMaxInvestigateS, transit_s + config_.investigate_s);
  InvestigationOrder order;
  order.command.type = radio::CommandType::kInvestigate;
  order.command.lat_deg = point.lat_deg;
  order.command.lon_deg = point.lon_deg;
  order.command.radius_m = radius_m > 0.0 ? radius_m : config_.investigate_radius_m;
  order.command.duration_s = static_cast<std::uint16_t>(std::lround(duration_s));
  order.investigation.vehicle = vehicle;
  order.investigation.track_id = track_id;
  order.investigation.started_s = now_s;
  order.investigation.until_s = now_s + order.command.duration_s;
  order.investigation.point_en_m = point_en_m;
  investigations_.push_back(order.investigation);
  return order;
}

void Investigations::Restore(const Investigation& investigation) {
  investigations_.push_back(investigation);
}

void Investigations::OnPosition(std::uint8_t vehicle, const Eigen::Vector2d& where_en_m,
                                double now_s) {
  for (Investigation& i : investigations_) {
    if (i.vehicle != vehicle || i.judged || now_s > i.until_s) continue;
    i.closest_m = std::min(i.closest_m, (where_en_m - i.point_en_m).norm());
  }
}

std::vector<std::uint8_t> Investigations::EndForConfirmed(std::int32_t track_id, double now_s) {
  std::vector<std::uint8_t> ended;
  for (Investigation& i : investigations_) {
    if (i.track_id != track_id || i.until_s <= now_s) continue;
    ended.push_back(i.vehicle);
    i.until_s = now_s;
  }
  return ended;
}

void Investigations::CallOff(std::uint8_t vehicle, double now_s) {
  for (Investigation& i : investigations_) {
    if (i.vehicle != vehicle || i.until_s <= now_s) continue;
    i.until_s = now_s;
    i.judged = true;
  }
}

common::Nanos Investigations::VerdictDue(const Investigation& investigation) const {
  return common::FromSeconds(investigation.until_s + config_.reject_grace_s);
}

std::vector<Rejection> Investigations::Judge(common::Nanos now, FireFusion& fusion) {
  std::vector<Rejection> rejections;
  for (Investigation& i : investigations_) {
    // Compared in the clock's own units: NextVerdict() asks for exactly VerdictDue(),
    // and a round trip through seconds could leave `now` a hair short of it.
    if (i.judged || i.track_id == 0 || now < VerdictDue(i)) continue;
    i.judged = true;
    const FireTrack* track = fusion.Find(i.track_id);
    if (track == nullptr || track->status != FireTrackStatus::kTentative) continue;
    if (!(i.closest_m <= config_.investigate_near_m)) continue;  // never got there: no verdict
    const bool seen_again = std::ranges::any_of(track->reports, [&](const FireObservation& o) {
      return o.vehicle_id == i.vehicle && o.detection_time_s >= i.started_s;
    });
    if (seen_again) continue;  // still tentative, but not a rock: leave it to later views
    // Rejected at once: a second investigation of the same track finds it decided.
    fusion.Reject(i.track_id);
    rejections.push_back({i.track_id, i.vehicle});
  }
  return rejections;
}

common::Nanos Investigations::NextVerdict(const FireFusion& fusion, common::Nanos next) const {
  for (const Investigation& i : investigations_) {
    if (i.track_id == 0 || i.judged) continue;
    const FireTrack* track = fusion.Find(i.track_id);
    if (track != nullptr && track->status == FireTrackStatus::kTentative) {
      next = std::min(next, VerdictDue(i));
    }
  }
  return next;
}

}  // namespace fireswarm::server
