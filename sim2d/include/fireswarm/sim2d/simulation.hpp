// The whole simulated plant in one place: the world (vehicles, sensors, faults,
// collisions), the fire, the ground temperatures, and each vehicle's thermal
// camera at its own frame rate. The lockstep runner and `fireswarm sim-bench`
// drive it; it never reads a clock.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "fireswarm/sim2d/fire_config.hpp"
#include "fireswarm/sim2d/fire_grid.hpp"
#include "fireswarm/sim2d/temperature_field.hpp"
#include "fireswarm/sim2d/thermal_camera.hpp"
#include "fireswarm/sim2d/thermal_image.hpp"
#include "fireswarm/sim2d/world.hpp"
#include "fireswarm/sim2d/world_config.hpp"

namespace fireswarm::sim2d {

/// The camera one vehicle carries.
struct VehicleCamera {
  int vehicle_id = 0;
  std::string model = "seed";  ///< a name from common::CameraModels()
  CameraMount mount;
  ThermalCameraOptions options;
};

struct SimulationConfig {
  WorldConfig world;  ///< its seed seeds every generator of the simulation
  FireConfig fire;    ///< the fire grid; its origin/size should cover the flown area
  std::vector<Ignition> ignitions;
  /// N more ignitions at random burnable cells, at random times in
  /// [0, random_ignition_window_s] (seed 4.3.1: random fire positions).
  int random_ignitions = 0;
  double random_ignition_window_s = 0.0;
  std::vector<Distractor> distractors;
  int random_distractors = 0;  ///< added at random in the fire area, 40-70 C
  std::vector<VehicleCamera> cameras;
  /// The fire advances in steps of this (its events keep exact times; this only
  /// sets how stale the temperatures a camera sees can be).
  double fire_step_s = 1.0;

  /// Checks what World and FireGrid do not: cameras name known vehicles and
  /// models, one camera per vehicle, counts and steps in range. Throws
  /// std::invalid_argument naming the field.
  void Validate() const;
};

/// A frame a camera took during the last step.
struct CameraFrame {
  int vehicle_id = 0;
  const ThermalImage* image = nullptr;  ///< valid until that camera's next frame
};

class Simulation {
 public:
  /// Validates the config (std::invalid_argument naming the field) and builds
  /// the world, the fire with its ignitions and the cameras.
  explicit Simulation(const SimulationConfig& config);
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  /// One fixed step: physics, then the fire when its step is due, then every
  /// camera whose frame is due. The three parts are also callable one by one
  /// (in this order) so a benchmark can time each.
  void Step();
  void StepPhysics();
  void StepFire();
  void StepCameras();

  World& world() { return world_; }
  const World& world() const { return world_; }
  const FireGrid& fire() const { return *fire_; }
  const TemperatureField& temperatures() const { return *field_; }
  double time_s() const { return world_.time_s(); }

  /// Frames taken in the last StepCameras(), in camera order.
  std::span<const CameraFrame> new_frames() const { return new_frames_; }
  /// The newest frame of a vehicle's camera; nullptr before its first frame or
  /// when the vehicle has no camera.
  const ThermalImage* LatestFrame(int vehicle_id) const;
  /// The camera of a vehicle (for geometry: pixel <-> ground); nullptr if none.
  const ThermalCamera* CameraOf(int vehicle_id) const;
  std::int64_t camera_frames() const { return camera_frames_; }

  /// World hash combined with the fire's cell states and every camera's newest frame.
  std::uint64_t StateHash() const;

 private:
  struct CameraSlot {
    int vehicle_id = 0;
    std::size_t vehicle_index = 0;
    ThermalCamera camera;
    Rng rng;
    ThermalImage image;
    std::int64_t frames = 0;  ///< frame slots passed; the next is due at (frames + 1) / rate
    bool has_image = false;
  };

  World world_;
  std::unique_ptr<FireGrid> fire_;
  std::unique_ptr<TemperatureField> field_;
  std::vector<CameraSlot> cameras_;
  std::vector<CameraFrame> new_frames_;
  double fire_step_s_ = 1.0;
  double next_fire_s_ = 0.0;
  std::int64_t camera_frames_ = 0;
};

}  // namespace fireswarm::sim2d
