// Drone-drone contacts and near misses through Box2D's broadphase.
//
// Each vehicle's body has two fixtures: a solid disc (its rotors) and a sensor
// disc of radius 1.1 x near-miss separation / 2, so two sensor discs overlap
// exactly when the vehicles are horizontally within 1.1 x the separation. Box2D
// keeps that pair list up to date cheaply; the tracker checks only those pairs
// in 3D. Solid contacts count only when the altitude bands overlap: PreSolve
// disables the contact otherwise, every step (Box2D 2.4 re-runs ShouldCollide
// only on refilter, and re-enables every contact at each update).
#pragma once

#include <box2d/box2d.h>

#include <cstdint>
#include <span>
#include <vector>

#include "fireswarm/sim2d/events.hpp"
#include "fireswarm/sim2d/vehicle_state.hpp"
#include "fireswarm/sim2d/world_config.hpp"

namespace fireswarm::sim2d {

/// Fixture user data: vehicle index << 1, low bit set for the near-miss sensor.
std::uintptr_t FixtureTag(std::size_t vehicle_index, bool near_miss_sensor);

/// Collision filter categories: solid discs meet solid discs, sensors sensors.
inline constexpr std::uint16_t kSolidCategory = 0x0001;
inline constexpr std::uint16_t kNearMissCategory = 0x0002;

/// The encounter factor: an encounter opens below the separation and closes
/// beyond this times it (a hysteresis, so one pass is one event).
inline constexpr double kNearMissExitFactor = 1.1;

/// A collision that must crash both vehicles (relative speed above the limit).
struct CollisionCrash {
  std::size_t vehicle_a = 0;
  std::size_t vehicle_b = 0;
  double relative_speed_mps = 0.0;
};

class CollisionTracker final : public b2ContactListener {
 public:
  /// The tracker reads the vehicles' truths and band half-heights (indexed like
  /// the fixtures' tags) and appends to `events`; all must outlive it.
  CollisionTracker(const CollisionParams& params, const std::vector<VehicleTruth>& truths,
                   const std::vector<double>& half_heights_m, EventLog& events);

  /// The time stamped on events recorded from now on.
  void set_time_s(double time_s) { time_s_ = time_s; }

  void BeginContact(b2Contact* contact) override;
  void EndContact(b2Contact* contact) override;
  void PreSolve(b2Contact* contact, const b2Manifold* old_manifold) override;

  /// After each physics step: 3D separations of the horizontally close pairs,
  /// near-miss encounters opened, updated and closed, the overall minimum.
  void UpdateNearMisses();

  /// Collisions since the last call that were hard enough to crash; cleared by the call.
  std::span<const CollisionCrash> crashes() const { return crashes_; }
  void ClearCrashes() { crashes_.clear(); }

  double min_separation_m() const { return min_separation_m_; }

 private:
  struct NearPair {
    std::uint32_t a = 0;
    std::uint32_t b = 0;
    bool in_encounter = false;
    std::uint64_t event_index = 0;  // its number in the EventLog
  };
  struct Pair {
    std::uint32_t a = 0;
    std::uint32_t b = 0;
  };

  bool BandsOverlap(std::size_t a, std::size_t b) const;
  double RelativeSpeed(const b2Body& body_a, const b2Body& body_b, std::size_t a,
                       std::size_t b) const;
  void CloseEncounter(NearPair& pair);

  CollisionParams params_;
  const std::vector<VehicleTruth>& truths_;
  const std::vector<double>& half_heights_m_;
  EventLog& events_;
  double time_s_ = 0.0;
  std::vector<NearPair> near_pairs_;  // sensor discs overlapping now
  std::vector<Pair> colliding_;       // solid contacts enabled and touching now
  std::vector<CollisionCrash> crashes_;
  double min_separation_m_;
};

}  // namespace fireswarm::sim2d
