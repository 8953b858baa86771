// The vehicle's control step and behaviours: which set-points each flight mode
// hands the cascade, the commands that switch modes, and the safety rules that
// override them (return to launch on low battery or a silent server).
#include <algorithm>
#include <cmath>

#include "fireswarm/agents/vehicle.hpp"
#include "fireswarm/common/time.hpp"

namespace fireswarm::agents {

namespace {

using radio::FlightMode;

// Take-off ends, and the search starts, this close below the target altitude.
constexpr double kTakeoffDoneBelowM = 1.5;
// Return to launch ends, and landing starts, this close to home.
constexpr double kHomeReachedM = 2.0;
// Landing slows to this descent rate below kSlowDescentBelowM (touchdown gently:
// the airframe crashes above 2.5 m/s).
constexpr double kSlowDescentMps = 0.5;
constexpr double kSlowDescentBelowM = 3.0;
// Landed: the (low-passed) altitude has not fallen by kLandProgressM for
// kLandedAfterS while descending. Works whatever the barometer's drift.
constexpr double kLandProgressM = 0.2;
constexpr double kLandedAfterS = 3.0;
// An investigation farther than this outside its circle flies there first on the
// navigator at cruise speed, and circles from there on (the loiter's radial
// control spirals in slowly from afar: a far investigator never arrived), m.
constexpr double kLoiterCaptureM = 10.0;
// On the ground, a pack at least this full is a fresh one (a battery swap between
// sorties): the low-battery state that sent the vehicle home is over. The server
// starts the next sortie at the same level (server::kFreshPackPercent).
constexpr double kFreshPackFraction = 0.95;

// A waypoint without an altitude (0) is flown at `default_altitude_m`.
std::vector<RoutePoint> RouteOf(const Mission& mission, double default_altitude_m) {
  std::vector<RoutePoint> route;
  route.reserve(mission.waypoints.size());
  for (const radio::Waypoint& waypoint : mission.waypoints) {
    RoutePoint point;
    point.position = {waypoint.lat_deg, waypoint.lon_deg};
    point.altitude_m = waypoint.altitude_m > 0.0 ? waypoint.altitude_m : default_altitude_m;
    point.speed_mps = waypoint.speed_mps;
    point.lane_start = (waypoint.flags & radio::Waypoint::kLaneStart) != 0;
    route.push_back(point);
  }
  return route;
}

}  // namespace

bool Vehicle::Airborne() const {
  return mode_ != FlightMode::kIdle && mode_ != FlightMode::kLanded;
}

NavigationInput Vehicle::NavInput() const {
  const Estimate& state = estimator_.estimate();
  NavigationInput input;
  input.position = estimator_.position();
  input.position_local = state.position_local;
  input.velocity_east_mps = state.velocity_east_mps;
  input.velocity_north_mps = state.velocity_north_mps;
  input.heading_rad = state.attitude.heading_rad;
  return input;
}

void Vehicle::StartRoute(std::vector<RoutePoint> route, std::size_t start_index) {
  navigator_->SetRoute(std::move(route), start_index, estimator_.position());
}

void Vehicle::HoldHere(double altitude_m) {
  RoutePoint here;
  here.position = estimator_.position();
  here.altitude_m = altitude_m;
  StartRoute({here}, 0);
}

double Vehicle::ReturnSpeedMps() const {
  const Mission* mission = missions_.IsComplete(active_mission_) ? missions_.complete() : nullptr;
  if (mission != nullptr && !mission->waypoints.empty()) {
    const std::size_t index = std::min(resume_index_, mission->waypoints.size() - 1);
    if (mission->waypoints[index].speed_mps > 0.0) return mission->waypoints[index].speed_mps;
  }
  return 0.0;  // the navigator's cruise speed (nav.cruise_speed_mps)
}

double Vehicle::ReturnAltitudeM() const {
  const Mission* mission = missions_.IsComplete(active_mission_) ? missions_.complete() : nullptr;
  double altitude_m = navigation_setpoint_.altitude_m;
  if (mission != nullptr && !mission->waypoints.empty() &&
      mission->waypoints.back().altitude_m > 0.0) {
    altitude_m = mission->waypoints.back().altitude_m;
  }
  return std::max(altitude_m, Param(ParamId::kTakeoffAltitudeM));
}

double Vehicle::ClimbOutAltitudeM() const {
  const Mission* mission = missions_.IsComplete(active_mission_) ? missions_.complete() : nullptr;
  if (mission != nullptr && !mission->waypoints.empty() &&
      mission->waypoints.front().altitude_m > 0.0) {
    return mission->waypoints.front().altitude_m;
  }
  return Param(ParamId::kTakeoffAltitudeM);
}

void Vehicle::EnterMode(FlightMode mode, Nanos now) {
  const Estimate& state = estimator_.estimate();
  // Leaving the search (for a hold, a loiter, a return): remember where to resume,
  // and the very point it left the route (unless it was still rejoining it).
  if (mode_ == FlightMode::kSearch && mode != FlightMode::kSearch && navigator_) {
    if (!rejoining_) {
      resume_index_ = navigator_->waypoint_index();
      rejoin_at_ = estimator_.position();
    }
    rejoining_ = false;
  }
  mode_ = mode;
  mode_since_ = now;
  switch (mode) {
    case FlightMode::kTakeoff:
      home_ = estimator_.position();
      estimator_.ZeroAltitude();
      cascade_.Reset();
      navigator_->ResetWindEstimate();
      // Straight up over the stand to its own altitude layer (the first
      // waypoint's), and only then toward the first waypoint: neighbours that
      // leave together turn away in different layers.
      HoldHere(ClimbOutAltitudeM());
      break;
    case FlightMode::kSearch:
      // Back to the point it left the route first: straight to the next waypoint
      // would cut the rest of the lane it was sweeping, unseen.
      if (rejoin_at_) {
        // At the altitude of the waypoint it resumes (its lane's layer), the
        // one it flies as soon as it is back: the server predicts it so.
        // Where an investigation or an avoid order happened to leave it (seed
        // 32 of bench/scenarios/separation120.yaml: 82.9 m, halfway down to
        // its lane at 75 m), it flew back 7.6 m under drone 21's layer.
        const std::vector<RoutePoint> route =
            RouteOf(*missions_.complete(), Param(ParamId::kTakeoffAltitudeM));
        RoutePoint rejoin;
        rejoin.position = *rejoin_at_;
        rejoin.altitude_m = resume_index_ < route.size() ? route[resume_index_].altitude_m
                                                         : state.altitude_m;
        StartRoute({rejoin}, 0);
        rejoining_ = true;
      } else {
        StartRoute(RouteOf(*missions_.complete(), Param(ParamId::kTakeoffAltitudeM)),
                   resume_index_);
      }
      break;
    case FlightMode::kHold:
      HoldHere(state.altitude_m);
      break;
    case FlightMode::kReturnToLaunch: {
      // At its mission's return altitude (its layer home); at the speed its
      // mission was flown at (the planner counts the way home at that speed),
      // else at the cruise speed.
      RoutePoint home;
      home.position = home_.value_or(estimator_.position());
      home.altitude_m = ReturnAltitudeM();
      home.speed_mps = ReturnSpeedMps();
      StartRoute({home}, 0);
      break;
    }
    case FlightMode::kLand:
      HoldHere(0.0);
      land_low_altitude_m_ = state.altitude_m;
      land_progress_at_ = now;
      break;
    case FlightMode::kIdle:
    case FlightMode::kLanded:
      cascade_.Reset();
      break;
    case FlightMode::kInvestigate:
      break;  // OnCommand starts the loiter
  }
}

radio::CommandResult Vehicle::OnCommand(const radio::Command& command) {
  using radio::CommandResult;
  using radio::CommandType;
  const Estimate& state = estimator_.estimate();
  const auto accept = [&](FlightMode mode) {
    EnterMode(mode, now_);
    ++stats_.commands_accepted;
    return CommandResult::kAccepted;
  };
  const auto reject = [&] {
    ++stats_.commands_rejected;
    return CommandResult::kRejected;
  };
  switch (command.type) {
    case CommandType::kStartMission: {
      // A mission flies only when every chunk of it is stored, and not on a
      // battery that already sent the vehicle home.
      if (!missions_.IsComplete(command.mission_id) || !navigator_ || low_battery_) {
        return reject();
      }
      active_mission_ = command.mission_id;
      resume_index_ = 0;
      rejoin_at_.reset();
      rejoining_ = false;
      return accept(Airborne() ? FlightMode::kSearch : FlightMode::kTakeoff);
    }
    case CommandType::kHold:
      if (!Airborne() || mode_ == FlightMode::kLand) return reject();
      // Resuming goes back to what was interrupted; a take-off resumes as the
      // search it was leading to (take-off again would re-zero home in the air).
      if (mode_ != FlightMode::kHold) {
        mode_before_hold_ = mode_ == FlightMode::kTakeoff ? FlightMode::kSearch : mode_;
      }
      return accept(FlightMode::kHold);
    case CommandType::kResume: {
      if (mode_ != FlightMode::kHold && mode_ != FlightMode::kInvestigate) return reject();
      if (low_battery_) return reject();
      const FlightMode back = mode_ == FlightMode::kHold ? mode_before_hold_ : FlightMode::kSearch;
      if (back == FlightMode::kSearch && missions_.complete() == nullptr) return reject();
      if (back == FlightMode::kInvestigate) return reject();  // its circle is gone: say where
      return accept(back);
    }
    case CommandType::kReturnToLaunch:
      if (!Airborne()) return reject();
      return accept(FlightMode::kReturnToLaunch);
    case CommandType::kLand:
      if (!Airborne()) return reject();
      return accept(FlightMode::kLand);
    case CommandType::kInvestigate: {
      if (!Airborne() || mode_ == FlightMode::kTakeoff || mode_ == FlightMode::kLand ||
          low_battery_) {
        return reject();
      }
      if (!common::IsValidLatLon({command.lat_deg, command.lon_deg})) return reject();
      const double radius =
          command.radius_m > 0.0 ? command.radius_m : Param(ParamId::kLoiterRadiusM);
      const double altitude = command.altitude_m > 0.0 ? command.altitude_m : state.altitude_m;
      const common::EastNorth center =
          estimator_.frame()->ToLocal({command.lat_deg, command.lon_deg});
      loiter_.Start(center, radius, altitude);
      // Far away: first the straight way to the nearest point of the circle.
      const double away_east = state.position_local.east_m - center.east_m;
      const double away_north = state.position_local.north_m - center.north_m;
      const double range = std::hypot(away_east, away_north);
      investigate_until_.reset();
      if (command.duration_s > 0)
        investigate_until_ = now_ + std::chrono::seconds(command.duration_s);
      // Entering the mode remembers where the search was: the approach route after.
      const CommandResult result = accept(FlightMode::kInvestigate);
      investigate_approach_ = range > radius + kLoiterCaptureM;
      if (investigate_approach_) {
        RoutePoint entry;
        entry.position =
            estimator_.frame()->ToGeodetic({center.east_m + away_east / range * radius,
                                            center.north_m + away_north / range * radius});
        entry.altitude_m = altitude;
        StartRoute({entry}, 0);
      }
      return result;
    }
    case CommandType::kAbort:
      // Stop the mission and come down where it is; on the ground, stay disarmed.
      if (!Airborne()) {
        ++stats_.commands_accepted;
        return CommandResult::kAccepted;
      }
      return accept(FlightMode::kLand);
    case CommandType::kAvoid:
      // Only in the air, and only for a while: an order without an end would
      // outlive the conflict it resolves. Altitude 0 ends the order early.
      if (!Airborne() || command.duration_s == 0) return reject();
      if (command.altitude_m <= 0.0) {
        avoid_altitude_m_.reset();
      } else {
        avoid_altitude_m_ = command.altitude_m;
        avoid_until_ = now_ + std::chrono::seconds(command.duration_s);
      }
      ++stats_.commands_accepted;
      ++stats_.avoid_orders;
      return CommandResult::kAccepted;
  }
  ++stats_.commands_rejected;
  return CommandResult::kUnsupported;
}

void Vehicle::CheckSafety(Nanos now) {
  const Estimate& state = estimator_.estimate();
  if (!Airborne() && low_battery_ && state.battery_fraction >= kFreshPackFraction) {
    low_battery_ = false;
  }
  if (!Airborne() || mode_ == FlightMode::kLand) return;
  // No GPS for long: come down where it is rather than drift until the pack is empty.
  if (state.has_position && state.gps_age_s > kGpsLostLandAfterS) {
    ++stats_.gps_lost_landings;
    EnterMode(FlightMode::kLand, now);
    return;
  }
  if (state.battery_fraction < Param(ParamId::kRtlBatteryFraction) && !low_battery_) {
    low_battery_ = true;
    if (mode_ != FlightMode::kReturnToLaunch) {
      ++stats_.low_battery_returns;
      EnterMode(FlightMode::kReturnToLaunch, now);
    }
  }
  const Nanos timeout = common::FromSeconds(Param(ParamId::kLinkLostTimeoutS));
  const Nanos heard = last_heard_.value_or(mode_since_);
  if (!link_lost_ && now - heard > timeout) {
    link_lost_ = true;
    // Home at its own layer, which the server predicts it on: an avoid order
    // of a server it no longer hears would never be released.
    avoid_altitude_m_.reset();
    if (mode_ != FlightMode::kReturnToLaunch) {
      ++stats_.link_lost_returns;
      EnterMode(FlightMode::kReturnToLaunch, now);
    }
  }
}

CascadeSetpoint Vehicle::Behave(Nanos now, std::optional<common::Micros> nav_dt) {
  const Estimate& state = estimator_.estimate();
  const bool no_fix = gps_lost();
  // Without GPS the navigator would steer by a guess: it waits for fixes.
  if (nav_dt && !no_fix) {
    const NavigationInput input = NavInput();
    const bool circling = mode_ == FlightMode::kInvestigate && !investigate_approach_;
    navigation_setpoint_ =
        circling ? loiter_.Step(input, *nav_dt) : navigator_->Step(input, *nav_dt);
  }
  CascadeSetpoint setpoint;
  setpoint.roll_rad = navigation_setpoint_.roll_rad;
  setpoint.pitch_rad = navigation_setpoint_.pitch_rad;
  setpoint.heading_rad = navigation_setpoint_.heading_rad;
  setpoint.altitude_m = navigation_setpoint_.altitude_m;

  switch (mode_) {
    case FlightMode::kTakeoff:
      if (state.altitude_m > ClimbOutAltitudeM() - kTakeoffDoneBelowM) {
        EnterMode(missions_.IsComplete(active_mission_) ? FlightMode::kSearch : FlightMode::kHold,
                  now);
      }
      break;
    case FlightMode::kSearch:
      if (rejoining_ && navigator_->finished()) {
        // On the route again where it left it: on along the same segment.
        rejoining_ = false;
        navigator_->SetRoute(RouteOf(*missions_.complete(), Param(ParamId::kTakeoffAltitudeM)),
                             resume_index_, *rejoin_at_);
        rejoin_at_.reset();
      } else if (navigator_->finished()) {
        EnterMode(FlightMode::kReturnToLaunch, now);
      }
      break;
    case FlightMode::kInvestigate:
      if (investigate_approach_) {
        const common::EastNorth center = loiter_.center();
        const double range = std::hypot(center.east_m - state.position_local.east_m,
                                        center.north_m - state.position_local.north_m);
        if (range <= loiter_.radius_m() + kLoiterCaptureM || navigator_->finished()) {
          investigate_approach_ = false;
        }
      }
      if (investigate_until_ && now >= *investigate_until_) {
        EnterMode(missions_.IsComplete(active_mission_) ? FlightMode::kSearch : FlightMode::kHold,
                  now);
      }
      break;
    case FlightMode::kReturnToLaunch: {
      // How far from home matters only once the navigator holds there (a
      // projection per physics step otherwise).
      if (!navigator_->finished()) break;
      const common::EastNorth home =
          estimator_.frame()->ToLocal(home_.value_or(estimator_.position()));
      const double distance = std::hypot(home.east_m - state.position_local.east_m,
                                         home.north_m - state.position_local.north_m);
      if (distance < kHomeReachedM) EnterMode(FlightMode::kLand, now);
      break;
    }
    case FlightMode::kLand: {
      setpoint.climb_rate_mps = state.altitude_m > kSlowDescentBelowM
                                    ? -Param(ParamId::kLandDescentMps)
                                    : -std::min(kSlowDescentMps, Param(ParamId::kLandDescentMps));
      if (state.altitude_m < land_low_altitude_m_ - kLandProgressM) {
        land_low_altitude_m_ = state.altitude_m;
        land_progress_at_ = now;
      } else if (common::ToSeconds(now - land_progress_at_) > kLandedAfterS) {
        EnterMode(FlightMode::kLanded, now);
      }
      break;
    }
    case FlightMode::kHold:
    case FlightMode::kIdle:
    case FlightMode::kLanded:
      break;
  }
  if (no_fix) {
    // Level, on its heading, at the altitude it flies to: it drifts with the wind
    // until fixes come back, then the navigator takes up its mode again.
    setpoint.roll_rad = 0.0;
    setpoint.pitch_rad = 0.0;
    setpoint.heading_rad = state.attitude.heading_rad;
  }
  ApplyAvoid(now, setpoint);
  return setpoint;
}

void Vehicle::ApplyAvoid(Nanos now, CascadeSetpoint& setpoint) {
  if (avoid_altitude_m_ && now >= avoid_until_) avoid_altitude_m_.reset();
  if (!avoid_altitude_m_ || !Airborne()) return;
  setpoint.altitude_m = *avoid_altitude_m_;
  if (mode_ == FlightMode::kLand) {
    // The landing waits level: no descent, and no "landed" while it waits.
    setpoint.climb_rate_mps.reset();
    land_low_altitude_m_ = estimator_.estimate().altitude_m;
    land_progress_at_ = now;
  }
}

ActuatorOutputs Vehicle::Step(Nanos now, const SensorInputs& inputs) {
  now_ = std::max(now_, now);
  estimator_.Update(now, inputs);
  if (!navigator_ && estimator_.frame())
    navigator_.emplace(navigation_config_, *estimator_.frame());
  if (resume_ && !ResumeFlight(now)) {
    // Rebooted in the air, its estimate not ready yet: level, holding its climb
    // rate at zero, no turn.
    outputs_ = ActuatorOutputs{};
    outputs_.armed = true;
    return outputs_;
  }
  if (inputs.frame != nullptr) ProcessFrame(now, *inputs.frame);
  CheckSafety(now);

  std::optional<common::Micros> nav_dt;
  const Nanos nav_period = common::FromSeconds(1.0 / config_.navigation_hz);
  if (!last_navigation_ || now - *last_navigation_ >= nav_period) {
    nav_dt = common::ToMicros(last_navigation_ ? now - *last_navigation_ : nav_period);
    last_navigation_ = now;
  }
  const Nanos telemetry_period = common::FromSeconds(1.0 / config_.telemetry_hz);
  if (!last_telemetry_ || now - *last_telemetry_ >= telemetry_period) {
    UpdateTelemetry(now);
    last_telemetry_ = now;
  }
  outputs_ = ActuatorOutputs{};
  if (!Airborne() || !navigator_) {
    SaveFlight();
    return outputs_;
  }

  const CascadeSetpoint setpoint = Behave(now, nav_dt);
  if (!Airborne()) {  // just landed
    SaveFlight();
    return outputs_;
  }
  const Estimate& state = estimator_.estimate();
  CascadeInput input;
  input.roll_rad = state.attitude.roll_rad;
  input.pitch_rad = state.attitude.pitch_rad;
  input.heading_rad = state.attitude.heading_rad;
  input.altitude_m = state.altitude_m;
  outputs_ = cascade_.Step(now, input, setpoint);
  outputs_.armed = true;
  SaveFlight();
  return outputs_;
}

}  // namespace fireswarm::agents
