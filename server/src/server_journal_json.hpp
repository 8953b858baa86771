// The journal's JSON for the two entries whose data is more than a few fields:
// shared by server.cpp (which records them) and server_journal.cpp (which also
// reads them back in Server::Restore), so the format lives in one place.
#pragma once

#include <nlohmann/json.hpp>
#include <vector>

#include "fireswarm/radio/messages.hpp"
#include "fireswarm/server/fire_fusion.hpp"

namespace fireswarm::server {

/// A mission's waypoints as a list of [lat_deg, lon_deg, altitude_m, speed_mps, flags].
nlohmann::json WaypointsJson(const std::vector<radio::Waypoint>& waypoints);

/// One fused fire observation, as recorded in a "report" entry.
nlohmann::json ObservationJson(const FireObservation& observation);

}  // namespace fireswarm::server
