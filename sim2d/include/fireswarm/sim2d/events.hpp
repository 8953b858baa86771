// Things that happen in the simulated world, recorded for the report and for
// scoring: collisions, near misses, crashes, losses, take-offs and landings.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <deque>

namespace fireswarm::sim2d {

enum class EventKind {
  kCollision,  ///< two vehicles' discs touch while their altitude bands overlap
  kNearMiss,   ///< two vehicles came closer (3D) than the near-miss separation
  kCrash,      ///< a vehicle hit the ground (or another vehicle) too hard
  kLoss,       ///< a total-loss fault removed a vehicle
  kTakeOff,
  kLanding,       ///< a soft touch-down
  kBatteryEmpty,  ///< the charge reached zero; the motors stop
  kBatterySwap,   ///< the ground crew put in a full pack (WorldConfig::battery_swap_s)
};
inline constexpr std::size_t kEventKinds = 8;

/// One event. `vehicle_b` is 0 for events of one vehicle.
struct WorldEvent {
  EventKind kind = EventKind::kCollision;
  double time_s = 0.0;  ///< simulated time when it began
  int vehicle_a = 0;    ///< receiver ID; for pairs the smaller ID
  int vehicle_b = 0;
  /// kCollision: |v_a - v_b| in 3D just before the impulse. kCrash: the impact
  /// speed (3D) against the ground or the other vehicle.
  double relative_speed_mps = 0.0;
  /// kNearMiss (and kCollision): the smallest 3D centre distance of the encounter.
  /// It keeps shrinking while `open` is true, i.e. while the encounter lasts.
  double min_separation_m = 0.0;
  bool open = false;  ///< kNearMiss: the vehicles are still inside the separation
};

/// The latest this many events are kept (and every open near miss, however
/// old); every event is counted. A day of patrols records some ten thousand.
inline constexpr std::size_t kKeptWorldEvents = 1'000;

/// The world's events in order of occurrence, numbered from 0: every one
/// counted, the latest kKeptWorldEvents kept, so a long run does not grow.
/// Read new ones by number (first(), at()) to miss none between steps.
class EventLog {
 public:
  /// Appends `event`; returns its number.
  std::uint64_t Add(const WorldEvent& event);
  /// Drops the oldest events beyond kKeptWorldEvents, stopping at an open one.
  void Trim();

  /// The event numbered `number`, first() <= number < total().
  const WorldEvent& at(std::uint64_t number) const { return kept_[number - first_]; }
  WorldEvent& at(std::uint64_t number) { return kept_[number - first_]; }
  /// The number of the oldest event kept.
  std::uint64_t first() const { return first_; }
  /// Events so far, kept or not.
  std::uint64_t total() const { return first_ + kept_.size(); }
  /// Events of `kind` so far, kept or not.
  std::uint64_t count(EventKind kind) const { return counts_[static_cast<std::size_t>(kind)]; }

  /// The kept events, oldest first.
  std::deque<WorldEvent>::const_iterator begin() const { return kept_.begin(); }
  std::deque<WorldEvent>::const_iterator end() const { return kept_.end(); }
  std::size_t size() const { return kept_.size(); }
  bool empty() const { return kept_.empty(); }

 private:
  std::deque<WorldEvent> kept_;
  std::uint64_t first_ = 0;
  std::array<std::uint64_t, kEventKinds> counts_{};
};

}  // namespace fireswarm::sim2d
