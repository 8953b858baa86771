// Keeping the drones apart: the separation rules every drone flies by, and the
// server's tactical resolution of the conflicts its telemetry still predicts.
//
// Strategic (airspace.hpp) gives each drone altitude layers before it flies.
// Tactical (TrafficControl, here) watches the fleet from telemetry: from each
// drone's reported position and velocity, and its route ahead flown as its
// navigator flies it, it predicts every pair's closest approach over
// `horizon_s`, and when that falls under `separation_m` it orders one drone of
// the pair to another altitude (radio CommandType::kAvoid) for as long as the
// encounter lasts. The order goes out urgent on the shared channel;
// the horizon covers the telemetry's age, the order's wait for its turn and the
// climb itself (docs/separation.md has the budget).
//
// A lost drone (no telemetry for the registry's lost time) flies home by itself
// at its return layer (agents' return to launch); the server predicts that way
// home and keeps the others off it.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace fireswarm::server {

/// The separation rules (scenario key `separation`, docs/scenario.md).
struct SeparationConfig {
  /// No two airborne drones closer than this, m (3-D distance).
  double separation_m = 10.0;
  /// Vertical spacing of the altitude layers, m: more than separation_m, as a
  /// drone's altitude hold wanders about +-2 m around its target.
  double layer_m = 15.0;
  /// Search altitudes: the fleet's altitude plus layer_m * (k % search_layers).
  int search_layers = 3;
  /// Transit layers above the search layers: one per heading sector of
  /// 360 / transit_sectors degrees, so head-on traffic never shares a layer.
  int transit_sectors = 4;
  /// A leg that is not a search lane and at least this long is a transit, m.
  double transit_min_m = 200.0;
  /// How far ahead the tactical watch predicts closest approaches, s.
  double horizon_s = 30.0;
  /// Tactical resolution on (false: conflicts are still predicted and counted,
  /// no order is sent: the benchmark's "without resolution").
  bool resolve = true;
  /// Strategic layers on (false: every drone at the fleet's altitude).
  bool layers = true;
  /// Take-offs sequenced: a drone is told to start only when its climb and the
  /// first stretch of its way out are predicted clear of every drone flying and
  /// of every take-off cleared before it (TrafficControl::ClearToDepart).
  bool sequence_takeoffs = true;
  /// Resolutions never send a drone above this or below min_altitude_m, m.
  double max_altitude_m = 300.0;
  double min_altitude_m = 30.0;
  /// Throws std::invalid_argument naming the field.
  void Validate() const;
};

/// What one drone's telemetry says, in the server's local frame.
struct TrafficSample {
  Eigen::Vector3d position_m = Eigen::Vector3d::Zero();  ///< east, north, up
  Eigen::Vector3d velocity_mps = Eigen::Vector3d::Zero();
  double at_s = 0.0;  ///< mission time the sample describes
  /// Where the drone is climbing or descending to by itself, m: a take-off's
  /// climb-out altitude, a landing's ground (0), a return's way-home layer.
  /// Predicted all the way there; without it a reported climb is carried on for
  /// a few seconds only (a change of layer ends soon).
  std::optional<double> intent_altitude_m;
  /// The waypoints ahead (east, north, up), the one it flies to first, while it
  /// flies its mission's route (or its way home) at route_speed_mps; empty
  /// otherwise. The watch and the clearances predict it along them.
  std::vector<Eigen::Vector3d> route_m;
  double route_speed_mps = 0.0;
  /// It stops at the route's last point (its stand, on its way home); otherwise
  /// it flies on there.
  bool route_stops = false;
  /// It holds its position where it is (a landing comes straight down over the
  /// point where it began): its reported horizontal drift is not carried on.
  bool holds_position = false;
  /// It is taking off: it climbs where it is to route_m's first altitude (its
  /// climb-out), then flies route_m (its sortie from the first waypoint).
  bool departing = false;
};

enum class Resolution : std::uint8_t {
  kNone = 0,     ///< predicted and watched, no order (resolve off, or nothing helps)
  kClimb = 1,    ///< the mover climbs to target_altitude_m
  kDescend = 2,  ///< the mover descends to target_altitude_m
  kLevel = 3,    ///< the mover stays at target_altitude_m (a take-off, a landing waits)
};
/// "none", "climb", "descend", "level".
const char* ToString(Resolution resolution);

enum class ConflictOutcome : std::uint8_t {
  kOpen = 0,            ///< still ahead or under way
  kResolved = 1,        ///< passed, never closer than separation_m as reported
  kLostSeparation = 2,  ///< passed, reported closer than separation_m
};
/// "open", "resolved", "lost_separation".
const char* ToString(ConflictOutcome outcome);

/// One predicted conflict between two drones, from detection to its outcome.
struct Conflict {
  std::int32_t id = 0;  ///< 1, 2, ... in detection order
  int vehicle_a = 0;    ///< the lower receiver ID
  int vehicle_b = 0;
  double detected_s = 0.0;              ///< mission time
  /// At the closest approach, as first predicted; its horizontal part counted
  /// short by the allowance for GPS noise (docs/separation.md).
  double predicted_separation_m = 0.0;
  double time_to_closest_s = 0.0;       ///< from detection
  Resolution resolution = Resolution::kNone;
  int mover = 0;  ///< the drone ordered (0: none)
  double target_altitude_m = 0.0;
  double order_s = 0.0;  ///< how long the order holds, s
  ConflictOutcome outcome = ConflictOutcome::kOpen;
  /// The closest the pair came as their telemetry reported it, since detection, m.
  double observed_min_separation_m = 0.0;
  double closed_s = 0.0;      ///< mission time of the outcome (0 while open)
  std::uint64_t version = 0;  ///< TrafficControl::version() when it last changed
};

/// An order to send: vehicle flies at altitude_m for duration_s (kAvoid).
/// altitude_m 0 ends the vehicle's standing order now (a release; the vehicle
/// refuses a duration of 0, so a release carries 1 s).
struct AvoidOrder {
  int vehicle = 0;
  double altitude_m = 0.0;  ///< 0: a release (the standing order ends)
  double duration_s = 0.0;
  std::int32_t conflict_id = 0;
  bool level = false;  ///< Resolution::kLevel: held where it is until released
};

/// A take-off the server is about to order: from its stand the drone climbs
/// straight up to its first waypoint's altitude, then flies its waypoints at
/// speed_mps.
struct Departure {
  Eigen::Vector2d stand_m = Eigen::Vector2d::Zero();  ///< east, north
  /// Its sortie's waypoints from the first (east, north, up); at least one.
  std::vector<Eigen::Vector3d> route_m;
  double speed_mps = 0.0;
};

/// Counts for the report and radio_stats-like summaries.
struct TrafficCounts {
  std::uint64_t conflicts = 0;  ///< predicted
  std::uint64_t orders = 0;     ///< avoid orders handed to the radio
  std::uint64_t resolved = 0;
  std::uint64_t lost_separation = 0;
  std::uint64_t takeoffs_held = 0;  ///< take-off clearances refused (asked again later)
  /// Level orders ended early (AvoidOrder with altitude 0): the conflict had closed.
  std::uint64_t releases = 0;
  /// Orders and releases the vehicle never took (TrafficControl::Taken).
  std::uint64_t not_taken = 0;
};

class TrafficControl {
 public:
  /// Throws std::invalid_argument as SeparationConfig::Validate.
  explicit TrafficControl(const SeparationConfig& config);

  /// A drone's telemetry while it flies.
  void Observe(int vehicle, const TrafficSample& sample);
  /// The drone is on the ground (or gone): no longer traffic.
  void Forget(int vehicle);
  /// The drone is lost: from `last` (its last telemetry, with the route ahead
  /// when it flew one) it flies on along that route until `turns_home_s` (when
  /// the vehicle's own lost-link return starts: it has not heard the server
  /// for its link_lost_timeout_s), then straight home to `home_m` (east, north)
  /// at `altitude_m` and `speed_mps`, and lands there; the others are kept off
  /// that way until `until_s`.
  void ExpectLost(int vehicle, const TrafficSample& last, const Eigen::Vector2d& home_m,
                  double altitude_m, double speed_mps, double turns_home_s, double until_s);
  /// The latest sample observed of a drone watched as flying, else nullptr.
  const TrafficSample* Last(int vehicle) const {
    const auto found = tracks_.find(vehicle);
    return found == tracks_.end() ? nullptr : &found->second;
  }
  /// Whether `vehicle` is watched as flying (not lost, not on the ground).
  bool Flying(int vehicle) const { return tracks_.contains(vehicle); }
  bool Lost(int vehicle) const { return ghosts_.contains(vehicle); }

  /// Whether `vehicle` may take off at `now_s`: its departure (the climb from a
  /// start within kStartDelayMaxS, then kDepartureTransitS along its waypoints)
  /// is predicted to keep the limit from every drone flying (along its route
  /// when it flies one, else straight on), every lost drone's way home and every
  /// departure cleared before it. Throws std::invalid_argument for a departure
  /// without waypoints. A clear departure is reserved:
  /// later clearances keep off it until the drone's telemetry shows it on its way
  /// at speed (or kDepartureHoldS after its clearance, unless an avoid order
  /// holds it then). A departure is also held while another cleared before it
  /// is predicted to reach a first waypoint within kArrivalReachFactor times
  /// the conflict reach of its own less than kArrivalSlotS before or after it
  /// (neighbours whose lanes start at one corner would fly the whole way out
  /// side by side and meet there), and while its way out (from over its stand
  /// straight to its first waypoint, at that waypoint's altitude) is predicted
  /// to pass within kWayOutReachFactor conflict reaches of another cleared way
  /// out in the same layer less than kWayOutSlotS before or after it, beyond
  /// the stretch the clearance looks at (kDepartureTransitS at its speed): two
  /// drones bound the same way in one layer would fly it abreast, or converge
  /// on it. A refusal is counted (counts().takeoffs_held); ask again later.
  bool ClearToDepart(int vehicle, const Departure& departure, double now_s);
  /// Arrivals at nearby first waypoints are kept this far apart, s.
  static constexpr double kArrivalSlotS = 30.0;
  /// First waypoints this many conflict reaches apart (39 m by default) or
  /// nearer share their arrival slots.
  static constexpr double kArrivalReachFactor = 3.0;
  /// Ways out in one layer that pass this many conflict reaches apart (26 m by
  /// default) or nearer are kept kWayOutSlotS apart in time there.
  static constexpr double kWayOutReachFactor = 2.0;
  static constexpr double kWayOutSlotS = 20.0;
  /// The longest a start command takes from the server's decision to the
  /// vehicle's climb (a wait for its radio turn, a resend), s.
  static constexpr double kStartDelayMaxS = 8.0;
  /// How much of the way out, after the climb, a clearance looks at, s.
  static constexpr double kDepartureTransitS = 20.0;
  /// A reservation lapses this long after its clearance at the latest, s.
  static constexpr double kDepartureHoldS = 120.0;

  /// Predicts, opens and closes conflicts at `now_s`; the orders to send now.
  /// A level order (a take-off or landing held where it is) is released as soon
  /// as no open conflict involves its drone and its own climb or descent from
  /// there is predicted clear of every other drone; a climb or descent order
  /// runs its course (the drone flies on along its route meanwhile, at the
  /// ordered altitude).
  /// Runs at most every kStepS (earlier calls return nothing).
  std::vector<AvoidOrder> Step(double now_s);
  static constexpr double kStepS = 0.5;
  /// What became of `order` (one Step() returned) at `now_s`: the vehicle
  /// acknowledged it (`taken`), or not (the radio gave up after its resends,
  /// or the vehicle refused it). The watch predicts each drone holding the
  /// order it last took: one not taken is dropped (the drone flies on as it
  /// did, and its conflicts may be resolved again at once, not kReorderS
  /// later); after a release not taken the drone still holds its order until
  /// the release check lets it go again. Without these reports the watch
  /// takes every order as delivered.
  void Taken(const AvoidOrder& order, bool taken, double now_s);

  /// Whether Step(now_s) would run (kStepS since the last that did).
  bool Due(double now_s) const { return now_s >= last_step_s_ + kStepS; }

  /// Every open conflict and the latest closed ones, kKeptConflicts in all at
  /// most (more only while more are open), in detection order: a server on
  /// watch for days keeps what an operator looks at, and counts() the rest.
  const std::deque<Conflict>& conflicts() const { return conflicts_; }
  static constexpr std::size_t kKeptConflicts = 1'000;
  /// The conflicts that lost separation, in the order they closed: the first
  /// kKeptLost of them (counts().lost_separation counts them all).
  const std::vector<Conflict>& lost() const { return lost_; }
  static constexpr std::size_t kKeptLost = 1'000;
  /// Rises whenever a conflict is added or changes.
  std::uint64_t version() const { return version_; }
  const TrafficCounts& counts() const { return counts_; }
  const SeparationConfig& config() const { return config_; }

 private:
  SeparationConfig config_;
  std::map<int, TrafficSample> tracks_;
  struct Ghost {
    TrafficSample last;
    Eigen::Vector2d home_m = Eigen::Vector2d::Zero();
    double altitude_m = 0.0;
    double speed_mps = 0.0;
    double until_s = 0.0;
    // Its way from `last` when it flew a route: the route up to where it
    // turns home, then home at altitude_m (empty: straight home from `last`).
    std::vector<Eigen::Vector3d> way_m;
  };
  std::map<int, Ghost> ghosts_;
  struct Held {
    double altitude_m = 0.0;
    double until_s = 0.0;
    double from_s = 0.0;  // when it was ordered
    bool level = false;   // Resolution::kLevel: released when its conflict is over
    std::int32_t conflict_id = 0;
  };
  struct Reserved {
    Departure departure;
    double cleared_s = 0.0;
  };
  std::map<int, Reserved> departures_;  // cleared take-offs not yet on their way
  // A cleared departure's way out: from over its stand (at from_s, the climb
  // done) straight to its first waypoint (at_m, at at_s), at altitude_m.
  struct Arrival {
    Eigen::Vector2d from_m = Eigen::Vector2d::Zero();  // its stand (east, north)
    double from_s = 0.0;
    Eigen::Vector2d at_m = Eigen::Vector2d::Zero();  // the first waypoint (east, north)
    double at_s = 0.0;                               // predicted there
    double altitude_m = 0.0;
  };
  // Whether two ways out in one layer pass within reach_m of each other less
  // than slot_s apart, farther than clear_m from both stands.
  static bool WaysOutMeet(const Arrival& a, const Arrival& b, double reach_m, double slot_s,
                          double clear_m);
  std::map<int, Arrival> arrivals_;  // vehicle -> its latest cleared departure's
  // Drops the reservations older than kDepartureHoldS, but not of a drone an
  // avoid order holds.
  void LapseReservations(double now_s);
  std::map<int, Held> orders_;  // vehicle -> its standing avoid order
  std::map<int, Held> taken_;   // vehicle -> the order it last acknowledged
  // pair -> its conflict's index among every conflict ever opened (id - 1)
  std::map<std::pair<int, int>, std::size_t> open_;
  std::map<std::pair<int, int>, double> last_order_s_;  // pair -> when it was last resolved
  double last_step_s_ = -1.0e9;
  std::deque<Conflict> conflicts_;
  std::size_t conflicts_dropped_ = 0;  // the oldest closed ones, gone from conflicts_
  Conflict& ConflictAt(std::size_t index) { return conflicts_[index - conflicts_dropped_]; }
  std::vector<Conflict> lost_;
  std::uint64_t version_ = 0;
  TrafficCounts counts_;
};

}  // namespace fireswarm::server
