// The hardware-in-the-loop bridge (seed chapter 4, the HIL FlightData idea): sim2d's
// sensor samples and camera frames become a vehicle's inputs, its actuator outputs
// become the simulator's commands. The vehicle never sees the simulator's truth.
#pragma once

#include <span>
#include <vector>

#include "fireswarm/agents/vehicle.hpp"
#include "fireswarm/agents/vehicle_io.hpp"
#include "fireswarm/common/time.hpp"
#include "fireswarm/sim2d/sensors.hpp"
#include "fireswarm/sim2d/simulation.hpp"
#include "fireswarm/sim2d/thermal_image.hpp"
#include "fireswarm/sim2d/vehicle_state.hpp"

namespace fireswarm::hil {

/// One step's sensor samples as the vehicle reads them (no camera frame).
agents::SensorInputs ToVehicleInputs(const sim2d::SensorSample& sample);

/// A view of `image` (its pixels must outlive the frame) with its grey mapping.
agents::CameraFrame ToCameraFrame(const sim2d::ThermalImage& image);

sim2d::ActuatorCommand ToActuatorCommand(const agents::ActuatorOutputs& outputs);

/// Steps a Simulation and the vehicles flying in it, in lockstep on simulated time:
/// the simulation steps (physics, fire, cameras), then each vehicle steps with its
/// sensors and any new frame, and its commands act from the next step on. The
/// radio is not part of it: the caller feeds the vehicles' OnRadio().
class LockstepFleet {
 public:
  /// `simulation` and every vehicle added must outlive the fleet.
  explicit LockstepFleet(sim2d::Simulation& simulation) : simulation_(simulation) {}

  /// Flies `vehicle` as the world's vehicle of the same ID. Throws
  /// std::invalid_argument when the world has no such vehicle.
  void Add(agents::Vehicle& vehicle);
  /// Stops stepping vehicle `id` (its software is down): the simulator keeps
  /// acting on its last commands, as motor controllers hold their last outputs.
  /// Nothing happens when it is not in the fleet.
  void Remove(int id);

  void Step();
  /// Steps until the simulated time reaches `time_s`.
  void RunUntil(double time_s);

  common::Nanos now() const { return common::FromSeconds(simulation_.time_s()); }
  sim2d::Simulation& simulation() { return simulation_; }

 private:
  sim2d::Simulation& simulation_;
  std::vector<agents::Vehicle*> vehicles_;
};

}  // namespace fireswarm::hil
