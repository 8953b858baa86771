// The vehicle's mission store: reassembles a mission uploaded over the radio in
// chunks (seed 5.3: the GCS sends the waypoints, the autopilot keeps them) and
// keeps the last complete mission flyable until another one completes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "fireswarm/radio/messages.hpp"
#include "fireswarm/radio/mission_chunks.hpp"  // SplitMission, the server's side

namespace fireswarm::agents {

/// A mission as uploaded: its ID and waypoints in flying order.
struct Mission {
  std::uint16_t id = 0;
  std::vector<radio::Waypoint> waypoints;
};

/// How far the upload in progress has come.
struct MissionUpload {
  std::uint16_t mission_id = 0;
  std::size_t chunks_received = 0;
  std::size_t chunk_count = 0;
  std::size_t waypoints_received = 0;
  std::size_t total_waypoints = 0;
};

/// Reassembles chunked uploads. A mission ID names one content: the server picks a
/// new ID for every new mission (a chunk of the complete mission's ID is a retry).
///
/// OnChunk() rules, in order:
///  - A malformed chunk is kRejected and changes nothing: total_waypoints 0,
///    chunk_index >= chunk_count, waypoint_count 0 or above kMaxWaypointsPerChunk,
///    waypoints beyond total_waypoints, a latitude outside [-90, 90] deg, a longitude
///    outside [-180, 180] deg, a negative altitude or speed, anything not finite.
///  - A chunk of the complete mission's ID is a retry: kComplete when it agrees with
///    the stored mission (counts and waypoints), else kRejected; the upload in
///    progress, if any, is untouched.
///  - A chunk of the upload in progress must agree with what arrived before: same
///    chunk_count and total_waypoints, a re-sent chunk_index with the same range, a
///    waypoint index already received with the same waypoint; else kRejected and
///    nothing changes. Re-sending a chunk is idempotent.
///  - A chunk of another ID starts a new upload, discarding the partial one.
///  - When every chunk index and every waypoint index has arrived, the upload
///    becomes the complete mission (replacing the previous one): kComplete.
///    Otherwise kAccepted. A half-uploaded mission never replaces a complete one.
class MissionStore {
 public:
  /// Stores one chunk as above. Never throws (radio callback).
  radio::MissionAckStatus OnChunk(const radio::MissionChunk& chunk);

  /// The last completely uploaded mission; nullptr before the first.
  const Mission* complete() const { return complete_ ? &*complete_ : nullptr; }
  /// True when `mission_id` is the complete mission.
  bool IsComplete(std::uint16_t mission_id) const {
    return complete_ && complete_->id == mission_id;
  }
  /// The upload in progress; nullopt when none (none started, or it completed).
  std::optional<MissionUpload> upload() const;
  /// Chunks answered kRejected since construction.
  std::uint64_t rejected_chunks() const { return rejected_chunks_; }

 private:
  struct Upload {
    std::uint16_t mission_id = 0;
    std::uint16_t total_waypoints = 0;
    // By chunk index: (first_waypoint, waypoint_count), count 0 until received.
    std::vector<std::pair<std::uint16_t, std::uint8_t>> chunks;
    std::vector<radio::Waypoint> waypoints;  // by index, valid where received
    std::vector<bool> received;              // by waypoint index
    std::size_t chunks_received = 0;
    std::size_t waypoints_received = 0;
  };

  radio::MissionAckStatus Reject();
  bool AgreesWithUpload(const radio::MissionChunk& chunk) const;
  bool AgreesWithComplete(const radio::MissionChunk& chunk) const;
  radio::MissionAckStatus Store(const radio::MissionChunk& chunk);

  std::optional<Upload> upload_;
  std::optional<Mission> complete_;
  std::size_t complete_chunk_count_ = 0;
  std::uint64_t rejected_chunks_ = 0;
};

}  // namespace fireswarm::agents
