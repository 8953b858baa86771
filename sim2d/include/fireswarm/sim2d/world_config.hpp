// Configuration of the simulated world: geodetic origin, time step, wind,
// collision settings and the vehicles with their parameters and fault schedules.
// Plain structs; scenario files are parsed elsewhere and fill these in.
#pragma once

#include <cstdint>
#include <vector>

#include "fireswarm/common/local_frame.hpp"
#include "fireswarm/sim2d/faults.hpp"
#include "fireswarm/sim2d/multirotor.hpp"
#include "fireswarm/sim2d/sensors.hpp"
#include "fireswarm/sim2d/vehicle_state.hpp"

namespace fireswarm::sim2d {

/// A steady wind plus optional gusts (first-order Gauss-Markov per axis, one
/// generator for the whole world: every vehicle feels the same gust).
struct WindParams {
  double speed_mps = 0.0;
  double from_deg = 0.0;      ///< where it blows from, clockwise from north
  double gust_std_mps = 0.0;  ///< per axis; 0 = steady
  double gust_time_constant_s = 5.0;
};

struct CollisionParams {
  /// A pair of vehicles closer than this (3D, centre to centre) is a near miss,
  /// recorded once per encounter. The encounter ends beyond 1.1 times this.
  double near_miss_separation_m = 2.0;
  /// A collision at a relative speed above this crashes both vehicles.
  double crash_relative_speed_mps = 4.0;
  double restitution = 0.3;
  double friction = 0.3;
};

/// One vehicle: its receiver ID, where it stands at launch, and its parameters.
struct VehicleConfig {
  int id = 1;                             ///< receiver ID, >= 1, unique
  Vec2 launch_position_m = Vec2::Zero();  ///< local ENU around the origin
  double launch_heading_rad = 0.0;        ///< clockwise from north
  MultirotorParams multirotor;
  SensorParams sensors;
  std::vector<FaultSpec> faults;
};

struct WorldConfig {
  common::LatLon origin{45.0, 7.0};  ///< geodetic origin of the local frame
  double step_s = 0.01;              ///< fixed step of World::Step()
  int substeps = 1;                  ///< physics sub-steps per step
  std::uint64_t seed = 1;            ///< scenario seed; one generator per source
  WindParams wind;
  CollisionParams collision;
  std::vector<VehicleConfig> vehicles;  ///< added by the World constructor
  /// The ground crew: a vehicle still on the ground this long after a soft
  /// landing gets a full pack (a kBatterySwap event), once per landing, s. Driven
  /// by simulated time only. 0: no crew, a pack is never swapped.
  double battery_swap_s = 0.0;

  /// Throws std::invalid_argument naming the first bad field and its value, e.g.
  /// "vehicle 3: multirotor.mass_kg must be > 0, got -1". Duplicate IDs are refused.
  void Validate() const;
};

/// Checks one vehicle against the world's step (sensor rates must not exceed
/// 1 / step_s). Throws std::invalid_argument like WorldConfig::Validate.
void ValidateVehicle(const VehicleConfig& vehicle, double step_s);

/// Checks one fault of the given vehicle. Throws std::invalid_argument.
void ValidateFault(int vehicle_id, const FaultSpec& fault);

}  // namespace fireswarm::sim2d
