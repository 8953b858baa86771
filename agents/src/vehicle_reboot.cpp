// The vehicle's non-volatile side (fault kind vehicle_reboot, docs/scenario.md):
// what it writes to its NonVolatileStore as it flies, and how a new Vehicle
// made with that store reloads it and resumes the flight.
#include "fireswarm/agents/vehicle.hpp"

namespace fireswarm::agents {

void Vehicle::Reload(const NonVolatileStore& storage) {
  for (const auto& [id, value] : storage.params()) params_.Write(id, value);
  if (storage.missions()) missions_ = *storage.missions();
  if (storage.endpoint()) endpoint_.Restore(*storage.endpoint());
  endpoint_saved_at_ = endpoint_.state_changes();
  const FlightRecord& flight = storage.flight();
  active_mission_ = flight.active_mission;
  home_ = flight.home;
  low_battery_ = flight.low_battery;
  mode_before_hold_ = flight.mode_before_hold;
  resume_index_ = flight.waypoint_index;
  rejoin_at_ = flight.rejoin_at;
  // Before the first reading: altitudes are above the ground it took off from.
  if (flight.baro_zero_m) estimator_.RestoreAltitudeZero(*flight.baro_zero_m);
  if (flight.mode == radio::FlightMode::kIdle || flight.mode == radio::FlightMode::kLanded) {
    mode_ = flight.mode;  // on the ground: nothing to resume
  } else {
    resume_ = flight;
  }
}

FlightRecord Vehicle::flight_record() const {
  FlightRecord flight;
  flight.mode = mode_;
  flight.mode_before_hold = mode_before_hold_;
  flight.active_mission = active_mission_;
  const bool on_route = mode_ == radio::FlightMode::kSearch && !rejoining_ && navigator_;
  flight.waypoint_index = on_route ? navigator_->waypoint_index() : resume_index_;
  flight.rejoin_at = rejoin_at_;
  flight.home = home_;
  flight.baro_zero_m = estimator_.altitude_zero_m();
  flight.low_battery = low_battery_;
  return flight;
}

void Vehicle::SaveFlight() {
  // Until the stored flight is resumed, the store keeps it.
  if (!config_.storage || resume_) return;
  FlightRecord flight = flight_record();
  if (flight != config_.storage->flight()) config_.storage->WriteFlight(flight);
}

void Vehicle::SaveEndpoint() {
  if (!config_.storage || endpoint_.state_changes() == endpoint_saved_at_) return;
  config_.storage->WriteEndpoint(endpoint_.state());
  endpoint_saved_at_ = endpoint_.state_changes();
}

bool Vehicle::ResumeFlight(Nanos now) {
  const Estimate& state = estimator_.estimate();
  if (!navigator_ || !state.has_attitude || !state.has_altitude) return false;
  const FlightRecord flight = *resume_;
  resume_.reset();
  // Reload() restored the mission, home, altitude zero and the waypoint to resume
  // at; the mode is entered here, now that there is a position to start from.
  switch (flight.mode) {
    case radio::FlightMode::kTakeoff: {
      // On with the climb over home (entering the mode again would take home
      // and the altitude zero here, in the air).
      mode_ = radio::FlightMode::kTakeoff;
      mode_since_ = now;
      RoutePoint over_home;
      over_home.position = home_.value_or(estimator_.position());
      over_home.altitude_m = ClimbOutAltitudeM();
      StartRoute({over_home}, 0);
      break;
    }
    case radio::FlightMode::kSearch:
    case radio::FlightMode::kInvestigate:
      // The search resumes where it was (an investigation's circle was the
      // server's order of the moment: the server sees the search and may send
      // it again); back to the point it left the route first, if it had.
      EnterMode(missions_.IsComplete(active_mission_) ? radio::FlightMode::kSearch
                                                      : radio::FlightMode::kHold,
                now);
      break;
    case radio::FlightMode::kHold:
    case radio::FlightMode::kReturnToLaunch:
    case radio::FlightMode::kLand:
      EnterMode(flight.mode, now);
      break;
    case radio::FlightMode::kIdle:
    case radio::FlightMode::kLanded:
      mode_ = flight.mode;
      break;
  }
  return true;
}

}  // namespace fireswarm::agents
