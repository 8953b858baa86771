#include "fireswarm/agents/navigation.hpp"

#include <algorithm>
#include <cmath>

#include "fireswarm/common/angles.hpp"

namespace fireswarm::agents {

namespace {

// seed 7.2: "the navigation loop uses the mean radius of earth that is 6378137 meters"
// (it is the WGS84 equatorial radius; kept as the seed has it).
constexpr double kSeedEarthRadiusM = 6378137.0;
// A segment shorter than this has no direction of its own.
constexpr double kMinSegmentM = 0.01;

struct Vec {
  double east = 0.0;
  double north = 0.0;
};
Vec Minus(common::EastNorth a, common::EastNorth b) {
  return {a.east_m - b.east_m, a.north_m - b.north_m};
}
double Norm(Vec v) {
  return std::hypot(v.east, v.north);
}

}  // namespace

double SeedBearingDeg(common::LatLon from, common::LatLon to) {
  // seed eq. 1, as its C++ listing: y = sin(dL) cos(lat2);
  // x = cos(lat1) sin(lat2) - sin(lat1) cos(lat2) cos(dL); bearing = atan2(y, x).
  const double lat1 = from.lat_deg * common::kRadPerDeg;
  const double lat2 = to.lat_deg * common::kRadPerDeg;
  const double delta_lon = (to.lon_deg - from.lon_deg) * common::kRadPerDeg;
  const double y = std::sin(delta_lon) * std::cos(lat2);
  const double x =
      std::cos(lat1) * std::sin(lat2) - std::sin(lat1) * std::cos(lat2) * std::cos(delta_lon);
  // The listing's `(theta * 180 / PI + 360) % 360`.
  return std::fmod(std::atan2(y, x) * common::kDegPerRad + 360.0, 360.0);
}

double SeedDistanceM(common::LatLon from, common::LatLon to) {
  // seed eq. 2-4 (haversine).
  const double lat1 = from.lat_deg * common::kRadPerDeg;
  const double lat2 = to.lat_deg * common::kRadPerDeg;
  const double delta_lat = (to.lat_deg - from.lat_deg) * common::kRadPerDeg;
  const double delta_lon = (to.lon_deg - from.lon_deg) * common::kRadPerDeg;
  const double a =
      std::sin(delta_lat / 2) * std::sin(delta_lat / 2) +
      std::cos(lat1) * std::cos(lat2) * std::sin(delta_lon / 2) * std::sin(delta_lon / 2);
  const double c = 2.0 * std::atan2(std::sqrt(a), std::sqrt(1.0 - a));
  return kSeedEarthRadiusM * c;
}

double DampingTilt(const PidGains& gains, double rate) {
  return std::clamp(gains.kd * rate, -gains.d_limit, gains.d_limit);
}

BodyTilt TiltToBody(double tilt_east_rad, double tilt_north_rad, double heading_rad,
                    double max_tilt_rad) {
  const double tilt = std::hypot(tilt_east_rad, tilt_north_rad);
  if (tilt > max_tilt_rad) {
    tilt_east_rad *= max_tilt_rad / tilt;
    tilt_north_rad *= max_tilt_rad / tilt;
  }
  // Body forward is (sin h, cos h) in east/north, body right (cos h, -sin h).
  const double sin_heading = std::sin(heading_rad);
  const double cos_heading = std::cos(heading_rad);
  BodyTilt body;
  body.pitch_rad = -(tilt_east_rad * sin_heading + tilt_north_rad * cos_heading);
  body.roll_rad = tilt_east_rad * cos_heading - tilt_north_rad * sin_heading;
  return body;
}

void CrossTrackAccumulator::Add(double error_m) {
  const double magnitude = std::abs(error_m);
  const auto bin = std::min(static_cast<std::size_t>(magnitude / kBinM), kBins - 1);
  ++bins_[bin];
  ++count_;
  sum_ += magnitude;
  sum_squares_ += magnitude * magnitude;
  max_ = std::max(max_, magnitude);
}

CrossTrackStats CrossTrackAccumulator::Stats() const {
  CrossTrackStats stats;
  stats.samples = count_;
  if (count_ == 0) return stats;
  const auto n = static_cast<double>(count_);
  stats.mean_m = sum_ / n;
  stats.rms_m = std::sqrt(sum_squares_ / n);
  stats.max_m = max_;
  // The upper edge of the bin holding the 95th percentile.
  const auto rank = static_cast<std::uint64_t>(std::ceil(0.95 * n));
  std::uint64_t seen = 0;
  for (std::size_t bin = 0; bin < kBins; ++bin) {
    seen += bins_[bin];
    if (seen >= rank) {
      stats.p95_m = std::min(static_cast<double>(bin + 1) * kBinM, max_);
      break;
    }
  }
  return stats;
}

void CrossTrackAccumulator::Clear() {
  std::fill(bins_.begin(), bins_.end(), 0U);
  count_ = 0;
  sum_ = sum_squares_ = max_ = 0.0;
}

Navigator::Navigator(const NavigationConfig& config, const common::LocalFrame& frame)
    : frame_(frame) {
  Configure(config);
}

void Navigator::Configure(const NavigationConfig& config) {
  config_ = config;
  // The two PIDs give the proportional and derivative parts in the segment's
  // frame; their integral parts live in one east/north wind integrator instead,
  // which survives segment changes (the wind does not turn with the lane).
  PidGains speed = config_.speed;
  PidGains cross_track = config_.cross_track;
  speed.ki = cross_track.ki = 0.0;
  // The cross-track damping comes from the GPS velocity (0.05 m/s noise), not
  // from differencing positions, whose noise the D term would amplify.
  cross_track.kd = 0.0;
  ApplyGains(speed, speed_pid_);
  ApplyGains(cross_track, cross_track_pid_);
}

void Navigator::SetRoute(std::vector<RoutePoint> route, std::size_t start_index,
                         common::LatLon from) {
  route_ = std::move(route);
  route_local_.clear();
  for (const RoutePoint& point : route_) route_local_.push_back(frame_.ToLocal(point.position));
  index_ = std::min(start_index, route_.size());
  finished_ = index_ >= route_.size();
  segment_start_ = frame_.ToLocal(from);
  segment_is_lane_ = false;
  speed_pid_.Reset();
  cross_track_pid_.Reset();
}

void Navigator::Advance() {
  segment_start_ = route_local_[index_];
  segment_is_lane_ = route_[index_].lane_start;
  ++index_;
  if (index_ >= route_.size()) {
    finished_ = true;
    index_ = route_.size() - 1;
  }
  cross_track_pid_.Reset();
}

void Navigator::IntegrateWind(double delta_east, double delta_north) {
  wind_tilt_east_ += delta_east;
  wind_tilt_north_ += delta_north;
  const double limit = std::max(config_.cross_track.i_limit, config_.speed.i_limit);
  const double magnitude = std::hypot(wind_tilt_east_, wind_tilt_north_);
  if (magnitude > limit) {
    wind_tilt_east_ *= limit / magnitude;
    wind_tilt_north_ *= limit / magnitude;
  }
}

void Navigator::ResetWindEstimate() {
  wind_tilt_east_ = wind_tilt_north_ = 0.0;
}

NavigationSetpoint Navigator::Step(const NavigationInput& input, common::Micros dt) {
  if (route_.empty()) {
    NavigationSetpoint hold;
    hold.heading_rad = input.heading_rad;
    return hold;
  }
  if (!finished_ && config_.mode == NavigationMode::kSeed) return StepSeed(input);
  return StepTrack(input, dt);
}

NavigationSetpoint Navigator::StepSeed(const NavigationInput& input) {
  if (SeedDistanceM(input.position, route_[index_].position) < config_.acceptance_radius_m) {
    Advance();
    if (finished_) return StepTrack(input, common::Micros{0.0});
  }
  const RoutePoint& target = route_[index_];
  NavigationSetpoint setpoint;
  setpoint.heading_rad = SeedBearingDeg(input.position, target.position) * common::kRadPerDeg;
  setpoint.altitude_m = target.altitude_m;
  // seed 7.2: roll is always zero; pitch 15 deg forward once the heading error is
  // under 5 deg, zero otherwise (so it does not overshoot while it turns).
  const double heading_error = std::abs(common::WrapPi(setpoint.heading_rad - input.heading_rad));
  const bool aligned = heading_error < config_.heading_tolerance_deg * common::kRadPerDeg;
  setpoint.pitch_rad = aligned ? -config_.seed_pitch_deg * common::kRadPerDeg : 0.0;
  cross_track_m_ = 0.0;
  return setpoint;
}

double Navigator::TargetSpeed(double distance_to_go_m) const {
  const RoutePoint& target = route_[index_];
  const double cruise = target.speed_mps > 0.0 ? target.speed_mps : config_.cruise_speed_mps;
  double end_speed = 0.0;  // stop at the last waypoint
  if (!finished_ && index_ + 1 < route_.size()) {
    const Vec in = Minus(route_local_[index_], segment_start_);
    const Vec out = Minus(route_local_[index_ + 1], route_local_[index_]);
    const double turn_rad =
        std::abs(common::WrapPi(std::atan2(out.east, out.north) - std::atan2(in.east, in.north)));
    const bool sharp = Norm(in) < kMinSegmentM || Norm(out) < kMinSegmentM ||
                       turn_rad > config_.sharp_turn_deg * common::kRadPerDeg;
    end_speed = sharp ? config_.corner_speed_mps : cruise;
  }
  const double braking_speed = std::sqrt(
      end_speed * end_speed + 2.0 * config_.braking_mps2 * std::max(distance_to_go_m, 0.0));
  return std::min(cruise, braking_speed);
}

NavigationSetpoint Navigator::StepTrack(const NavigationInput& input, common::Micros dt) {
  const common::EastNorth here = input.position_local;
  const common::EastNorth target = route_local_[index_];
  Vec along_unit;
  double distance_to_go = 0.0;
  double cross_track = 0.0;
  const Vec segment = Minus(target, segment_start_);
  const double length = Norm(segment);
  if (!finished_) {
    if (length >= kMinSegmentM) {
      along_unit = {segment.east / length, segment.north / length};
      const Vec from_start = Minus(here, segment_start_);
      const double along = from_start.east * along_unit.east + from_start.north * along_unit.north;
      // Right of the track: the along direction turned 90 deg clockwise.
      cross_track = from_start.east * along_unit.north - from_start.north * along_unit.east;
      distance_to_go = length - along;
    }
    if (length < kMinSegmentM || distance_to_go <= 0.0) {
      Advance();
      return StepTrack(input, dt);
    }
  }

  NavigationSetpoint setpoint;
  setpoint.altitude_m = route_[index_].altitude_m;
  const double dt_s = std::max(dt.count(), 0.0) * 1e-6;
  double tilt_east = 0.0;
  double tilt_north = 0.0;
  if (finished_) {
    // Hold the last waypoint: a PD on the position error in east/north, plus the
    // wind integrator driven by the same error.
    const Vec error = Minus(target, here);
    const PidGains& gains = config_.cross_track;
    tilt_east = gains.kp * error.east - gains.kd * input.velocity_east_mps;
    tilt_north = gains.kp * error.north - gains.kd * input.velocity_north_mps;
    IntegrateWind(gains.ki * error.east * dt_s, gains.ki * error.north * dt_s);
    setpoint.heading_rad = input.heading_rad;
    cross_track_m_ = 0.0;
  } else {
    const double speed_along =
        input.velocity_east_mps * along_unit.east + input.velocity_north_mps * along_unit.north;
    const double target_speed = TargetSpeed(distance_to_go);
    const double tilt_along = speed_pid_.Update(speed_along, target_speed, dt);
    const double cross_track_rate =
        input.velocity_east_mps * along_unit.north - input.velocity_north_mps * along_unit.east;
    const double tilt_right = cross_track_pid_.Update(cross_track, 0.0, dt) -
                              DampingTilt(config_.cross_track, cross_track_rate);
    // Right of the track is (along.north, -along.east); the error toward the
    // track is -cross_track along it.
    const double toward_track = -config_.cross_track.ki * cross_track * dt_s;
    const double speed_up = config_.speed.ki * (target_speed - speed_along) * dt_s;
    IntegrateWind(toward_track * along_unit.north + speed_up * along_unit.east,
                  -toward_track * along_unit.east + speed_up * along_unit.north);
    tilt_east = tilt_along * along_unit.east + tilt_right * along_unit.north;
    tilt_north = tilt_along * along_unit.north - tilt_right * along_unit.east;
    setpoint.heading_rad = std::atan2(along_unit.east, along_unit.north);
    cross_track_m_ = cross_track;
    if (segment_is_lane_) cross_track_stats_.Add(cross_track);
  }
  tilt_east += wind_tilt_east_;
  tilt_north += wind_tilt_north_;
  const BodyTilt body = TiltToBody(tilt_east, tilt_north, input.heading_rad, config_.max_tilt_rad);
  setpoint.roll_rad = body.roll_rad;
  setpoint.pitch_rad = body.pitch_rad;
  return setpoint;
}

}  // namespace fireswarm::agents
