// Splitting a mission into the MissionChunk requests of an upload: the one place
// both ends agree on how waypoints are numbered across chunks (the server sends
// them, the vehicle's mission store reassembles them, the radio bench times them).
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "fireswarm/radio/messages.hpp"

namespace fireswarm::radio {

/// Most waypoints one mission can have: chunk_count is one byte.
inline constexpr std::size_t kMaxMissionWaypoints = 255 * kMaxWaypointsPerChunk;

/// The chunks of mission `mission_id`, in order: chunk k carries waypoints
/// [k * kMaxWaypointsPerChunk, ...), at most kMaxWaypointsPerChunk each; headers are
/// left default (the scheduler sets them). Throws std::invalid_argument when
/// `waypoints` is empty or longer than kMaxMissionWaypoints.
std::vector<MissionChunk> SplitMission(std::uint16_t mission_id,
                                       std::span<const Waypoint> waypoints);

}  // namespace fireswarm::radio
