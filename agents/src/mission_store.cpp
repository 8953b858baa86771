#include "fireswarm/agents/mission_store.hpp"

#include <algorithm>
#include <cmath>
#include <span>

namespace fireswarm::agents {
namespace {

using radio::MissionAckStatus;
using radio::MissionChunk;
using radio::Waypoint;

constexpr double kMaxLatDeg = 90.0;
constexpr double kMaxLonDeg = 180.0;

bool ValidWaypoint(const Waypoint& w) {
  return std::isfinite(w.lat_deg) && std::abs(w.lat_deg) <= kMaxLatDeg &&
         std::isfinite(w.lon_deg) && std::abs(w.lon_deg) <= kMaxLonDeg &&
         std::isfinite(w.altitude_m) && w.altitude_m >= 0.0 && std::isfinite(w.speed_mps) &&
         w.speed_mps >= 0.0;
}

// What a chunk must satisfy on its own, whatever arrived before.
bool WellFormed(const MissionChunk& chunk) {
  if (chunk.total_waypoints == 0 || chunk.chunk_index >= chunk.chunk_count) return false;
  if (chunk.waypoint_count == 0 || chunk.waypoint_count > radio::kMaxWaypointsPerChunk) {
    return false;
  }
  if (std::size_t{chunk.first_waypoint} + chunk.waypoint_count > chunk.total_waypoints) {
    return false;
  }
  const std::span<const Waypoint> waypoints = chunk.active();
  return std::all_of(waypoints.begin(), waypoints.end(), ValidWaypoint);
}

// The chunk's waypoints as they sit in the whole mission.
std::span<const Waypoint> Slice(const std::vector<Waypoint>& mission, const MissionChunk& chunk) {
  return std::span<const Waypoint>(mission).subspan(chunk.first_waypoint, chunk.waypoint_count);
}

}  // namespace

MissionAckStatus MissionStore::OnChunk(const MissionChunk& chunk) {
  if (!WellFormed(chunk)) return Reject();
  if (IsComplete(chunk.mission_id)) {
    return AgreesWithComplete(chunk) ? MissionAckStatus::kComplete : Reject();
  }
  if (upload_ && upload_->mission_id == chunk.mission_id) {
    if (!AgreesWithUpload(chunk)) return Reject();
  } else {
    // A new mission: the partial upload, if any, is dropped; the complete one stays.
    Upload fresh;
    fresh.mission_id = chunk.mission_id;
    fresh.total_waypoints = chunk.total_waypoints;
    fresh.chunks.assign(chunk.chunk_count, {0, 0});
    fresh.waypoints.assign(chunk.total_waypoints, Waypoint{});
    fresh.received.assign(chunk.total_waypoints, false);
    upload_ = std::move(fresh);
  }
  return Store(chunk);
}

std::optional<MissionUpload> MissionStore::upload() const {
  if (!upload_) return std::nullopt;
  MissionUpload progress;
  progress.mission_id = upload_->mission_id;
  progress.chunks_received = upload_->chunks_received;
  progress.chunk_count = upload_->chunks.size();
  progress.waypoints_received = upload_->waypoints_received;
  progress.total_waypoints = upload_->total_waypoints;
  return progress;
}

MissionAckStatus MissionStore::Reject() {
  ++rejected_chunks_;
  return MissionAckStatus::kRejected;
}

bool MissionStore::AgreesWithComplete(const MissionChunk& chunk) const {
  const std::vector<Waypoint>& stored = complete_->waypoints;
  if (chunk.chunk_count != complete_chunk_count_ || chunk.total_waypoints != stored.size()) {
    return false;
  }
  const std::span<const Waypoint> slice = Slice(stored, chunk);
  return std::equal(slice.begin(), slice.end(), chunk.active().begin());
}

bool MissionStore::AgreesWithUpload(const MissionChunk& chunk) const {
  const Upload& up = *upload_;
  if (chunk.chunk_count != up.chunks.size() || chunk.total_waypoints != up.total_waypoints) {
    return false;
  }
  const auto& [first, count] = up.chunks[chunk.chunk_index];
  if (count != 0 && (first != chunk.first_waypoint || count != chunk.waypoint_count)) {
    return false;
  }
  const std::span<const Waypoint> incoming = chunk.active();
  for (std::size_t k = 0; k < incoming.size(); ++k) {
    const std::size_t index = chunk.first_waypoint + k;
    if (up.received[index] && up.waypoints[index] != incoming[k]) return false;
  }
  return true;
}

MissionAckStatus MissionStore::Store(const MissionChunk& chunk) {
  Upload& up = *upload_;
  auto& range = up.chunks[chunk.chunk_index];
  if (range.second == 0) {
    range = {chunk.first_waypoint, chunk.waypoint_count};
    ++up.chunks_received;
  }
  const std::span<const Waypoint> incoming = chunk.active();
  for (std::size_t k = 0; k < incoming.size(); ++k) {
    const std::size_t index = chunk.first_waypoint + k;
    if (!up.received[index]) {
      up.received[index] = true;
      up.waypoints[index] = incoming[k];
      ++up.waypoints_received;
    }
  }
  if (up.chunks_received < up.chunks.size() || up.waypoints_received < up.waypoints.size()) {
    return MissionAckStatus::kAccepted;
  }
  Mission mission;
  mission.id = up.mission_id;
  mission.waypoints = std::move(up.waypoints);
  complete_ = std::move(mission);
  complete_chunk_count_ = up.chunks.size();
  upload_.reset();
  return MissionAckStatus::kComplete;
}

}  // namespace fireswarm::agents
