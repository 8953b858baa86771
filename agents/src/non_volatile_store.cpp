#include "fireswarm/agents/non_volatile_store.hpp"

namespace fireswarm::agents {
namespace {

bool SamePosition(const std::optional<common::LatLon>& a, const std::optional<common::LatLon>& b) {
  if (!a || !b) return a.has_value() == b.has_value();
  return a->lat_deg == b->lat_deg && a->lon_deg == b->lon_deg;
}

}  // namespace

bool operator==(const FlightRecord& a, const FlightRecord& b) {
  return a.mode == b.mode && a.mode_before_hold == b.mode_before_hold &&
         a.active_mission == b.active_mission && a.waypoint_index == b.waypoint_index &&
         SamePosition(a.rejoin_at, b.rejoin_at) && SamePosition(a.home, b.home) &&
         a.baro_zero_m == b.baro_zero_m && a.low_battery == b.low_battery;
}

void NonVolatileStore::WriteParam(std::uint16_t id, float value) {
  params_[id] = value;
  ++writes_;
}

void NonVolatileStore::WriteMissions(const MissionStore& missions) {
  missions_ = missions;
  ++writes_;
}

void NonVolatileStore::WriteFlight(const FlightRecord& flight) {
  flight_ = flight;
  ++writes_;
}

void NonVolatileStore::WriteEndpoint(const radio::VehicleEndpointState& endpoint) {
  endpoint_ = endpoint;
  ++writes_;
}

bool NonVolatileStore::WriteSecurity(const radio::SecurityState& security) {
  security_ = security;
  ++writes_;
  return true;
}

}  // namespace fireswarm::agents
