#include "fireswarm/radio/mission_chunks.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace fireswarm::radio {

std::vector<MissionChunk> SplitMission(std::uint16_t mission_id,
                                       std::span<const Waypoint> waypoints) {
  const std::size_t total = waypoints.size();
  if (total == 0 || total > kMaxMissionWaypoints) {
    throw std::invalid_argument("mission " + std::to_string(mission_id) +
                                ": waypoints must be 1.." + std::to_string(kMaxMissionWaypoints) +
                                ", got " + std::to_string(total));
  }
  const std::size_t count = (total + kMaxWaypointsPerChunk - 1) / kMaxWaypointsPerChunk;
  std::vector<MissionChunk> chunks(count);
  for (std::size_t c = 0; c < count; ++c) {
    MissionChunk& chunk = chunks[c];
    const std::size_t first = c * kMaxWaypointsPerChunk;
    const std::size_t in_chunk = std::min(kMaxWaypointsPerChunk, total - first);
    chunk.mission_id = mission_id;
    chunk.chunk_index = static_cast<std::uint8_t>(c);
    chunk.chunk_count = static_cast<std::uint8_t>(count);
    chunk.total_waypoints = static_cast<std::uint16_t>(total);
    chunk.first_waypoint = static_cast<std::uint16_t>(first);
    chunk.waypoint_count = static_cast<std::uint8_t>(in_chunk);
    std::copy_n(waypoints.begin() + static_cast<std::ptrdiff_t>(first), in_chunk,
                chunk.waypoints.begin());
  }
  return chunks;
}

}  // namespace fireswarm::radio
