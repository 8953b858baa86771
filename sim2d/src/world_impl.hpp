// The world's private state and step, behind World's pimpl (Box2D stays out of
// the public headers).
#pragma once

#include <box2d/box2d.h>

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "collision_tracker.hpp"
#include "fault_state.hpp"
#include "fireswarm/common/local_frame.hpp"
#include "fireswarm/sim2d/world.hpp"
#include "multirotor_dynamics.hpp"
#include "sensor_suite.hpp"

namespace fireswarm::sim2d {

/// One vehicle's plant state beyond its VehicleTruth.
struct VehicleRuntime {
  /// On the ground, disarmed, battery at its initial charge.
  VehicleRuntime(const VehicleConfig& vehicle, b2Body* vehicle_body, double substep_s,
                 std::uint64_t seed);

  VehicleConfig config;                 ///< parameters and fault schedule
  MultirotorCoefficients coefficients;  ///< for the physics sub-step
  b2Body* body = nullptr;               ///< owned by the b2World
  ActuatorCommand command;
  double thrust_n = 0.0;
  AttitudeTrig trig;     ///< of the attitude in the current sub-step
  double power_w = 0.0;  ///< electrical draw of the last sub-step
  double energy_j = 0.0;
  double capacity_j = 0.0;
  bool battery_empty = false;
  /// When the ground crew's swap is due (a landing with battery_swap_s > 0);
  /// negative: none due.
  double swap_due_s = -1.0;
  FaultState faults;  ///< active during the current step
  SensorSuite sensors;
};

struct World::Impl {
  explicit Impl(const WorldConfig& world_config);

  void Add(const VehicleConfig& vehicle);
  std::size_t IndexOf(int id) const;
  double time_s() const { return static_cast<double>(steps) * config.step_s; }
  void Step();
  std::uint64_t Hash() const;

  WorldConfig config;  ///< without the vehicles (they live in `vehicles`)
  common::LocalFrame frame;
  double substep_s;
  std::vector<VehicleTruth> truths;
  std::vector<double> half_heights_m;
  std::vector<SensorSample> samples;
  std::vector<VehicleRuntime> vehicles;
  std::unordered_map<int, std::size_t> index_of;
  EventLog events;
  CollisionTracker tracker;
  b2World physics;  // after the tracker: destroyed first, it points to it
  NoiseSource wind_noise;
  Vec2 steady_wind_mps = Vec2::Zero();
  GaussMarkov gust_east;
  GaussMarkov gust_north;
  Vec2 wind_mps = Vec2::Zero();
  std::int64_t steps = 0;
  double event_time_s = 0.0;  ///< stamped on events recorded now (sub-step start)

 private:
  void UpdateWindAndFaults(double time_s);
  void PrePhysics(std::size_t index);
  void PostPhysics(std::size_t index);
  void HandleCollisionCrashes();
  void SampleSensors(double time_s);
  void Crash(std::size_t index, double impact_speed_mps, int other_id);
  void Lose(std::size_t index);
  void Record(EventKind kind, std::size_t index, double speed_mps = 0.0, int other_id = 0);
};

}  // namespace fireswarm::sim2d
