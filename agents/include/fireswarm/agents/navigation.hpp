// Waypoint navigation (seed 7.2): the outer loop of the cascade. It turns the
// vehicle's estimate and the route into heading, roll, pitch and altitude
// set-points for the attitude loops (control_cascade.hpp).
//
// Two modes:
//  * kSeed, the seed's strategy: turn toward the waypoint (bearing from seed eq. 1);
//    when the heading error is under 5 deg pitch 15 deg forward, else pitch 0; roll
//    always 0; the next waypoint once closer than 10 m (distance from seed eq. 2-4).
//  * kTrack, for search lanes: hold the straight segment between the previous and
//    the current waypoint. The heading follows the segment's bearing (the camera's
//    footprint stays aligned with the lane); a cross-track PID and an along-track
//    speed PID give a tilt in the segment's frame, rotated into body roll and pitch.
//    The vehicle slows before a sharp corner, so it starts the next lane on it.
//    The PIDs' integral parts are one east/north "wind" integrator, kept across
//    segments: a lawnmower's lanes alternate direction but the wind does not.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "fireswarm/agents/pid.hpp"
#include "fireswarm/agents/pid_gains.hpp"
#include "fireswarm/common/local_frame.hpp"
#include "fireswarm/common/time.hpp"

namespace fireswarm::agents {

/// seed eq. 1: initial great-circle bearing from `from` to `to`, degrees in [0, 360)
/// clockwise from north, on a sphere. Kept for the seed navigation mode only.
double SeedBearingDeg(common::LatLon from, common::LatLon to);

/// seed eq. 2-4: haversine distance in metres with the seed's R = 6,378,137 m.
double SeedDistanceM(common::LatLon from, common::LatLon to);

/// Body roll and pitch that tilt the thrust toward a horizontal direction.
struct BodyTilt {
  double roll_rad = 0.0;
  double pitch_rad = 0.0;  ///< FRD: negative tilts the nose down, flying forward
};

/// The tilt wanted in east/north components (rad; the direction the vehicle should
/// accelerate in, small-angle: tilt ~ acceleration / g), its magnitude limited to
/// `max_tilt_rad`, expressed as body roll and pitch at `heading_rad`.
BodyTilt TiltToBody(double tilt_east_rad, double tilt_north_rad, double heading_rad,
                    double max_tilt_rad);

/// The derivative part of a position loop taken from a measured rate (m/s) instead
/// of differenced positions: kd * rate clamped to [-d_limit, d_limit].
double DampingTilt(const PidGains& gains, double rate);

enum class NavigationMode : std::uint8_t { kSeed = 0, kTrack = 1 };

/// One point of the route the vehicle flies.
struct RoutePoint {
  common::LatLon position;
  double altitude_m = 0.0;  ///< above the ground
  double speed_mps = 0.0;   ///< along-track speed toward this point; 0 = cruise speed
  bool lane_start = false;  ///< the segment leaving this point is a search lane
};

struct NavigationConfig {
  NavigationMode mode = NavigationMode::kTrack;
  double acceptance_radius_m = 10.0;   ///< seed: next waypoint inside 10 m
  double seed_pitch_deg = 15.0;        ///< seed: forward pitch when aligned
  double heading_tolerance_deg = 5.0;  ///< seed: pitch forward under this heading error
  double cruise_speed_mps = 8.0;       ///< track mode, when a point gives no speed
  double max_tilt_rad = 0.44;          ///< track mode: the tilt it asks for at most
  /// Track mode: the deceleration it plans with before a corner, m/s^2.
  double braking_mps2 = 1.5;
  /// Track mode: a turn sharper than this is taken at `corner_speed_mps`.
  double sharp_turn_deg = 20.0;
  double corner_speed_mps = 0.5;
  /// Along-track speed error (m/s) -> forward tilt (rad). Its ki feeds the wind
  /// integrator, whose magnitude is clamped to the larger of the two i_limits.
  PidGains speed;
  /// Cross-track error (m) -> tilt toward the track (rad); kp and kd also hold the
  /// last waypoint after the route. Its ki feeds the wind integrator; its kd
  /// multiplies the GPS cross-track velocity (DampingTilt).
  PidGains cross_track;
};

/// What navigation knows of the vehicle at one step.
struct NavigationInput {
  common::LatLon position;
  common::EastNorth position_local;  ///< the same point in the navigator's frame
  double velocity_east_mps = 0.0;
  double velocity_north_mps = 0.0;
  double heading_rad = 0.0;  ///< clockwise from north
};

/// Set-points for the attitude and altitude loops (FRD: forward flight is
/// negative pitch, roll right positive).
struct NavigationSetpoint {
  double heading_rad = 0.0;
  double roll_rad = 0.0;
  double pitch_rad = 0.0;
  double altitude_m = 0.0;
};

/// Cross-track error statistics over the search lanes flown in track mode.
struct CrossTrackStats {
  std::uint64_t samples = 0;
  double mean_m = 0.0;  ///< of the absolute error
  double rms_m = 0.0;
  double p95_m = 0.0;  ///< to the histogram's 1 cm resolution
  double max_m = 0.0;
};

/// Absolute cross-track errors, kept in a 1 cm histogram so a long mission costs
/// constant memory.
class CrossTrackAccumulator {
 public:
  void Add(double error_m);
  CrossTrackStats Stats() const;
  void Clear();

 private:
  static constexpr double kBinM = 0.01;
  static constexpr std::size_t kBins = 10'000;  // 100 m; beyond goes in the last bin
  std::vector<std::uint32_t> bins_ = std::vector<std::uint32_t>(kBins, 0);
  std::uint64_t count_ = 0;
  double sum_ = 0.0;
  double sum_squares_ = 0.0;
  double max_ = 0.0;
};

class Navigator {
 public:
  /// `frame` is the local frame positions are expressed in (origin at launch).
  Navigator(const NavigationConfig& config, const common::LocalFrame& frame);

  /// Gains, limits and mode; the route and statistics are kept.
  void Configure(const NavigationConfig& config);

  /// Starts `route` at `start_index`; the first segment runs from `from` (where
  /// the vehicle is) to route[start_index]. An empty route finishes at once.
  void SetRoute(std::vector<RoutePoint> route, std::size_t start_index, common::LatLon from);

  /// One navigation step, `dt` after the previous one (seed PID timing).
  /// After the last waypoint it holds the last waypoint's position.
  NavigationSetpoint Step(const NavigationInput& input, common::Micros dt);

  /// Forgets the wind integrator (before a take-off).
  void ResetWindEstimate();
  /// The tilt (east, north; rad) the integrator holds against the wind.
  double wind_tilt_east_rad() const { return wind_tilt_east_; }
  double wind_tilt_north_rad() const { return wind_tilt_north_; }

  std::size_t waypoint_index() const { return index_; }
  bool finished() const { return finished_; }
  bool has_route() const { return !route_.empty(); }
  const std::vector<RoutePoint>& route() const { return route_; }
  /// Signed cross-track error of the last track-mode step (m, right of the track
  /// positive); 0 in seed mode.
  double cross_track_m() const { return cross_track_m_; }
  const CrossTrackAccumulator& cross_track() const { return cross_track_stats_; }
  CrossTrackAccumulator& cross_track() { return cross_track_stats_; }
  const NavigationConfig& config() const { return config_; }

 private:
  NavigationSetpoint StepSeed(const NavigationInput& input);
  NavigationSetpoint StepTrack(const NavigationInput& input, common::Micros dt);
  void Advance();
  void IntegrateWind(double delta_east, double delta_north);
  double TargetSpeed(double distance_to_go_m) const;

  NavigationConfig config_;
  common::LocalFrame frame_;
  std::vector<RoutePoint> route_;
  std::vector<common::EastNorth> route_local_;
  std::size_t index_ = 0;
  bool finished_ = true;
  common::EastNorth segment_start_;
  bool segment_is_lane_ = false;
  double cross_track_m_ = 0.0;
  Pid speed_pid_;
  Pid cross_track_pid_;
  CrossTrackAccumulator cross_track_stats_;
  double wind_tilt_east_ = 0.0;
  double wind_tilt_north_ = 0.0;
};

}  // namespace fireswarm::agents
