// The tactical watch over the fleet: closest approaches predicted from
// telemetry, avoid orders, outcomes. The rules are in traffic.hpp.
#include "fireswarm/server/traffic.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "fireswarm/common/angles.hpp"

namespace fireswarm::server {

namespace {

// A prediction counts as a conflict this much inside the limit's reach: the
// positions are noisy by a few metres, and two drones in neighbouring layers
// (layer_m apart, each wandering about +-2 m) must not count.
constexpr double kPredictionMarginM = 3.0;
// ... and horizontally this much more: each drone's GPS position is off by a
// bias of about 1.8 m per axis (sim2d's GpsParams: 2.5 m CEP, 70 % of it a
// bias wandering over a minute), so two drones' telemetry puts them up to
// about 6 m (95 %) nearer or farther apart than they are, where the altitudes
// (barometers, 1 m) are off far less. A pair counts as in conflict when its
// horizontal distance less this, with its vertical one, comes within the
// reach. Over the 100 seeds of bench/scenarios/separation120.yaml (before
// the way home was predicted after a sortie's end): 10 m kept in 95 seeds
// (84 without it), worst 8.21 m (8.07), 10 conflicts lost (10), 16.64 h in
// the air a run (16.45), makespan 754 s (730); with 5 m: 96 seeds, but
// 16.99 h and 795 s.
constexpr double kHorizontalNoiseM = 3.0;
// A resolution clears its pair only if it leaves them this much more than the
// conflict reach apart: a level order that held a landing drone where it was
// left it 13.4 m over a transit layer, the reach plus 0.4 m, and its altitude
// hold (1 m under its target) and the two barometers took the rest (seed 58 of
// bench/scenarios/separation120.yaml: drones 64 and 51, 9.57 m). A climb or
// descent to a layer past the other's (layer_m, 15 m) still clears it, m.
constexpr double kResolvedMarginM = 2.0;
// The time an order needs before the mover answers it: the telemetry's age at
// 250 drones on one channel (about 3 s), the order's wait for its turn and the
// vehicle's altitude loop; the prediction of a candidate resolution starts its
// climb this late.
constexpr double kOrderDelayS = 3.0;
// What the vehicles climb and descend at when ordered, m/s (agents' altitude
// loop; the planner's FleetSpec climb_mps and descent_mps).
constexpr double kClimbMps = 3.0;
constexpr double kDescentMps = 2.0;
// A landing comes down at about this (agents' land_descent_mps), m/s.
constexpr double kLandingMps = 1.0;
// A drone's reported climb rate is carried on for this long at most: a climb to a
// layer ends there, and the prediction must not climb it to the sky.
constexpr double kVerticalLookS = 8.0;
// Telemetry older than this is carried on no further (the registry gives the
// drone up as lost later; ExpectLost then predicts its way home).
constexpr double kMaxExtrapolationS = 10.0;
// The prediction's time step inside a close window, s.
constexpr double kSampleS = 0.25;
// An order lasts until the pair has passed, plus this, s; and at least kMinOrderS.
constexpr double kOrderTailS = 10.0;
constexpr double kMinOrderS = 15.0;
constexpr double kMaxOrderS = 180.0;
// A release (altitude 0) carries this duration: the vehicle refuses 0, s.
constexpr double kReleaseS = 1.0;
// A release clears a held drone as a departure with this many times the
// conflict reach (separation_m + kPredictionMarginM): its own way out and the
// others' routes are predicted more roughly than a straight encounter. Over
// 120 drones and 3 seeds (bench/separation_bench.cpp), 1x: 13 conflicts lost
// against 3 without releases; 2x: 7; 3x: 1 and the fleet's time in the air
// 1.7 % lower than without releases; 4x: 3 lost, nearly no gain.
constexpr double kReleaseReachFactor = 3.0;
// A climb or descent order is released once going back to its own altitudes
// is predicted clear by this many conflict reaches: its route is predicted
// better than a take-off's way out. Over the 100 seeds of
// bench/scenarios/separation120.yaml, against ending the order with the
// encounter: 10 m kept in 84 seeds (82), worst 3.94 m (2.33), 13 conflicts
// lost (18), makespan 735 s (728).
constexpr double kReturnReachFactor = 2.0;
// A pair still predicted in conflict is resolved again at most this often, s:
// the mover's telemetry needs time to show the order.
constexpr double kReorderS = 5.0;
// A ghost (lost drone) comes down over its home at this rate, m/s.
constexpr double kGhostDescentMps = 1.0;
// A departure is on its way (its reservation ends) at this fraction of its speed.
constexpr double kOnItsWayFraction = 0.7;
// The start delays a departure not yet seen climbing is predicted with, as
// fractions of TrafficControl::kStartDelayMaxS.
constexpr std::array<double, 3> kStartDelayFractions = {0.0, 0.5, 1.0};

// How the vehicles fly a route (agents' NavigationConfig, track mode): at
// cruise, slowing to kCornerSpeedMps for a turn sharper than kSharpTurnDeg
// (braking at kBrakingMps2), then speeding up again. Speeding up is limited by
// the tilt, not configured: kAccelMps2 fits the simulated vehicle best (the
// watch's position error 5 s ahead, p90, over one 120-drone run: 7.1 m at 2.5,
// 9.0 m at 1.0, 9.6 m at 4.0).
constexpr double kBrakingMps2 = 1.5;
constexpr double kAccelMps2 = 2.5;
constexpr double kCornerSpeedMps = 0.5;
constexpr double kSharpTurnDeg = 20.0;
// Legs shorter than this are turns in place for the navigator, m.
constexpr double kMinLegM = 0.01;
// A route's cruise speed is at least this, m/s.
constexpr double kMinRouteSpeedMps = 0.1;
// A drone flying its first leg faster than this fraction of its cruise speed
// holds the speed it reports there (the wind, its speed loop); slower, it is
// speeding up to cruise.
constexpr double kHoldsItsSpeedFraction = 0.5;
// A drone on its route faster than this, flying away from the route's way
// ahead, is off its route (AlongItsRoute), m/s.
constexpr double kOffRouteSpeedMps = 2.0;
// A drone this near the waypoint it flies to is turning there, on its route,
// whichever way it flies (the vehicles' acceptance radius, agents'
// NavigationConfig), m. Without it, seed 93 of separation120.yaml: drone 27,
// braking into its lane end 0.3 m past the waypoint, flew away from it and was
// predicted straight on instead of up its next lane; a release cleared drone 28
// to climb through its altitude there (6.4 m).
constexpr double kTurningAtWaypointM = 10.0;
// A take-off an order holds sets off this late: never, within any horizon.
constexpr double kHeldDepartureS = 1e6;
// Around a sharp turn a drone may be this much farther on the way it came than
// predicted, from kTurnBeforeS before the turn to kTurnAfterS after it, m and
// s: the vehicle's speed loop lags its braking curve, so it reaches the corner
// at 3 to 4 m/s, not kCornerSpeedMps, and runs on past it before it turns.
// Seed 13 of bench/scenarios/separation120.yaml: drones 87 and 93, descending
// on one line toward lane ends 20.7 m apart, each ran 5.6 to 7.4 m past its
// own and came within 8.84 m of the other, never predicted closer than the
// 20.7 m between the corners (12.97 m since). Over the 100 seeds: 10 m kept in
// 95 (95 without it), 16.75 h in the air a run (16.74). Counted all round (not
// only the way it came in): 96 seeds but 17.14 h; also at a route's end, the
// stop over the stand: 96 seeds but 16.95 h.
constexpr double kTurnAllowanceM = 6.0;
constexpr double kTurnBeforeS = 1.0;
constexpr double kTurnAfterS = 6.0;

// A part of a route's leg flown at one acceleration: from at_s (since the route
// starts), along_m into leg `leg`, at speed_mps.
struct Stretch {
  double at_s = 0.0;
  std::size_t leg = 0;
  double along_m = 0.0;
  double speed_mps = 0.0;
  double accel_mps2 = 0.0;
};

// How one drone is predicted to move from now: along its route as the vehicle
// flies it, when it flies one; else straight on horizontally, and vertically
// toward its intent or on its reported climb for a while; toward an ordered
// altitude either way.
struct Motion {
  int vehicle = 0;
  Eigen::Vector2d position_m = Eigen::Vector2d::Zero();  // now
  Eigen::Vector2d velocity_mps = Eigen::Vector2d::Zero();
  double altitude_m = 0.0;
  double climb_mps = 0.0;
  std::optional<double> intent_m;  // where it climbs or descends to by itself
  std::optional<double> target_m;  // an ordered altitude
  double target_after_s = 0.0;     // the order starts to act this late
  // A lost drone (it cannot be told anything), and one flying straight home.
  bool blind = false;
  bool ghost = false;
  Eigen::Vector2d home_m = Eigen::Vector2d::Zero();
  double ghost_speed_mps = 0.0;
  // A take-off: climbs where it is from climb_starts_s on to climb_out_m, then
  // flies its route.
  bool departing = false;
  double climb_out_m = 0.0;
  double climb_starts_s = 0.0;
  // A route (east, north, up) flown from route_starts_s on, from its first
  // point (where it sets off); at its end it stays. route_at_s: when it passes
  // each point, from route_starts_s; route_z_at: its altitude then; stretches:
  // how it moves along the legs.
  std::vector<Eigen::Vector3d> route;
  std::vector<double> route_at_s;
  std::vector<double> route_z_at;
  std::vector<Stretch> stretches;
  double route_starts_s = 0.0;
  // Its sharp turns: when it passes each, from route_starts_s, and the way it
  // comes in (TurnAllowanceAt). Not its route's end: a drone home over its
  // stand lands where it has stopped.
  struct Turn {
    double at_s = 0.0;
    Eigen::Vector2d in = Eigen::Vector2d::Zero();  // unit
  };
  std::vector<Turn> turns;

  // Whether it moves along one straight line at one velocity all the time.
  bool Straight() const { return !ghost && !departing && route.empty(); }
  // How much nearer than predicted it may be at `t` to a drone `toward` (a
  // unit vector) of it, running on past a turn the way it came in
  // (kTurnAllowanceM), m.
  double TurnAllowanceAt(double t, const Eigen::Vector2d& toward) const {
    const double since_s = t - route_starts_s;
    for (const Turn& turn : turns) {
      if (since_s >= turn.at_s - kTurnBeforeS && since_s <= turn.at_s + kTurnAfterS) {
        return kTurnAllowanceM * std::max(0.0, turn.in.dot(toward));
      }
    }
    return 0.0;
  }
  // Whether any turn's allowance falls within [0, horizon_s].
  bool TurnsWithin(double horizon_s) const {
    return std::any_of(turns.begin(), turns.end(), [&](const Turn& turn) {
      const double at_s = route_starts_s + turn.at_s;
      return at_s + kTurnAfterS >= 0.0 && at_s - kTurnBeforeS <= horizon_s;
    });
  }
  // Ordered to `altitude` from `after_s` on. A take-off flies its order where
  // it is (agents' take-off mode holds its point) and sets off only once the
  // order ends: held there over any horizon.
  void Order(double altitude, double after_s) {
    target_m = altitude;
    target_after_s = after_s;
    if (departing) climb_starts_s = route_starts_s = kHeldDepartureS;
  }
  // Its order ended now: a take-off climbs on and sets off.
  void Unorder() {
    target_m.reset();
    if (departing && climb_starts_s >= kHeldDepartureS) {
      climb_starts_s = 0.0;
      route_starts_s = ClimbEndS();
    }
  }
  double ClimbEndS() const {
    return climb_starts_s + std::max(0.0, climb_out_m - altitude_m) / kClimbMps;
  }
  // The route through `points`, flown as the vehicle's navigator flies it: at
  // `speed_mps`, slowing down for sharp turns, and for its last point when it
  // `stops` there. It passes the first point at `entry_mps` (0: from a hover),
  // and, faster than kHoldsItsSpeedFraction of speed_mps, flies its first leg
  // at that speed. Vertically it climbs or descends toward each point's
  // altitude while it flies there, and goes on from wherever it has got to
  // (the navigator does not wait for the altitude at a waypoint).
  void SetRoute(std::vector<Eigen::Vector3d> points, double speed_mps, double starts_s,
                double entry_mps, bool stops = false) {
    route = std::move(points);
    route_starts_s = starts_s;
    route_at_s.assign(route.size(), 0.0);
    stretches.clear();
    turns.clear();
    const double cruise = std::max(speed_mps, kMinRouteSpeedMps);
    double speed = std::clamp(entry_mps, 0.0, cruise);
    for (std::size_t k = 0; k + 1 < route.size(); ++k) {
      const bool last = k + 2 == route.size();
      const bool brakes = last ? stops : SharpTurn(route[k], route[k + 1], route[k + 2]);
      double exit = brakes ? (last ? 0.0 : kCornerSpeedMps) : cruise;
      const double leg_cruise = k == 0 && speed > kHoldsItsSpeedFraction * cruise ? speed : cruise;
      exit = std::min(exit, leg_cruise);
      route_at_s[k + 1] = AddLeg(k, route_at_s[k], speed, exit, leg_cruise);
      // A turn it brakes for at the end of a leg it flies (not a turn in place).
      const Eigen::Vector2d in = (route[k + 1] - route[k]).head<2>();
      if (brakes && !last && in.norm() >= kMinLegM) {
        turns.push_back({route_at_s[k + 1], in.normalized()});
      }
      speed = exit;
    }
    route_z_at.assign(route.size(), route.empty() ? 0.0 : route.front().z());
    for (std::size_t k = 1; k < route.size(); ++k) {
      route_z_at[k] = Toward(route_z_at[k - 1], route[k].z(), route_at_s[k] - route_at_s[k - 1]);
    }
  }
  // Whether the navigator slows down for the turn at `at` (agents' Navigator).
  static bool SharpTurn(const Eigen::Vector3d& from, const Eigen::Vector3d& at,
                        const Eigen::Vector3d& to) {
    const Eigen::Vector2d in = (at - from).head<2>();
    const Eigen::Vector2d out = (to - at).head<2>();
    if (in.norm() < kMinLegM || out.norm() < kMinLegM) return true;
    return in.dot(out) < std::cos(kSharpTurnDeg * common::kRadPerDeg) * in.norm() * out.norm();
  }
  // Leg k flown from `at_s`, entered at `entry` and left at `exit` (both at
  // most `cruise`): speeds up, cruises, brakes, as far as its length allows.
  // Returns when it ends.
  double AddLeg(std::size_t k, double at_s, double entry, double exit, double cruise) {
    const double length = (route[k + 1] - route[k]).head<2>().norm();
    // The top speed: cruise, or where speeding up meets braking.
    const double meet = std::sqrt((2.0 * kAccelMps2 * kBrakingMps2 * length +
                                   kBrakingMps2 * entry * entry + kAccelMps2 * exit * exit) /
                                  (kAccelMps2 + kBrakingMps2));
    const double top = std::clamp(meet, std::max(entry, exit), cruise);
    const double up_m = std::min(length, (top * top - entry * entry) / (2.0 * kAccelMps2));
    const double down_m =
        std::clamp((top * top - exit * exit) / (2.0 * kBrakingMps2), 0.0, length - up_m);
    double along = 0.0;
    const auto add = [&](double distance, double from_mps, double accel) {
      if (distance <= 0.0) return;
      stretches.push_back({at_s, k, along, from_mps, accel});
      const double to_mps = std::sqrt(std::max(0.0, from_mps * from_mps + 2.0 * accel * distance));
      at_s += accel != 0.0 ? (to_mps - from_mps) / accel : distance / std::max(from_mps, 1e-3);
      along += distance;
    };
    add(up_m, entry, kAccelMps2);
    add(length - up_m - down_m, top, 0.0);
    add(down_m, top, -kBrakingMps2);
    return at_s;
  }
  // The leg flown `since_s` after setting off: [k, k + 1]; the last point once
  // past the end (k + 1 == route.size()).
  std::size_t LegAt(double since_s) const {
    const auto after = std::upper_bound(route_at_s.begin(), route_at_s.end(), since_s);
    return static_cast<std::size_t>(std::max<std::ptrdiff_t>(0, after - route_at_s.begin() - 1));
  }

  Eigen::Vector2d PositionAt(double t) const {
    if (!route.empty()) {
      if (t <= route_starts_s) return position_m;
      const double since_s = t - route_starts_s;
      if (since_s >= route_at_s.back() || stretches.empty()) return route.back().head<2>();
      const auto after =
          std::upper_bound(stretches.begin(), stretches.end(), since_s,
                           [](double s, const Stretch& stretch) { return s < stretch.at_s; });
      const Stretch& stretch = after == stretches.begin() ? stretches.front() : *(after - 1);
      const double dt = std::max(0.0, since_s - stretch.at_s);
      const double speed = std::max(0.0, stretch.speed_mps + stretch.accel_mps2 * dt);
      const double along = stretch.along_m + 0.5 * (stretch.speed_mps + speed) * dt;
      const Eigen::Vector2d leg = (route[stretch.leg + 1] - route[stretch.leg]).head<2>();
      const double length = leg.norm();
      if (length < kMinLegM) return route[stretch.leg].head<2>();
      return route[stretch.leg].head<2>() + std::min(along / length, 1.0) * leg;
    }
    if (!ghost) return position_m + velocity_mps * t;
    const Eigen::Vector2d to_home = home_m - position_m;
    const double distance = to_home.norm();
    if (distance < 1e-6) return home_m;
    return position_m + to_home / distance * std::min(distance, ghost_speed_mps * t);
  }

  double AltitudeAt(double t) const {
    if (ghost) {
      const double arrival_s = (home_m - position_m).norm() / std::max(ghost_speed_mps, 0.1);
      return std::max(0.0, altitude_m - kGhostDescentMps * std::max(0.0, t - arrival_s));
    }
    const double before = std::min(t, target_after_s);
    double z = OwnAltitudeAt(target_m ? before : t);
    if (target_m && t > target_after_s) z = Toward(z, *target_m, t - target_after_s);
    return std::max(0.0, z);
  }

  // From altitude `from` toward `to` for `seconds` at the vehicles' rates.
  static double Toward(double from, double to, double seconds) {
    const double rate = to > from ? kClimbMps : kDescentMps;
    const double step = std::min(std::abs(to - from), rate * std::max(0.0, seconds));
    return to > from ? from + step : from - step;
  }

  // Unordered: a take-off's climb, a route's altitudes, or as SelfAltitudeAt.
  double OwnAltitudeAt(double t) const {
    if (departing && t <= route_starts_s) {
      const double climbed = kClimbMps * std::max(0.0, t - climb_starts_s);
      return std::max(altitude_m, std::min(climb_out_m, altitude_m + climbed));
    }
    if (route.empty()) return SelfAltitudeAt(t);
    const double since_s = std::max(0.0, t - route_starts_s);
    const std::size_t k = LegAt(since_s);
    const double target = route[std::min(k + 1, route.size() - 1)].z();
    return Toward(route_z_at[k], target, since_s - route_at_s[k]);
  }

  // Toward its own intent at its reported rate (at least the vehicles' usual
  // one), or on its reported climb for a few seconds.
  double SelfAltitudeAt(double t) const {
    if (!intent_m) return altitude_m + climb_mps * std::min(t, kVerticalLookS);
    const bool up = *intent_m > altitude_m;
    const double rate = std::max(std::abs(climb_mps), up ? kClimbMps : kLandingMps);
    const double step = std::min(std::abs(*intent_m - altitude_m), rate * t);
    return altitude_m + (up ? step : -step);
  }
};

struct Approach {
  // The closest, its horizontal part counted short as Closest says.
  double distance_m = std::numeric_limits<double>::infinity();
  double at_s = 0.0;
  double window_end_s = 0.0;  // when the pair is apart horizontally again
  // How deep and how long the pair is inside the reach: the integral of
  // reach - distance over the times it is, m s.
  double intrusion_m_s = 0.0;
};

// The closest the two come over [0, horizon_s] while horizontally within
// `reach_m` of each other (farther apart they cannot conflict), their
// horizontal distance counted kHorizontalNoiseM short, and each one's turn
// allowance toward the other (Motion::TurnAllowanceAt) more while it turns.
Approach Closest(const Motion& a, const Motion& b, double horizon_s, double reach_m) {
  Approach out;
  double first = 0.0;
  double last = horizon_s;
  const double horizontal_reach_m = reach_m + kHorizontalNoiseM;
  const bool turning = a.TurnsWithin(horizon_s) || b.TurnsWithin(horizon_s);
  if (a.Straight() && b.Straight()) {
    // Straight lines: the window where the horizontal distance is under reach.
    const Eigen::Vector2d r = b.position_m - a.position_m;
    const Eigen::Vector2d w = b.velocity_mps - a.velocity_mps;
    const double ww = w.squaredNorm();
    const double c = r.squaredNorm() - horizontal_reach_m * horizontal_reach_m;
    if (ww < 1e-9) {
      if (c > 0.0) return out;
    } else {
      const double half_b = r.dot(w);
      const double discriminant = half_b * half_b - ww * c;
      if (discriminant < 0.0) return out;
      const double root = std::sqrt(discriminant);
      first = std::max(0.0, (-half_b - root) / ww);
      last = std::min(horizon_s, (-half_b + root) / ww);
      if (first > last) return out;
    }
  }
  for (double t = first;; t += kSampleS) {
    t = std::min(t, last);
    const Eigen::Vector2d dh = b.PositionAt(t) - a.PositionAt(t);
    const double dh_m = dh.norm();
    double allowance_m = kHorizontalNoiseM;
    if (turning && dh_m > 1e-9) {
      const Eigen::Vector2d a_to_b = dh / dh_m;
      allowance_m += a.TurnAllowanceAt(t, a_to_b) + b.TurnAllowanceAt(t, -a_to_b);
    }
    if (dh_m <= reach_m + allowance_m) {
      const double d =
          std::hypot(std::max(0.0, dh_m - allowance_m), b.AltitudeAt(t) - a.AltitudeAt(t));
      out.intrusion_m_s += std::max(0.0, reach_m - d) * kSampleS;
      if (d < out.distance_m) {
        out.distance_m = d;
        out.at_s = t;
      }
      out.window_end_s = t;
    }
    if (t >= last) break;
  }
  return out;
}

// A candidate resolution's cost for a pair it leaves inside the reach: `cost`,
// plus as much again times its intrusion (Approach) as a share of the most
// there can be over the horizon: a brief near miss beats a long or deep one.
// The pair in conflict costs kPairCost, so a resolution that clears it costs
// less than any that does not; each other drone the mover would come too near
// costs kOthersCost. A climb or descent of one layer costs 1.
constexpr double kPairCost = 1000.0;
constexpr double kOthersCost = 100.0;
double Shortfall(const Approach& approach, double reach_m, double horizon_s, double cost) {
  if (approach.distance_m >= reach_m) return 0.0;
  return cost * (1.0 + std::min(1.0, approach.intrusion_m_s / (reach_m * horizon_s)));
}

void RequirePositive(double value, const char* field) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    throw std::invalid_argument(std::string("separation: ") + field + " must be a positive number");
  }
}

}  // namespace

void SeparationConfig::Validate() const {
  RequirePositive(separation_m, "separation_m");
  RequirePositive(layer_m, "layer_m");
  RequirePositive(transit_min_m, "transit_min_m");
  RequirePositive(horizon_s, "horizon_s");
  RequirePositive(max_altitude_m, "max_altitude_m");
  if (!(min_altitude_m >= 0.0) || !(min_altitude_m < max_altitude_m)) {
    throw std::invalid_argument("separation: min_altitude_m must be in [0, max_altitude_m)");
  }
  if (search_layers < 1 || search_layers > 10) {
    throw std::invalid_argument("separation: search_layers must be in 1..10");
  }
  if (transit_sectors < 1 || transit_sectors > 12) {
    throw std::invalid_argument("separation: transit_sectors must be in 1..12");
  }
}

const char* ToString(Resolution resolution) {
  switch (resolution) {
    case Resolution::kNone:
      return "none";
    case Resolution::kClimb:
      return "climb";
    case Resolution::kDescend:
      return "descend";
    case Resolution::kLevel:
      return "level";
  }
  return "unknown";
}

const char* ToString(ConflictOutcome outcome) {
  switch (outcome) {
    case ConflictOutcome::kOpen:
      return "open";
    case ConflictOutcome::kResolved:
      return "resolved";
    case ConflictOutcome::kLostSeparation:
      return "lost_separation";
  }
  return "unknown";
}

TrafficControl::TrafficControl(const SeparationConfig& config) : config_(config) {
  config_.Validate();
}

void TrafficControl::Observe(int vehicle, const TrafficSample& sample) {
  tracks_[vehicle] = sample;
  ghosts_.erase(vehicle);  // heard again: no longer predicted blind
  // On its way at speed: its telemetry predicts it from now on.
  const auto departure = departures_.find(vehicle);
  if (departure != departures_.end() &&
      std::hypot(sample.velocity_mps.x(), sample.velocity_mps.y()) >=
          kOnItsWayFraction * departure->second.departure.speed_mps) {
    departures_.erase(departure);
  }
}

void TrafficControl::Taken(const AvoidOrder& order, bool taken, double now_s) {
  const int vehicle = order.vehicle;
  const auto standing = orders_.find(vehicle);
  const bool release = order.altitude_m <= 0.0;
  if (taken) {
    // The vehicle holds it from about now (its own clock starts on arrival).
    if (release) {
      taken_.erase(vehicle);
    } else {
      taken_[vehicle] = Held{order.altitude_m, now_s + order.duration_s, now_s, order.level,
                             order.conflict_id};
    }
    return;
  }
  ++counts_.not_taken;
  // Seed 52 of bench/scenarios/separation120.yaml: an order to climb out of
  // a drone's way home failed after its resends; predicted at the order's
  // altitude while it flew on level, drone 80 was seen in conflict again only
  // 3.75 s before drone 61, climbing to its own way home, came 8.31 m under it.
  const auto last = taken_.find(vehicle);
  const bool holds = last != taken_.end() && last->second.until_s > now_s;
  if (release) {
    // Still holding what the release was to end: predicted so, and let go of
    // again by the release check.
    if (holds && standing == orders_.end()) orders_.emplace(vehicle, last->second);
    return;
  }
  // Superseded since (a later order stands): nothing of this one is predicted.
  if (standing == orders_.end() || standing->second.conflict_id != order.conflict_id ||
      standing->second.altitude_m != order.altitude_m) {
    return;
  }
  if (holds) {
    standing->second = last->second;
  } else {
    orders_.erase(standing);
  }
  std::erase_if(last_order_s_, [&](const auto& entry) {
    return entry.first.first == vehicle || entry.first.second == vehicle;
  });
}

void TrafficControl::Forget(int vehicle) {
  tracks_.erase(vehicle);
  ghosts_.erase(vehicle);
}

namespace {

Eigen::Vector2d Horizontal(const Eigen::Vector3d& v) {
  return {v.x(), v.y()};
}

// The departure as a motion: from `at_m` (its stand, or where its telemetry puts
// it) and `altitude_m`, climbing from `delay_s` on, then along its waypoints.
Motion DepartureMotion(int vehicle, const Departure& departure, const Eigen::Vector2d& at_m,
                       double altitude_m, double delay_s) {
  Motion m;
  m.vehicle = vehicle;
  m.departing = true;
  m.position_m = at_m;
  m.altitude_m = altitude_m;
  m.climb_out_m = departure.route_m.front().z();
  m.climb_starts_s = delay_s;
  std::vector<Eigen::Vector3d> route = {{at_m.x(), at_m.y(), m.climb_out_m}};
  route.insert(route.end(), departure.route_m.begin(), departure.route_m.end());
  m.SetRoute(std::move(route), departure.speed_mps, m.ClimbEndS(), /*entry_mps=*/0.0);
  return m;
}
// Whether a drone on its route flies along it: slower than kOffRouteSpeedMps
// (turning, hovering), within kTurningAtWaypointM of the waypoint it flies to,
// or toward that waypoint. A drone resuming its
// search after an investigation or a hold flies back to where it left the
// route first (agents' rejoin), which the route does not show: it is
// predicted straight on until it turns onto the route again.
bool AlongItsRoute(const TrafficSample& sample) {
  const Eigen::Vector2d velocity = Horizontal(sample.velocity_mps);
  if (velocity.norm() < kOffRouteSpeedMps) return true;
  const Eigen::Vector2d ahead = Horizontal(sample.route_m.front() - sample.position_m);
  return ahead.norm() < kTurningAtWaypointM || velocity.dot(ahead) >= 0.0;
}

// A drone along its route from where `sample` reported it, `age_s` ago.
Motion RouteMotion(int vehicle, const TrafficSample& sample, double age_s) {
  Motion m;
  m.vehicle = vehicle;
  m.velocity_mps = Horizontal(sample.velocity_mps);
  m.climb_mps = sample.velocity_mps.z();
  m.position_m = Horizontal(sample.position_m);  // where a route starting now is
  m.altitude_m = sample.position_m.z();
  std::vector<Eigen::Vector3d> route = {sample.position_m};
  route.insert(route.end(), sample.route_m.begin(), sample.route_m.end());
  m.SetRoute(std::move(route), sample.route_speed_mps, -age_s, m.velocity_mps.norm(),
             sample.route_stops);
  m.position_m = m.PositionAt(0.0);
  m.altitude_m = m.OwnAltitudeAt(0.0);
  return m;
}

// Every drone watched, as predicted from `now_s`: a take-off cleared
// (`departures`) as its departure goes until it is on its way at speed; a drone
// on its route along it; others straight on; an ordered one toward its order;
// lost drones on their way home.
std::vector<Motion> Motions(const std::map<int, TrafficSample>& tracks, const auto& ghosts,
                            const auto& orders, const auto& departures, double now_s) {
  std::vector<Motion> out;
  for (const auto& [vehicle, sample] : tracks) {
    const double age_s = std::clamp(now_s - sample.at_s, 0.0, kMaxExtrapolationS);
    Motion m;
    m.vehicle = vehicle;
    m.velocity_mps = sample.holds_position ? Eigen::Vector2d::Zero()
                                           : Eigen::Vector2d(Horizontal(sample.velocity_mps));
    m.position_m = Horizontal(sample.position_m) + m.velocity_mps * age_s;
    m.climb_mps = sample.velocity_mps.z();
    m.intent_m = sample.intent_altitude_m;
    m.altitude_m = sample.position_m.z();
    m.altitude_m = std::max(0.0, m.SelfAltitudeAt(age_s));
    const auto departure = departures.find(vehicle);
    if (departure != departures.end()) {
      m = DepartureMotion(vehicle, departure->second.departure, m.position_m, m.altitude_m, 0.0);
      m.climb_mps = sample.velocity_mps.z();
    } else if (sample.departing && !sample.route_m.empty()) {
      // Taking off: up where it is, then on its way along its sortie.
      Departure taking_off;
      taking_off.route_m = sample.route_m;
      taking_off.speed_mps = sample.route_speed_mps;
      m = DepartureMotion(vehicle, taking_off, m.position_m, m.altitude_m, 0.0);
      m.climb_mps = sample.velocity_mps.z();
      m.intent_m = sample.intent_altitude_m;
    } else if (!sample.route_m.empty() && AlongItsRoute(sample)) {
      m = RouteMotion(vehicle, sample, age_s);
      m.intent_m = sample.intent_altitude_m;
    } else if (!sample.route_m.empty() && !m.intent_m) {
      // Flying back to where it left its route: straight on, at the altitude
      // of the waypoint it resumes (agents' rejoin).
      m.intent_m = sample.route_m.front().z();
      m.altitude_m = sample.position_m.z();
      m.altitude_m = std::max(0.0, m.SelfAltitudeAt(age_s));
    }
    const auto order = orders.find(vehicle);
    if (order != orders.end() && order->second.until_s > now_s) {
      // Ordered a while ago: the climb has started; just now: it starts later.
      m.Order(order->second.altitude_m, std::max(0.0, order->second.from_s + kOrderDelayS - now_s));
    }
    out.push_back(m);
  }
  for (const auto& [vehicle, ghost] : ghosts) {
    if (ghost.until_s <= now_s) continue;
    if (!ghost.way_m.empty()) {
      // Along its route, then home; it stops over its stand.
      Motion m;
      m.vehicle = vehicle;
      m.blind = true;
      m.velocity_mps = Horizontal(ghost.last.velocity_mps);
      m.position_m = Horizontal(ghost.last.position_m);
      m.altitude_m = ghost.last.position_m.z();
      m.SetRoute(ghost.way_m, ghost.speed_mps, ghost.last.at_s - now_s, m.velocity_mps.norm(),
                 /*stops=*/true);
      m.velocity_mps = m.PositionAt(1.0) - m.PositionAt(0.0);
      m.position_m = m.PositionAt(0.0);
      m.altitude_m = m.OwnAltitudeAt(0.0);
      out.push_back(m);
      continue;
    }
    Motion m;
    m.blind = true;
    m.vehicle = vehicle;
    m.ghost = true;
    m.home_m = ghost.home_m;
    m.ghost_speed_mps = ghost.speed_mps;
    // Where it would be by now on its way home.
    Motion from_last = m;
    from_last.position_m = Horizontal(ghost.last.position_m);
    from_last.altitude_m = ghost.altitude_m;
    const double since_s = std::max(0.0, now_s - ghost.last.at_s);
    m.position_m = from_last.PositionAt(since_s);
    m.altitude_m = from_last.AltitudeAt(since_s);
    out.push_back(m);
  }
  return out;
}

// What a clearance (a take-off's, a held drone's release) keeps `vehicle` off:
// every other drone as its telemetry says, along its route, and those cleared to
// take off as their departures go (their telemetry shows no way out yet; not yet
// heard: from their stands, at each start delay).
std::vector<Motion> ClearanceTraffic(const std::map<int, TrafficSample>& tracks, const auto& ghosts,
                                     const auto& orders, const auto& departures, double now_s,
                                     int vehicle) {
  std::vector<Motion> others;
  for (Motion& m : Motions(tracks, ghosts, orders, departures, now_s)) {
    if (m.vehicle != vehicle) others.push_back(std::move(m));
  }
  for (const auto& [other, reserved] : departures) {
    if (other == vehicle || tracks.contains(other) || ghosts.contains(other)) continue;
    const double since_s = now_s - reserved.cleared_s;
    for (const double fraction : kStartDelayFractions) {
      others.push_back(
          DepartureMotion(other, reserved.departure, reserved.departure.stand_m, 0.0,
                          std::max(0.0, fraction * TrafficControl::kStartDelayMaxS - since_s)));
    }
  }
  return others;
}

// The box a drone's horizontal path stays in over [0, horizon_s].
struct Box {
  Eigen::Vector2d low;
  Eigen::Vector2d high;
  void Add(const Eigen::Vector2d& p) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
};
Box Sweep(const Motion& m, double horizon_s) {
  Box box{m.PositionAt(0.0), m.PositionAt(0.0)};
  box.Add(m.PositionAt(horizon_s));                   // every kind's path is straight between these
  for (std::size_t k = 0; k < m.route.size(); ++k) {  // ... or bends at its points
    if (m.route_starts_s + m.route_at_s[k] > horizon_s) break;
    box.Add(m.route[k].head<2>());
  }
  if (m.TurnsWithin(horizon_s)) {  // ... give or take its turns' allowance
    box.low.array() -= kTurnAllowanceM;
    box.high.array() += kTurnAllowanceM;
  }
  return box;
}

// Whether two drones' boxes (Sweep) are too far apart in x or y for Closest
// to find them within reach_m: a cheap test before sampling the pair.
bool Apart(const Box& a, const Box& b, double reach_m) {
  const Eigen::Vector2d gap = (b.low - a.high).cwiseMax(a.low - b.high);
  return gap.maxCoeff() > reach_m + kHorizontalNoiseM;
}

// Whether a drone held level may go on by itself from now: `self` is its
// motion now (its order ignored), `departure` its reserved take-off when it is
// taking off (then it is predicted as that departure, from where it is, starting
// within kStartDelayMaxS: the release waits for its radio turn), `others` the
// traffic (ClearanceTraffic). Over `horizon_s`, or the climb and the first
// stretch of the way out for a take-off.
bool ClearToGoOn(const Motion& self, const Departure* departure, const std::vector<Motion>& others,
                 double horizon_s, double reach_m) {
  std::vector<Motion> candidates;
  if (departure != nullptr) {
    for (const double fraction : kStartDelayFractions) {
      candidates.push_back(DepartureMotion(self.vehicle, *departure, self.position_m,
                                           self.altitude_m,
                                           fraction * TrafficControl::kStartDelayMaxS));
    }
    horizon_s =
        std::max(horizon_s, candidates.back().ClimbEndS() + TrafficControl::kDepartureTransitS);
  } else {
    candidates.push_back(self);
    candidates.back().Unorder();
  }
  for (const Motion& released : candidates) {
    const Box box = Sweep(released, horizon_s);
    for (const Motion& other : others) {
      if (Apart(box, Sweep(other, horizon_s), reach_m)) continue;
      if (Closest(released, other, horizon_s, reach_m).distance_m < reach_m) return false;
    }
  }
  return true;
}

}  // namespace

void TrafficControl::ExpectLost(int vehicle, const TrafficSample& last,
                                const Eigen::Vector2d& home_m, double altitude_m, double speed_mps,
                                double turns_home_s, double until_s) {
  tracks_.erase(vehicle);
  Ghost ghost{last, home_m, altitude_m, speed_mps, until_s, {}};
  if (!last.route_m.empty() && turns_home_s > last.at_s) {
    // On along its route (as the watch predicts a route) until it turns home.
    const Motion on = RouteMotion(vehicle, last, 0.0);
    const double turns_s = turns_home_s - last.at_s;
    const std::size_t leg = on.LegAt(turns_s - on.route_starts_s);
    ghost.way_m.assign(on.route.begin(), on.route.begin() + static_cast<std::ptrdiff_t>(leg) + 1);
    const Eigen::Vector2d turn = on.PositionAt(turns_s);
    ghost.way_m.emplace_back(turn.x(), turn.y(), on.OwnAltitudeAt(turns_s));
    // An order it got before it fell silent holds its altitude until it turns
    // home (the vehicle drops it then: no release would reach it).
    const auto order = orders_.find(vehicle);
    if (order != orders_.end() && order->second.until_s > last.at_s) {
      for (std::size_t k = 1; k < ghost.way_m.size(); ++k) {
        ghost.way_m[k].z() = order->second.altitude_m;
      }
    }
    ghost.way_m.emplace_back(home_m.x(), home_m.y(), altitude_m);
  }
  ghosts_[vehicle] = std::move(ghost);
}

// Whether two ways out in one layer pass within `reach_m` of each other less
// than `slot_s` apart in time, farther than `clear_m` along both from their
// stands (nearer, every way out from one site starts within reach of its
// neighbours', and the clearance's own look covers it). Each is flown at one
// speed; the time offsets are tried a second apart.
bool TrafficControl::WaysOutMeet(const Arrival& a, const Arrival& b, double reach_m, double slot_s,
                                 double clear_m) {
  struct Leg {
    Eigen::Vector2d from_m;
    Eigen::Vector2d velocity_mps;
    double from_s = 0.0;
    double to_s = 0.0;
  };
  const auto trimmed = [&](const Arrival& way) -> std::optional<Leg> {
    const Eigen::Vector2d along = way.at_m - way.from_m;
    const double length = along.norm();
    const double duration = way.at_s - way.from_s;
    if (length <= clear_m || duration <= 0.0) return std::nullopt;
    const double cut = clear_m / length;
    return Leg{way.from_m + cut * along, along / duration, way.from_s + cut * duration, way.at_s};
  };
  const std::optional<Leg> first = trimmed(a);
  const std::optional<Leg> second = trimmed(b);
  if (!first || !second) return false;
  for (double offset = -slot_s; offset <= slot_s; offset += 1.0) {
    // `first` at t against `second` at t + offset, over the times both fly.
    const double from = std::max(first->from_s, second->from_s - offset);
    const double to = std::min(first->to_s, second->to_s - offset);
    if (from > to) continue;
    const Eigen::Vector2d gap_at_from =
        (first->from_m + first->velocity_mps * (from - first->from_s)) -
        (second->from_m + second->velocity_mps * (from + offset - second->from_s));
    const Eigen::Vector2d closing = first->velocity_mps - second->velocity_mps;
    const double speed2 = closing.squaredNorm();
    const double t =
        speed2 < 1e-12 ? 0.0 : std::clamp(-gap_at_from.dot(closing) / speed2, 0.0, to - from);
    if ((gap_at_from + closing * t).norm() < reach_m) return true;
  }
  return false;
}

void TrafficControl::LapseReservations(double now_s) {
  // A take-off held by an avoid order keeps its reservation: its release is
  // cleared as that departure (Step).
  std::erase_if(departures_, [&](const auto& entry) {
    return entry.second.cleared_s + kDepartureHoldS <= now_s && !orders_.contains(entry.first);
  });
}

bool TrafficControl::ClearToDepart(int vehicle, const Departure& departure, double now_s) {
  if (departure.route_m.empty()) {
    throw std::invalid_argument("ClearToDepart: a departure needs its waypoints");
  }
  LapseReservations(now_s);
  const double reach_m = config_.separation_m + kPredictionMarginM;
  const double horizon_s =
      kStartDelayMaxS + departure.route_m.front().z() / kClimbMps + kDepartureTransitS;

  // Its arrival at its first waypoint (from a start halfway through the delay)
  // against the others' cleared before it.
  const Motion planned =
      DepartureMotion(vehicle, departure, departure.stand_m, 0.0, 0.5 * kStartDelayMaxS);
  Arrival arrival;
  arrival.from_m = departure.stand_m;
  arrival.from_s = now_s + planned.route_starts_s;
  arrival.at_m = departure.route_m.front().head<2>();
  arrival.at_s = arrival.from_s + planned.route_at_s[1];
  arrival.altitude_m = departure.route_m.front().z();
  // Nearer its stand than this, the clearance's own look covers its way out.
  const double clear_m = kDepartureTransitS * departure.speed_mps;
  std::erase_if(arrivals_,
                [&](const auto& entry) { return entry.second.at_s + kArrivalSlotS <= now_s; });
  for (const auto& [other, slot] : arrivals_) {
    if (other == vehicle) continue;
    const bool same_slot = (slot.at_m - arrival.at_m).norm() < kArrivalReachFactor * reach_m &&
                           std::abs(slot.at_s - arrival.at_s) < kArrivalSlotS;
    const bool same_way =
        std::abs(slot.altitude_m - arrival.altitude_m) < 0.5 * config_.layer_m &&
        WaysOutMeet(arrival, slot, kWayOutReachFactor * reach_m, kWayOutSlotS, clear_m);
    if (same_slot || same_way) {
      ++counts_.takeoffs_held;
      return false;
    }
  }

  const std::vector<Motion> others =
      ClearanceTraffic(tracks_, ghosts_, orders_, departures_, now_s, vehicle);

  std::vector<Box> boxes;
  for (const Motion& other : others) boxes.push_back(Sweep(other, horizon_s));
  for (const double fraction : kStartDelayFractions) {
    const Motion self =
        DepartureMotion(vehicle, departure, departure.stand_m, 0.0, fraction * kStartDelayMaxS);
    const Box box = Sweep(self, horizon_s);
    for (std::size_t k = 0; k < others.size(); ++k) {
      const Motion& other = others[k];
      if (Apart(box, boxes[k], reach_m)) continue;
      if (Closest(self, other, horizon_s, reach_m).distance_m < reach_m) {
        ++counts_.takeoffs_held;
        return false;
      }
    }
  }
  departures_[vehicle] = Reserved{departure, now_s};
  arrivals_[vehicle] = arrival;
  return true;
}

std::vector<AvoidOrder> TrafficControl::Step(double now_s) {
  if (!Due(now_s)) return {};
  last_step_s_ = now_s;
  std::erase_if(ghosts_, [&](const auto& entry) { return entry.second.until_s <= now_s; });
  std::erase_if(orders_, [&](const auto& entry) { return entry.second.until_s <= now_s; });
  std::erase_if(taken_, [&](const auto& entry) { return entry.second.until_s <= now_s; });
  LapseReservations(now_s);
  // Along their routes, as the clearances (departures are theirs alone): a
  // route flown as the navigator flies it (its turns, its layer changes) sees
  // a conflict behind a turn long before straight on would (docs/separation.md).
  std::vector<Motion> motions = Motions(tracks_, ghosts_, orders_, decltype(departures_){}, now_s);
  const double reach_m = config_.separation_m + kPredictionMarginM;
  const auto index_of = [&](int vehicle) -> std::size_t {
    for (std::size_t i = 0; i < motions.size(); ++i) {
      if (motions[i].vehicle == vehicle) return i;
    }
    return motions.size();
  };

  // Every pair predicted inside the limit, soonest first.
  struct Predicted {
    std::pair<int, int> pair;
    Approach approach;
  };
  std::vector<Predicted> predicted;
  std::vector<Box> boxes;
  for (const Motion& m : motions) boxes.push_back(Sweep(m, config_.horizon_s));
  for (std::size_t i = 0; i < motions.size(); ++i) {
    for (std::size_t j = i + 1; j < motions.size(); ++j) {
      if (Apart(boxes[i], boxes[j], reach_m)) continue;
      const Approach approach = Closest(motions[i], motions[j], config_.horizon_s, reach_m);
      if (approach.distance_m >= reach_m) continue;
      predicted.push_back({std::minmax(motions[i].vehicle, motions[j].vehicle), approach});
    }
  }
  std::sort(predicted.begin(), predicted.end(), [](const Predicted& a, const Predicted& b) {
    return std::tie(a.approach.at_s, a.pair) < std::tie(b.approach.at_s, b.pair);
  });

  std::vector<AvoidOrder> out;
  std::map<std::pair<int, int>, bool> still;
  for (const Predicted& p : predicted) {
    still[p.pair] = true;
    auto open = open_.find(p.pair);
    if (open == open_.end()) {
      Conflict conflict;
      conflict.id = static_cast<std::int32_t>(conflicts_dropped_ + conflicts_.size() + 1);
      conflict.vehicle_a = p.pair.first;
      conflict.vehicle_b = p.pair.second;
      conflict.detected_s = now_s;
      conflict.predicted_separation_m = p.approach.distance_m;
      conflict.time_to_closest_s = p.approach.at_s;
      const Motion& a = motions[index_of(p.pair.first)];
      const Motion& b = motions[index_of(p.pair.second)];
      conflict.observed_min_separation_m =
          std::hypot((a.position_m - b.position_m).norm(), a.altitude_m - b.altitude_m);
      conflicts_.push_back(conflict);
      open = open_.emplace(p.pair, conflicts_dropped_ + conflicts_.size() - 1).first;
      ++counts_.conflicts;
      conflicts_.back().version = ++version_;
    }
    if (!config_.resolve) continue;
    const auto last = last_order_s_.find(p.pair);
    if (last != last_order_s_.end() && now_s < last->second + kReorderS) continue;
    // Candidates: either drone (a lost one cannot be told) to above or below the
    // other, or, when it is climbing or descending, to stay where it is.
    struct Candidate {
      int mover = 0;
      double altitude_m = 0.0;
      Resolution resolution = Resolution::kNone;
      double score = std::numeric_limits<double>::infinity();
    };
    Candidate best;
    for (const int mover : {p.pair.second, p.pair.first}) {
      const std::size_t m = index_of(mover);
      const std::size_t o = index_of(mover == p.pair.first ? p.pair.second : p.pair.first);
      if (m == motions.size() || o == motions.size() || motions[m].blind) continue;
      const Motion& self = motions[m];
      const Motion& other = motions[o];
      double other_low = other.AltitudeAt(0.0);
      double other_high = other_low;
      for (double t = 0.0; t <= p.approach.window_end_s + kSampleS; t += 1.0) {
        other_low = std::min(other_low, other.AltitudeAt(t));
        other_high = std::max(other_high, other.AltitudeAt(t));
      }
      std::vector<std::pair<double, Resolution>> targets;
      const double above = other_high + config_.layer_m;
      const double below = other_low - config_.layer_m;
      if (above <= config_.max_altitude_m) targets.emplace_back(above, Resolution::kClimb);
      if (below >= config_.min_altitude_m) targets.emplace_back(below, Resolution::kDescend);
      if (std::abs(self.climb_mps) > 0.5) targets.emplace_back(self.altitude_m, Resolution::kLevel);
      for (const auto& [altitude, resolution] : targets) {
        Motion moved = self;
        moved.Order(altitude, kOrderDelayS);
        double score = std::abs(altitude - self.altitude_m) / config_.layer_m;
        for (std::size_t k = 0; k < motions.size(); ++k) {
          if (k == m || Apart(boxes[m], boxes[k], reach_m)) continue;
          const double k_reach_m = k == o ? reach_m + kResolvedMarginM : reach_m;
          const Approach after = Closest(moved, motions[k], config_.horizon_s, k_reach_m);
          score += Shortfall(after, k_reach_m, config_.horizon_s, k == o ? kPairCost : kOthersCost);
        }
        if (score < best.score) best = {mover, altitude, resolution, score};
      }
    }
    // No order when none is predicted to do better than the drones flying on
    // (too late for any: one told to stay level while climbing away from the
    // other would stay in its way).
    if (best.mover == 0 ||
        best.score >= Shortfall(p.approach, reach_m, config_.horizon_s, kPairCost)) {
      continue;
    }
    // A climb or a descent is held until going back is predicted clear (the
    // release check below), kMaxOrderS at most: ended with the encounter, it
    // sent a drone flying beside the other back down beside it.
    const double order_s =
        best.resolution == Resolution::kLevel
            ? std::clamp(p.approach.window_end_s + kOrderTailS, kMinOrderS, kMaxOrderS)
            : kMaxOrderS;
    orders_[best.mover] = Held{best.altitude_m, now_s + order_s, now_s,
                               best.resolution == Resolution::kLevel, ConflictAt(open->second).id};
    // Later pairs see the order.
    motions[index_of(best.mover)].Order(best.altitude_m, kOrderDelayS);
    last_order_s_[p.pair] = now_s;
    out.push_back({best.mover, best.altitude_m, order_s, ConflictAt(open->second).id,
                   best.resolution == Resolution::kLevel});
    ++counts_.orders;
    Conflict& conflict = ConflictAt(open->second);
    conflict.resolution = best.resolution;
    conflict.mover = best.mover;
    conflict.target_altitude_m = best.altitude_m;
    conflict.order_s = order_s;
    conflict.version = ++version_;
  }

  // What the telemetry says of the open ones; those no longer predicted close.
  for (auto it = open_.begin(); it != open_.end();) {
    Conflict& conflict = ConflictAt(it->second);
    const std::size_t a = index_of(conflict.vehicle_a);
    const std::size_t b = index_of(conflict.vehicle_b);
    const bool both = a < motions.size() && b < motions.size();
    if (both) {
      const double d = std::hypot((motions[a].position_m - motions[b].position_m).norm(),
                                  motions[a].altitude_m - motions[b].altitude_m);
      if (d < conflict.observed_min_separation_m) {
        conflict.observed_min_separation_m = d;
        conflict.version = ++version_;
      }
    }
    // Open until no longer predicted close and past each other (or one gone):
    // a working order takes the pair out of the predictions before it passes.
    const bool passed =
        !both || (motions[b].position_m - motions[a].position_m)
                         .dot(motions[b].velocity_mps - motions[a].velocity_mps) >= 0.0;
    if (still.contains(it->first) || !passed) {
      ++it;
      continue;
    }
    conflict.outcome = conflict.observed_min_separation_m < config_.separation_m
                           ? ConflictOutcome::kLostSeparation
                           : ConflictOutcome::kResolved;
    ++(conflict.outcome == ConflictOutcome::kResolved ? counts_.resolved : counts_.lost_separation);
    conflict.closed_s = now_s;
    conflict.version = ++version_;
    if (conflict.outcome == ConflictOutcome::kLostSeparation && lost_.size() < kKeptLost) {
      lost_.push_back(conflict);
    }
    last_order_s_.erase(it->first);
    it = open_.erase(it);
  }
  // The oldest closed ones go once more are kept (an open one stays, and those
  // after it with it).
  while (conflicts_.size() > kKeptConflicts &&
         conflicts_.front().outcome != ConflictOutcome::kOpen) {
    conflicts_.pop_front();
    ++conflicts_dropped_;
  }

  // A level order holds a take-off or a landing where it is: kept to its end,
  // the drone would hover there for up to kMaxOrderS after the traffic passed.
  // Released when nothing open involves the drone and going on by itself (a
  // take-off as its reserved departure) is predicted clear of the others along
  // their routes: a release clears the drone to go as ClearToDepart does. A
  // climb or a descent likewise, once going back to its own altitudes is
  // predicted clear. Checked again every step until then.
  if (!config_.resolve) return out;
  for (auto held = orders_.begin(); held != orders_.end();) {
    const int vehicle = held->first;
    const bool involved = std::any_of(open_.begin(), open_.end(), [&](const auto& entry) {
      return entry.first.first == vehicle || entry.first.second == vehicle;
    });
    const std::size_t m = index_of(vehicle);
    if (involved || m == motions.size() || (held->second.level && !motions[m].intent_m)) {
      ++held;
      continue;
    }
    const std::vector<Motion> others =
        ClearanceTraffic(tracks_, ghosts_, orders_, departures_, now_s, vehicle);
    const auto reserved = departures_.find(vehicle);
    const Departure* departure =
        reserved == departures_.end() ? nullptr : &reserved->second.departure;
    const double factor = held->second.level ? kReleaseReachFactor : kReturnReachFactor;
    if (!ClearToGoOn(motions[m], departure, others, config_.horizon_s, factor * reach_m)) {
      ++held;
      continue;
    }
    out.push_back({vehicle, 0.0, kReleaseS, held->second.conflict_id});
    ++counts_.releases;
    held = orders_.erase(held);
  }
  return out;
}

}  // namespace fireswarm::server
