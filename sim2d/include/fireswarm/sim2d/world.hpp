// The simulated world: multirotors moving in a Box2D horizontal plane with
// altitude integrated beside it, ground contact, battery, drone-drone collisions
// only when altitude bands overlap, near-miss tracking, sensors at their own rates
// and scheduled faults. A pure core: fixed step, no wall clock, seeded generators.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <vector>

#include "fireswarm/common/local_frame.hpp"
#include "fireswarm/sim2d/events.hpp"
#include "fireswarm/sim2d/faults.hpp"
#include "fireswarm/sim2d/sensors.hpp"
#include "fireswarm/sim2d/vehicle_state.hpp"
#include "fireswarm/sim2d/world_config.hpp"

namespace fireswarm::sim2d {

/// Typical use (the lockstep runner):
/// ```
///   World world(config);                       // adds config.vehicles
///   for (...) {
///     world.SetCommand(id, command);           // held until changed
///     world.Step();                            // + config.step_s
///     const SensorSample& s = world.Sensors(id);
///     if (s.gps) { ... }                       // set only when a sample came up
///   }
///   world.events(); world.StateHash();
/// ```
/// Vehicles keep the index they were added with; the *At(index) accessors and the
/// spans skip the ID lookup for whole-fleet loops.
class World {
 public:
  /// Validates `config` (std::invalid_argument naming the field) and adds its vehicles.
  explicit World(const WorldConfig& config);
  ~World();
  World(World&&) noexcept;
  World& operator=(World&&) noexcept;
  World(const World&) = delete;
  World& operator=(const World&) = delete;

  /// Adds a vehicle on the ground at its launch position, disarmed. Throws
  /// std::invalid_argument on a duplicate ID or a bad parameter.
  void AddVehicle(const VehicleConfig& vehicle);
  /// Adds a vehicle with default parameters.
  void AddVehicle(int id, Vec2 launch_position_m);
  /// Schedules a fault on a vehicle. Throws std::out_of_range for an unknown ID and
  /// std::invalid_argument for a bad fault.
  void ScheduleFault(int id, const FaultSpec& fault);

  /// The command held from the next step on. Throws std::out_of_range for an unknown ID.
  void SetCommand(int id, const ActuatorCommand& command);
  void SetCommandAt(std::size_t index, const ActuatorCommand& command);

  /// Advances the world by one fixed step (config.step_s).
  void Step();
  /// Steps until time_s() has advanced by `duration_s` (rounded to whole steps).
  void RunFor(double duration_s);

  double time_s() const;
  double step_s() const;
  std::int64_t step_count() const;
  std::size_t vehicle_count() const;
  /// The index of a vehicle. Throws std::out_of_range for an unknown ID.
  std::size_t IndexOf(int id) const;
  bool HasVehicle(int id) const;

  /// Truth (for cameras and scoring only). Throws std::out_of_range for an unknown ID.
  const VehicleTruth& Truth(int id) const;
  /// All truths, in the order the vehicles were added.
  std::span<const VehicleTruth> Truths() const;
  /// The sensor samples of the last step. Throws std::out_of_range for an unknown ID.
  const SensorSample& Sensors(int id) const;
  /// All sensor samples of the last step, aligned with Truths().
  std::span<const SensorSample> AllSensors() const;

  /// The events so far, in order of occurrence: every one counted, the latest
  /// kKeptWorldEvents kept (near misses stay `open` while the encounter lasts
  /// and their min_separation_m keeps shrinking).
  const EventLog& events() const;
  /// The smallest 3D centre distance seen between two vehicles (neither lost, at
  /// least one flying) whose horizontal distance was within 1.1 times the near-miss
  /// separation; +infinity when no pair ever came that close.
  double min_separation_m() const;
  /// The wind now (steady + gust), local ENU, where the air moves to.
  Vec2 wind_mps() const;
  const common::LocalFrame& frame() const;

  /// A hash of the whole simulation state (truth, internal plant state, sensor
  /// biases and last readings, events), over the bit patterns of the doubles.
  /// Same config and commands, same binary -> same hash.
  std::uint64_t StateHash() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fireswarm::sim2d
