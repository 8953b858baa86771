// The server core at run time: configuration checks, the radio step and what
// follows from its events (telemetry, fire reports, investigations, mission
// state). Operator commands are in server_commands.cpp; the journal half
// (recording entries and Server::Restore) is in server_journal.cpp.
#include "fireswarm/server/server.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <span>
#include <stdexcept>
#include <utility>
#include <variant>

#include "fireswarm/common/angles.hpp"
#include "fireswarm/common/time.hpp"
#include "local_point.hpp"

namespace fireswarm::server {

namespace {

// A lost drone's way home as the tactical watch predicts it (ResolveConflicts)
// when its mission does not say its speed: the vehicles' cruise speed, m/s; it
// comes down over its stand at about this rate, m/s; and the watch keeps it this
// much longer, s (a landing that takes longer, wind).
constexpr double kLostDroneSpeedMps = 10.0;
constexpr double kLostDroneDescentMps = 1.0;
constexpr double kLostDroneSlackS = 60.0;
// A vehicle that has not heard the server for this long returns to launch by
// itself (agents' safety.link_lost_timeout_s, its default), s.
constexpr double kVehicleLinkLostS = 30.0;
// A drone taking off below this is over its stand, m.
constexpr double kJustOffTheStandM = 5.0;
// How many waypoints ahead a drone on its route is predicted along (take-off
// clearances look about a minute ahead: at 10 m/s, lanes are longer than 50 m).
constexpr std::size_t kRouteAheadWaypoints = 12;

// The waypoints of the sortie `vehicle` flies now (its last when it is done);
// empty without a mission for it. The vehicle holds just this sortie.
std::span<const radio::Waypoint> SortieFlown(const MissionManager* mission, std::uint8_t vehicle) {
  if (mission == nullptr) return {};
  const std::vector<std::uint8_t> vehicles = mission->vehicles();  // ascending
  if (!std::ranges::binary_search(vehicles, vehicle)) return {};
  const DroneMission& flown = mission->mission_of(vehicle);
  const std::size_t sorties = SortieCount(flown);
  if (sorties == 0) return {};
  const auto [first, end] =
      SortieRange(flown, std::min(mission->progress(vehicle).sortie, sorties - 1));
  return std::span<const radio::Waypoint>(flown.waypoints).subspan(first, end - first);
}

// Room the transit planner keeps around the no-fly zones for its sampling, m (it
// grows its box to each query's endpoints as well).
constexpr double kTransitMarginM = 1'000.0;

const ServerConfig& Validated(const ServerConfig& config) {
  config.Validate();
  return config;
}

// The planner of routes around the no-fly zones; null when there are none.
std::unique_ptr<const planner::TransitPlanner> TransitFor(const ServerConfig& config) {
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

InvestigationsConfig InvestigationsConfigOf(const ServerConfig& config) {
  return {.investigate_s = config.investigate_s,
          .investigate_transit_mps = config.investigate_transit_mps,
          .investigate_near_m = config.investigate_near_m,
          .investigate_radius_m = config.investigate_radius_m,
          .reject_grace_s = config.reject_grace_s,
          .no_fly = config.no_fly};
}

}  // namespace

void ServerConfig::Validate() const {
  radio.Validate();
  fusion.Validate();
  separation.Validate();
  if (!(telemetry_hz > 0.0) || !std::isfinite(telemetry_hz)) {
    throw std::invalid_argument("telemetry_hz must be a positive number");
  }
  if (!(investigate_s >= 1.0 && investigate_s <= kMaxInvestigateS)) {
    throw std::invalid_argument("investigate_s must be in [1, 65535] s");
  }
  if (!(investigate_transit_mps > 0.0) || !std::isfinite(investigate_transit_mps)) {
    throw std::invalid_argument("investigate_transit_mps must be a positive number");
  }
  if (!(investigate_near_m > 0.0) || !std::isfinite(investigate_near_m)) {
    throw std::invalid_argument("investigate_near_m must be a positive number");
  }
  if (!(investigate_radius_m >= 0.0) || !std::isfinite(investigate_radius_m)) {
    throw std::invalid_argument("investigate_radius_m must be >= 0");
  }
  if (!(reject_grace_s >= 0.0) || !std::isfinite(reject_grace_s)) {
    throw std::invalid_argument("reject_grace_s must be >= 0");
  }
  if (!area.empty() && !camera) {
    throw std::invalid_argument("camera must be given with an area (the coverage is the camera's)");
  }
  if (camera) {
    common::ValidateCamera(*camera, camera_pitch_deg, "server config");
    // The footprint needs the image's near edge on the ground (FootprintWidthM).
    if (!(camera_pitch_deg < 0.0)) {
      throw std::invalid_argument(
          "server config: camera_pitch_deg must be < 0 (below the horizon)");
    }
  }
}

const char* ToString(MissionState state) {
  switch (state) {
    case MissionState::kIdle:
      return "idle";
    case MissionState::kUploading:
      return "uploading";
    case MissionState::kRunning:
      return "running";
    case MissionState::kReturning:
      return "returning";
    case MissionState::kComplete:
      return "complete";
    case MissionState::kAborted:
      return "aborted";
  }
  return "unknown";
}

Server::Server(const ServerConfig& config, const common::LocalFrame& frame)
    : config_(Validated(config)),
      frame_(frame),
      transit_(TransitFor(config_)),
      scheduler_(std::make_unique<radio::ChannelRouter>(config_.ChannelConfigs())),
      registry_(config.link),
      fusion_(config.fusion),
      investigations_(InvestigationsConfigOf(config_), frame_, transit_.get()),
      traffic_(config_.separation),
      verifier_(config_.operators, config_.command_window_us) {
  if (!config_.area.empty()) coverage_.emplace(config_.area, config_.no_fly);
}

void Server::AddVehicle(int receiver_id, double now_s) {
  registry_.Register(receiver_id);
  // Stagger the first telemetry turns so a fleet does not ask all at once.
  const auto index = static_cast<double>(registry_.size() - 1);
  const auto fixed = config_.vehicle_channels.find(receiver_id);
  scheduler_->AddVehicle(static_cast<std::uint8_t>(receiver_id), config_.telemetry_hz,
                         common::FromSeconds(index * 0.05),
                         fixed == config_.vehicle_channels.end()
                             ? std::nullopt
                             : std::optional<std::size_t>(fixed->second));
  Record(now_s, VehicleAdded{receiver_id});
}

void Server::LoadMission(std::vector<DroneMission> missions, double now_s,
                         std::optional<AirspacePlan> airspace) {
  // A journal replay trusts the order it was recorded in (the registry has no
  // telemetry then to tell whether the drones are down).
  if (mission_ && !restoring_ && !MissionOver()) {
    throw std::invalid_argument(std::string("a mission is already loaded and not over (") +
                                ToString(state_) + ")");
  }
  const std::uint16_t first_id = NextMissionId();
  for (const DroneMission& m : missions) {
    if (!registry_.Contains(m.vehicle)) {
      throw std::invalid_argument("mission for vehicle " + std::to_string(m.vehicle) +
                                  ", which is not registered");
    }
    // A vehicle takes an ID it flew before for a resend of that mission.
    if (m.mission_id < first_id) {
      throw std::invalid_argument("mission for vehicle " + std::to_string(m.vehicle) + " has ID " +
                                  std::to_string(m.mission_id) + ", below the next free one (" +
                                  std::to_string(first_id) + ")");
    }
  }
  MissionLoaded loaded{missions, airspace};
  mission_.emplace(*scheduler_, std::move(missions), config_.mission);
  airspace_ = std::move(airspace);
  // What belonged to the mission before, if any.
  state_ = MissionState::kIdle;
  start_command_id_ = 0;
  handed_over_.clear();
  journaled_phases_.fill(std::nullopt);
  if (coverage_) coverage_.emplace(config_.area, config_.no_fly);
  Record(now_s, std::move(loaded));
}

bool Server::MissionOver() const {
  if (!mission_ || state_ == MissionState::kComplete) return true;
  if (state_ != MissionState::kAborted) return false;
  // Aborted: over once every drone of it is down or given up.
  const std::vector<std::uint8_t> lost = registry_.LostAt(last_step_s_);
  return std::ranges::all_of(mission_->vehicles(), [&](std::uint8_t id) {
    if (std::ranges::find(lost, id) != lost.end()) return true;
    const std::optional<radio::Telemetry>& telemetry = registry_.state(id).telemetry;
    return !telemetry || telemetry->mode == radio::FlightMode::kIdle ||
           telemetry->mode == radio::FlightMode::kLanded;
  });
}

bool Server::FleetReady(double now_s) const {
  return std::ranges::all_of(registry_.ids(), [&](std::uint8_t id) {
    if (registry_.LinkAt(id, now_s) == LinkState::kLost) return true;
    const std::optional<radio::Telemetry>& telemetry = registry_.state(id).telemetry;
    const bool on_ground = telemetry && (telemetry->mode == radio::FlightMode::kLanded ||
                                         telemetry->mode == radio::FlightMode::kIdle);
    return on_ground && telemetry->battery_percent >= kFreshPackPercent &&
           (telemetry->flags & radio::telemetry_flags::kLowBattery) == 0;
  });
}

std::uint16_t Server::NextMissionId() const {
  if (!mission_) return 1;
  const std::uint16_t last = mission_->LastMissionId();
  if (last == std::numeric_limits<std::uint16_t>::max()) {
    throw std::invalid_argument("the mission IDs are used up (65535): restart the server with a "
                                "new journal");
  }
  return static_cast<std::uint16_t>(last + 1);
}

std::vector<radio::Burst> Server::Step(common::Nanos now, std::size_t channel,
                                       std::span<const std::uint8_t> received) {
  const double now_s = common::ToSeconds(now);
  last_step_s_ = now_s;
  if (mission_) mission_->Step(now, TakeOffGate());
  std::vector<radio::Burst> bursts = scheduler_->Step(now, channel, received);
  bytes_received_ += received.size();
  for (const radio::Burst& burst : bursts) bytes_sent_ += burst.bytes.size();
  for (const radio::SchedulerEvent& event : scheduler_->TakeEvents()) OnEvent(event, now_s);
  CheckInvestigations(now);
  HandOverLostDrones(now_s);
  RecallHandedOverDrones(now_s);
  RebalanceSorties(now_s);
  ResolveConflicts(now_s);
  UpdateState(now_s);
  return bursts;
}

void Server::OnEvent(const radio::SchedulerEvent& event, double now_s) {
  if (const auto* telemetry = std::get_if<radio::TelemetryReceived>(&event)) {
    registry_.OnTelemetry(telemetry->telemetry, now_s);
    const Eigen::Vector2d where =
        LocalM(frame_, {telemetry->telemetry.lat_deg, telemetry->telemetry.lon_deg});
    investigations_.OnPosition(telemetry->vehicle, where, now_s);
    MarkCoverage(telemetry->telemetry, where);
    const radio::FlightMode mode = telemetry->telemetry.mode;
    const bool fix = (telemetry->telemetry.flags & radio::telemetry_flags::kGpsFix) != 0;
    if ((mode == radio::FlightMode::kIdle || mode == radio::FlightMode::kLanded) && fix) {
      stand_en_m_[telemetry->vehicle] = where;
    } else if (mode == radio::FlightMode::kTakeoff && fix &&
               telemetry->telemetry.altitude_m < kJustOffTheStandM) {
      // First heard just off the ground: a take-off climbs straight up from its
      // stand (on a crowded channel a drone may be started before it is heard
      // on the ground, and its way home ends there).
      stand_en_m_.try_emplace(telemetry->vehicle, where);
    }
    clock_offset_s_[telemetry->vehicle] =
        now_s - static_cast<double>(telemetry->telemetry.time_ms) / common::kMillisPerSecond;
    WatchTraffic(telemetry->vehicle, telemetry->telemetry, where, now_s);
  } else if (const auto* report = std::get_if<radio::FireReportReceived>(&event)) {
    registry_.OnReply(report->vehicle, now_s);
    OnFireReport(*report, now_s);
  } else if (const auto* finished = std::get_if<radio::RequestFinished>(&event)) {
    if (finished->status == radio::RequestStatus::kCompleted) {
      registry_.OnReply(finished->vehicle, now_s);
    }
    // The watch predicts each drone holding the avoid order it last took.
    if (const auto avoid = avoid_requests_.find(finished->id); avoid != avoid_requests_.end()) {
      const auto* ack = finished->ack ? std::get_if<radio::CommandAck>(&*finished->ack) : nullptr;
      traffic_.Taken(avoid->second, ack != nullptr && ack->result == radio::CommandResult::kAccepted,
                     now_s);
      avoid_requests_.erase(avoid);
    }
  } else if (const auto* silent = std::get_if<radio::VehicleSilent>(&event)) {
    registry_.OnMissedReply(silent->vehicle);
  }
  commands_.OnEvent(event);
  if (!mission_) return;
  mission_->OnEvent(event, TakeOffGate());
  UpdateStartCommand(event);
  for (const std::uint8_t id : mission_->vehicles()) {
    // A new phase, or sorties cut in two (a low-battery return) in the same one.
    // Compared in place: this runs for every drone on every radio event.
    const DroneProgress& progress = mission_->progress(id);
    const std::vector<std::size_t>& sortie_starts = mission_->mission_of(id).sortie_starts;
    std::optional<JournaledPhase>& journaled = journaled_phases_[id];
    if (journaled && journaled->phase == progress.phase &&
        journaled->sortie_starts == sortie_starts) {
      continue;
    }
    Record(now_s, PhaseChanged{id, progress.phase, progress.sortie, sortie_starts});
    journaled = JournaledPhase{progress.phase, sortie_starts};
  }
}

void Server::WatchTraffic(std::uint8_t vehicle, const radio::Telemetry& telemetry,
                          const Eigen::Vector2d& where_en_m, double now_s) {
  const bool on_ground =
      telemetry.mode == radio::FlightMode::kIdle || telemetry.mode == radio::FlightMode::kLanded;
  if (on_ground || (telemetry.flags & radio::telemetry_flags::kGpsFix) == 0) {
    traffic_.Forget(vehicle);
    return;
  }
  TrafficSample sample;
  sample.position_m = {where_en_m.x(), where_en_m.y(), telemetry.altitude_m};
  sample.velocity_mps = {telemetry.velocity_east_mps, telemetry.velocity_north_mps,
                         telemetry.climb_rate_mps};
  sample.at_s = now_s;
  sample.intent_altitude_m = IntentAltitudeM(vehicle, telemetry.mode);
  // A landing comes straight down where it began (agents' land mode holds that
  // point): what its telemetry reports as drift is the hold working against
  // the wind, and carried on for the horizon it made neighbours landing on
  // their stands 20 m away look 13 m close.
  sample.holds_position = telemetry.mode == radio::FlightMode::kLand;
  // On its route (its sortie's, as the vehicle reports it): the waypoints ahead.
  const std::span<const radio::Waypoint> sortie =
      telemetry.mode == radio::FlightMode::kSearch ? SortieFlown(mission(), vehicle)
                                                   : std::span<const radio::Waypoint>{};
  const auto stand = stand_en_m_.find(vehicle);
  if (!sortie.empty()) {  // so the mission has the vehicle
    const DroneProgress& progress = mission_->progress(vehicle);
    if (progress.phase == DronePhase::kFlying &&
        telemetry.mission_id == SortieMissionId(mission_->mission_of(vehicle), progress.sortie) &&
        telemetry.waypoint_index < sortie.size()) {
      sample.route_m = RouteAhead(sortie, telemetry.waypoint_index);
      const double speed_mps = sortie[telemetry.waypoint_index].speed_mps;
      sample.route_speed_mps = speed_mps > 0.0 ? speed_mps : kLostDroneSpeedMps;
      // Its sortie's end in sight: then home to its stand at its last
      // waypoint's layer, where it stops (agents: a finished route returns to
      // launch). Without it, a drone whose lane ends near the site was
      // predicted hovering at the lane's end while it flew home across the
      // traffic leaving the site.
      const std::optional<double> home_m =
          IntentAltitudeM(vehicle, radio::FlightMode::kReturnToLaunch);
      if (telemetry.waypoint_index + sample.route_m.size() == sortie.size() &&
          stand != stand_en_m_.end() && home_m) {
        sample.route_m.emplace_back(stand->second.x(), stand->second.y(), *home_m);
        sample.route_stops = true;
      }
    }
  }
  // Taking off: straight up where it is to its climb-out altitude, then on its
  // way along its sortie (agents' take-off mode holds its point while it
  // climbs). The drift its telemetry reports is the hold chasing GPS noise, a
  // few tenths of a m/s either way: carried on for the horizon, it made
  // neighbouring take-offs conflicts and held them level in the air.
  const std::span<const radio::Waypoint> climbing_to = telemetry.mode == radio::FlightMode::kTakeoff
                                                           ? SortieFlown(mission(), vehicle)
                                                           : std::span<const radio::Waypoint>{};
  if (!climbing_to.empty() && climbing_to.front().altitude_m > 0.0 &&
      telemetry.mission_id ==
          SortieMissionId(mission_->mission_of(vehicle), mission_->progress(vehicle).sortie)) {
    sample.route_m = RouteAhead(climbing_to, 0);
    sample.route_speed_mps =
        climbing_to.front().speed_mps > 0.0 ? climbing_to.front().speed_mps : kLostDroneSpeedMps;
    sample.departing = true;
    sample.holds_position = true;
  }
  // On its way home: straight to its stand at its return layer, where it stops
  // and comes down (agents' return to launch). Straight on, it would be
  // predicted flying on past its stand, and a drone crossing over the stand
  // while it comes down there would be seen only as it stops.
  if (telemetry.mode == radio::FlightMode::kReturnToLaunch && stand != stand_en_m_.end()) {
    const double altitude_m = sample.intent_altitude_m.value_or(telemetry.altitude_m);
    sample.route_m = {{stand->second.x(), stand->second.y(), altitude_m}};
    const std::span<const radio::Waypoint> flown = SortieFlown(mission(), vehicle);
    sample.route_speed_mps = !flown.empty() && flown.back().speed_mps > 0.0 ? flown.back().speed_mps
                                                                            : kLostDroneSpeedMps;
    sample.route_stops = true;
  }
  traffic_.Observe(vehicle, sample);
}

std::optional<double> Server::IntentAltitudeM(std::uint8_t vehicle, radio::FlightMode mode) const {
  if (mode == radio::FlightMode::kLand) return 0.0;
  if (mode != radio::FlightMode::kTakeoff && mode != radio::FlightMode::kReturnToLaunch) {
    return std::nullopt;
  }
  // The vehicle's sortie: it climbs out to its first waypoint's altitude and
  // flies home at its last's (agents' ClimbOutAltitudeM, ReturnAltitudeM).
  const std::span<const radio::Waypoint> sortie = SortieFlown(mission(), vehicle);
  if (sortie.empty()) return std::nullopt;
  const double altitude_m =
      mode == radio::FlightMode::kTakeoff ? sortie.front().altitude_m : sortie.back().altitude_m;
  if (altitude_m <= 0.0) return std::nullopt;
  return altitude_m;
}

std::vector<Eigen::Vector3d> Server::RouteAhead(std::span<const radio::Waypoint> sortie,
                                                std::size_t from) const {
  std::vector<Eigen::Vector3d> route;
  for (std::size_t k = from; k < sortie.size() && route.size() < kRouteAheadWaypoints; ++k) {
    const Eigen::Vector2d at = LocalM(frame_, {sortie[k].lat_deg, sortie[k].lon_deg});
    route.emplace_back(at.x(), at.y(), sortie[k].altitude_m);
  }
  return route;
}

StartGate Server::TakeOffGate() {
  return [this](std::uint8_t vehicle, common::Nanos now) {
    return ClearToTakeOff(vehicle, common::ToSeconds(now));
  };
}

bool Server::ClearToTakeOff(std::uint8_t vehicle, double now_s) {
  if (!config_.separation.sequence_takeoffs) return true;
  const auto stand = stand_en_m_.find(vehicle);
  const std::span<const radio::Waypoint> sortie = SortieFlown(mission(), vehicle);
  if (sortie.empty() || sortie.front().altitude_m <= 0.0) {
    return true;  // nothing to predict its take-off from
  }
  if (stand == stand_en_m_.end()) {
    // Not yet heard (on a crowded channel the first telemetry takes seconds):
    // it waits. Started blind, its climb and way out would be unpredicted in
    // every later clearance, and neighbours whose lanes start together would
    // leave together. Heard in the air, it takes off from no stand: it goes.
    const std::optional<radio::Telemetry>& heard = registry_.state(vehicle).telemetry;
    return heard && heard->mode != radio::FlightMode::kIdle &&
           heard->mode != radio::FlightMode::kLanded;
  }
  Departure departure;
  departure.stand_m = stand->second;
  departure.route_m = RouteAhead(sortie, 0);
  departure.speed_mps =
      sortie.front().speed_mps > 0.0 ? sortie.front().speed_mps : kLostDroneSpeedMps;
  return traffic_.ClearToDepart(vehicle, departure, now_s);
}

void Server::ResolveConflicts(double now_s) {
  if (!traffic_.Due(now_s)) return;  // Step runs for every radio event: not this
  // A drone given up as lost flies home by itself at its sortie's last altitude
  // (its return layer), at its mission's speed, and comes down over its stand.
  for (const std::uint8_t vehicle : registry_.LostAt(now_s)) {
    if (!traffic_.Flying(vehicle)) continue;
    const VehicleState& state = registry_.state(vehicle);
    const auto stand = stand_en_m_.find(vehicle);
    if (!state.telemetry || stand == stand_en_m_.end()) {
      traffic_.Forget(vehicle);  // nowhere to predict it to
      continue;
    }
    const radio::Telemetry& last = *state.telemetry;
    // As the watch last saw it (with the route ahead when it flew one).
    TrafficSample sample = *traffic_.Last(vehicle);
    const Eigen::Vector2d where = sample.position_m.head<2>();
    double altitude_m = last.altitude_m;
    double speed_mps = kLostDroneSpeedMps;
    // The vehicle flies home at its sortie's way home altitude (agents'
    // Vehicle::ReturnAltitudeM).
    const std::span<const radio::Waypoint> sortie = SortieFlown(mission(), vehicle);
    if (!sortie.empty() && sortie.back().altitude_m > 0.0) {
      altitude_m = sortie.back().altitude_m;
      if (sortie.back().speed_mps > 0.0) speed_mps = sortie.back().speed_mps;
    }
    // It flies its mission on until its own lost-link return.
    const double turns_home_s = sample.at_s + kVehicleLinkLostS;
    const double home_s = (stand->second - where).norm() / speed_mps;
    traffic_.ExpectLost(
        vehicle, sample, stand->second, altitude_m, speed_mps, turns_home_s,
        turns_home_s + home_s + altitude_m / kLostDroneDescentMps + kLostDroneSlackS);
  }
  for (const AvoidOrder& order : traffic_.Step(now_s)) {
    radio::Command avoid;
    avoid.type = radio::CommandType::kAvoid;
    avoid.altitude_m = order.altitude_m;
    avoid.duration_s = static_cast<std::uint16_t>(std::ceil(order.duration_s));
    const radio::RequestId request =
        scheduler_->SendCommand(static_cast<std::uint8_t>(order.vehicle), avoid, /*urgent=*/true);
    avoid_requests_.emplace(request, order);
  }
}

void Server::MarkCoverage(const radio::Telemetry& telemetry, const Eigen::Vector2d& where_en_m) {
  // Without a fix the vehicle sends (0, 0); below kMinCoverageAltitudeM the grid
  // marks nothing (taking off, landing, on the ground).
  if (!coverage_ || (telemetry.flags & radio::telemetry_flags::kGpsFix) == 0) return;
  coverage_->Mark(where_en_m, telemetry.heading_deg * common::kRadPerDeg, telemetry.altitude_m,
                  *config_.camera, config_.camera_pitch_deg);
}

void Server::OnFireReport(const radio::FireReportReceived& received, double now_s) {
  // The report's time is the vehicle's clock; telemetry gave its offset to ours.
  const auto offset = clock_offset_s_.find(received.vehicle);
  const double detection_s = offset == clock_offset_s_.end()
                                 ? now_s
                                 : std::min(now_s, static_cast<double>(received.report.time_ms) /
                                                           common::kMillisPerSecond +
                                                       offset->second);
  const FireObservation observation = ObservationFromReport(received.report, frame_, detection_s);
  const FireReportResult result = fusion_.Add(observation);
  if (result.outcome == FireReportOutcome::kDuplicate ||
      result.outcome == FireReportOutcome::kInvalid) {
    return;
  }
  report_stats_.Add(now_s, detection_s);
  Record(now_s, ReportFused{observation});
  AfterFusion(observation, result, now_s);
}

void Server::AfterFusion(const FireObservation& observation, const FireReportResult& result,
                         double now_s) {
  if (result.outcome == FireReportOutcome::kConfirmed) {
    // The investigator's job is done: back to its lanes at once.
    for (const std::uint8_t vehicle : investigations_.EndForConfirmed(result.track_id, now_s)) {
      radio::Command resume;
      resume.type = radio::CommandType::kResume;
      scheduler_->SendCommand(vehicle, resume);
    }
    return;
  }
  if (result.outcome != FireReportOutcome::kNewTrack || !config_.auto_investigate) return;
  if (state_ != MissionState::kRunning && state_ != MissionState::kUploading) return;
  const FireTrack* track = fusion_.Find(result.track_id);
  if (track == nullptr) return;
  const double radius_m = investigations_.RadiusM(0.0);
  std::string why_none;
  std::optional<std::uint8_t> vehicle;
  if (std::optional<std::string> no =
          investigations_.CircleRefusal(track->position_en_m, radius_m)) {
    why_none = std::move(*no);
  } else {
    vehicle = investigations_.BestPlacedFor(registry_, track->position_en_m, radius_m,
                                            observation.vehicle_id, now_s, &why_none);
  }
  if (!vehicle) {
    Record(now_s, InvestigationNotSent{result.track_id, why_none});
    return;
  }
  const common::LatLon point = Geodetic(frame_, track->position_en_m);
  Investigate(*vehicle, point, 0.0, result.track_id, now_s);
}

void Server::CheckInvestigations(common::Nanos now) {
  const double now_s = common::ToSeconds(now);
  for (const Rejection& rejection : investigations_.Judge(now, fusion_)) {
    Record(now_s, TrackRejected{rejection.track_id, rejection.by_vehicle});
  }
}

void Server::UpdateState(double now_s) {
  if (!mission_ || state_ == MissionState::kIdle || state_ == MissionState::kAborted) return;
  const std::vector<std::uint8_t> ids = mission_->vehicles();
  const auto phase = [&](std::uint8_t id) { return mission_->progress(id).phase; };
  const bool all_over = std::ranges::all_of(ids, [&](std::uint8_t id) {
    return phase(id) == DronePhase::kDone || phase(id) == DronePhase::kFailed;
  });
  // The search is over when no drone searches any more: each is down (done,
  // failed) or, by its latest telemetry, on its way home or landing from its last
  // sortie (a drone uploading or starting a handed-over mission, or between
  // sorties, still searches).
  const auto heading_home = [&](std::uint8_t id) {
    const DroneProgress& progress = mission_->progress(id);
    if (progress.phase != DronePhase::kFlying || progress.sortie + 1 < progress.sortie_count) {
      return false;
    }
    const std::optional<radio::Telemetry>& telemetry = registry_.state(id).telemetry;
    if (!telemetry || mission_->CutShort(id, *telemetry)) return false;
    const radio::FlightMode mode = telemetry->mode;
    return mode == radio::FlightMode::kReturnToLaunch || mode == radio::FlightMode::kLand ||
           mode == radio::FlightMode::kLanded;
  };
  const bool search_over = std::ranges::all_of(ids, [&](std::uint8_t id) {
    return phase(id) == DronePhase::kDone || phase(id) == DronePhase::kFailed || heading_home(id);
  });
  MissionState next = state_;
  if (all_over) {
    next = MissionState::kComplete;
  } else if (state_ == MissionState::kUploading && mission_->AllStarted()) {
    next = MissionState::kRunning;
  } else if (state_ == MissionState::kRunning && search_over) {
    next = MissionState::kReturning;
  }
  if (next != state_) {
    state_ = next;
    Record(now_s, MissionStateChanged{state_});
  }
}

}  // namespace fireswarm::server
