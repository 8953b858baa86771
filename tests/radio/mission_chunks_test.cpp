#include "fireswarm/radio/mission_chunks.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

namespace fireswarm::radio {
namespace {

std::vector<Waypoint> Numbered(std::size_t count) {
  std::vector<Waypoint> waypoints(count);
  for (std::size_t i = 0; i < count; ++i) {
    waypoints[i].lat_deg = 45.0 + 1e-4 * static_cast<double>(i);
    waypoints[i].lon_deg = 7.0;
  }
  return waypoints;
}

TEST(SplitMission, ChunksCoverEveryWaypointInOrder) {
  const std::vector<Waypoint> waypoints = Numbered(45);
  const std::vector<MissionChunk> chunks = SplitMission(9, waypoints);
  ASSERT_EQ(chunks.size(), 3U);
  std::vector<Waypoint> joined;
  for (std::size_t c = 0; c < chunks.size(); ++c) {
    EXPECT_EQ(chunks[c].mission_id, 9);
    EXPECT_EQ(chunks[c].chunk_index, c);
    EXPECT_EQ(chunks[c].chunk_count, 3);
    EXPECT_EQ(chunks[c].total_waypoints, 45);
    EXPECT_EQ(chunks[c].first_waypoint, joined.size());
    EXPECT_LE(chunks[c].waypoint_count, kMaxWaypointsPerChunk);
    joined.insert(joined.end(), chunks[c].active().begin(), chunks[c].active().end());
  }
  EXPECT_EQ(chunks.back().waypoint_count, 5);
  EXPECT_EQ(joined, waypoints);
}

TEST(SplitMission, ExactMultipleHasNoEmptyChunk) {
  EXPECT_EQ(SplitMission(1, Numbered(2 * kMaxWaypointsPerChunk)).size(), 2U);
  EXPECT_EQ(SplitMission(1, Numbered(1)).size(), 1U);
}

TEST(SplitMission, LargestMissionFitsAndBeyondThrows) {
  const std::vector<MissionChunk> chunks = SplitMission(1, Numbered(kMaxMissionWaypoints));
  EXPECT_EQ(chunks.size(), 255U);
  EXPECT_EQ(chunks.back().chunk_index, 254);
  EXPECT_THROW(SplitMission(1, Numbered(kMaxMissionWaypoints + 1)), std::invalid_argument);
}

TEST(SplitMission, EmptyMissionThrows) {
  EXPECT_THROW(SplitMission(1, {}), std::invalid_argument);
}

}  // namespace
}  // namespace fireswarm::radio
