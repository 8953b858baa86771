// Investigations: which vehicle is sent to look again at a fire, whether it may
// go there past the no-fly zones, and the verdict on its track when it is back.
// A pure core beside FireFusion, MissionManager and VehicleRegistry: it reads
// the registry and the fusion it is handed, and gives back the commands to send
// and the tracks to reject; the server sends, rejects and journals them.
//
// Choosing: the nearest searching vehicle with a good link, not low on battery
// and not investigating already; another than the reporter when one exists (its
// GPS error is independent).
//
// No-fly zones: a vehicle ordered to investigate flies straight from where it is
// to the circle's nearest point, circles, and flies straight back to where it
// left its lane (agents' investigate behaviour); all of it must stay out of
// every zone, so a vehicle is sent only when the convex hull of where it is and
// the circle enters none.
//
// Verdict: a track that is still tentative when its investigation is over (plus
// a grace for reports still in the air), with no report from an investigator
// that did get near it, is rejected (the hot spot was not seen again: a
// sun-heated rock). An investigator that never got near (called away, lost)
// judges nothing: the track stays tentative.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "fireswarm/common/local_frame.hpp"
#include "fireswarm/common/time.hpp"
#include "fireswarm/planner/geometry.hpp"
#include "fireswarm/planner/transit.hpp"
#include "fireswarm/radio/master_scheduler.hpp"
#include "fireswarm/radio/messages.hpp"
#include "fireswarm/server/fire_fusion.hpp"
#include "fireswarm/server/vehicle_registry.hpp"

namespace fireswarm::server {

/// The longest investigation a command can carry, s (Command::duration_s is 16 bits).
inline constexpr double kMaxInvestigateS = 65'535.0;

/// What Investigations needs of ServerConfig (which documents each field).
struct InvestigationsConfig {
  double investigate_s = 60.0;           ///< loiter time of an investigation, s
  double investigate_transit_mps = 8.0;  ///< assumed transit speed to the circle, m/s
  double investigate_near_m = 60.0;      ///< closer than this, the investigator judges, m
  double investigate_radius_m = 0.0;     ///< 0: the vehicle's own loiter radius
  double reject_grace_s = 10.0;          ///< verdict this long after the investigation, s
  planner::MultiPolygon no_fly;          ///< local (x east, y north) m; empty: none
};

/// An investigation the server ordered.
struct Investigation {
  std::uint8_t vehicle = 0;
  std::int32_t track_id = 0;  ///< 0: an operator's point, not a track
  double started_s = 0.0;
  /// When the vehicle stops circling: the order's time, the transit to the circle
  /// at investigate_transit_mps, and investigate_s around it.
  double until_s = 0.0;
  /// The point circled, local (east, north) m.
  Eigen::Vector2d point_en_m = Eigen::Vector2d::Zero();
  /// Closest the vehicle's telemetry came to the point during the investigation, m.
  double closest_m = std::numeric_limits<double>::infinity();
  /// The verdict on its track has been drawn (rejected, seen again, or not
  /// judged because the vehicle never got near): the server no longer waits.
  bool judged = false;
};

/// An order to investigate: the command for the vehicle and what was opened.
struct InvestigationOrder {
  radio::Command command;
  Investigation investigation;
};

/// A track rejected by its investigation's verdict.
struct Rejection {
  std::int32_t track_id = 0;
  std::uint8_t by_vehicle = 0;
};

class Investigations {
 public:
  /// `frame`: the local frame of the fusion's positions. `transit`: the planner
  /// around config.no_fly (null when there are none); it must outlive this object.
  Investigations(InvestigationsConfig config, const common::LocalFrame& frame,
                 const planner::TransitPlanner* transit);

  /// The circle's radius, m: `ordered_radius_m` when positive, else the
  /// configured one, else the vehicle's default loiter radius (20 m).
  double RadiusM(double ordered_radius_m) const;
  /// Why no vehicle may circle `point_en_m` (local east, north m) at `radius_m`:
  /// the point or the circle is in a no-fly zone. nullopt: it may.
  std::optional<std::string> CircleRefusal(const Eigen::Vector2d& point_en_m,
                                           double radius_m) const;
  /// Why `vehicle` may not be sent to that circle: its way there or back crosses
  /// a no-fly zone, or it has sent no position to check that by. nullopt: it may.
  std::optional<std::string> ApproachRefusal(const VehicleRegistry& registry, std::uint8_t vehicle,
                                             const Eigen::Vector2d& point_en_m,
                                             double radius_m) const;
  /// The vehicle to send to the circle at `now_s` (see the file comment), or
  /// nullopt with the reason in `why_none` (when given).
  std::optional<std::uint8_t> BestPlacedFor(const VehicleRegistry& registry,
                                            const Eigen::Vector2d& point_en_m, double radius_m,
                                            std::uint8_t reporter, double now_s,
                                            std::string* why_none) const;

  /// Opens an investigation of `point` by `vehicle` at `now_s` for `track_id`
  /// (0: an operator's point) and returns the command to send it. Its duration
  /// counts the vehicle's transit from where its telemetry last put it.
  InvestigationOrder Open(const VehicleRegistry& registry, std::uint8_t vehicle,
                          common::LatLon point, double radius_m, std::int32_t track_id,
                          double now_s);
  /// Puts back an investigation a previous server opened (its journal), as it was opened.
  void Restore(const Investigation& investigation);

  /// A vehicle's position `where_en_m` (local east, north m) at `now_s`: how
  /// close its open investigations have come.
  void OnPosition(std::uint8_t vehicle, const Eigen::Vector2d& where_en_m, double now_s);
  /// `track_id` was confirmed at `now_s`: its investigations still running end
  /// now. Returns their vehicles, in order, to be sent back to their lanes.
  std::vector<std::uint8_t> EndForConfirmed(std::int32_t track_id, double now_s);
  /// The operator took `vehicle` off its work at `now_s` (a hold, resume, return or
  /// land): its investigations still running end now and judge nothing, so their
  /// tracks stay tentative (it did not look for as long as it was sent to).
  void CallOff(std::uint8_t vehicle, double now_s);
  /// Draws the verdicts due by `now`: tentative tracks not seen again by an
  /// investigator that got near are rejected in `fusion`; returns them in order.
  std::vector<Rejection> Judge(common::Nanos now, FireFusion& fusion);
  /// The earliest verdict still awaited on a tentative track of `fusion`, or `next`.
  common::Nanos NextVerdict(const FireFusion& fusion, common::Nanos next) const;

  const std::vector<Investigation>& all() const { return investigations_; }

 private:
  common::Nanos VerdictDue(const Investigation& investigation) const;

  InvestigationsConfig config_;
  common::LocalFrame frame_;
  const planner::TransitPlanner* transit_;
  std::vector<Investigation> investigations_;
};

}  // namespace fireswarm::server
