#include "fireswarm/sim2d/simulation.hpp"

#include <cmath>
#include <set>
#include <stdexcept>
#include <string>

#include "fireswarm/common/camera_model.hpp"
#include "fireswarm/sim2d/random.hpp"
#include "world_hash.hpp"

namespace fireswarm::sim2d {
namespace {

// Camera frames are due at k / rate; this absorbs the rounding of step sums.
constexpr double kFrameDueToleranceS = 1e-9;

[[noreturn]] void Bad(const std::string& field, const std::string& problem) {
  throw std::invalid_argument("simulation: " + field + " " + problem);
}

// The fire grid's area as a ground box (for random distractors).
GroundBox FireArea(const FireConfig& fire) {
  return {fire.origin_m, fire.origin_m + Vec2(fire.width_m, fire.height_m)};
}

}  // namespace

void SimulationConfig::Validate() const {
  world.Validate();
  fire.Validate();
  if (!(fire_step_s > 0.0 && std::isfinite(fire_step_s))) {
    Bad("fire_step_s", "must be > 0, got " + std::to_string(fire_step_s));
  }
  if (random_ignitions < 0) {
    Bad("random_ignitions", "must be >= 0, got " + std::to_string(random_ignitions));
  }
  if (!(random_ignition_window_s >= 0.0)) {
    Bad("random_ignition_window_s",
        "must be >= 0, got " + std::to_string(random_ignition_window_s));
  }
  if (random_distractors < 0) {
    Bad("random_distractors", "must be >= 0, got " + std::to_string(random_distractors));
  }
  std::set<int> vehicle_ids;
  for (const VehicleConfig& vehicle : world.vehicles) vehicle_ids.insert(vehicle.id);
  std::set<int> with_camera;
  for (std::size_t i = 0; i < cameras.size(); ++i) {
    const VehicleCamera& camera = cameras[i];
    const std::string field = "cameras[" + std::to_string(i) + "]";
    if (!vehicle_ids.contains(camera.vehicle_id)) {
      Bad(field + ".vehicle_id", "names no vehicle: " + std::to_string(camera.vehicle_id));
    }
    if (!with_camera.insert(camera.vehicle_id).second) {
      Bad(field + ".vehicle_id", "already has a camera: " + std::to_string(camera.vehicle_id));
    }
    if (common::FindCameraModel(camera.model) == nullptr) {
      Bad(field + ".model",
          "must be one of " + common::CameraModelNames() + ", got '" + camera.model + "'");
    }
  }
}

Simulation::Simulation(const SimulationConfig& config)
    : world_((config.Validate(), config.world)), fire_step_s_(config.fire_step_s) {
  const std::uint64_t seed = config.world.seed;
  fire_ = std::make_unique<FireGrid>(config.fire, MakeRng(seed, "fire.spread"));
  for (const Ignition& ignition : config.ignitions) fire_->AddIgnition(ignition);
  if (config.random_ignitions > 0) {
    Rng rng = MakeRng(seed, "fire.ignitions");
    for (const Ignition& ignition : RandomIgnitions(*fire_, config.random_ignitions, 0.0,
                                                    config.random_ignition_window_s, rng)) {
      fire_->AddIgnition(ignition);
    }
  }
  std::vector<Distractor> distractors = config.distractors;
  if (config.random_distractors > 0) {
    Rng rng = MakeRng(seed, "distractors");
    for (const Distractor& d :
         RandomDistractors(config.random_distractors, FireArea(config.fire), rng)) {
      distractors.push_back(d);
    }
  }
  field_ = std::make_unique<TemperatureField>(*fire_, std::move(distractors));
  cameras_.reserve(config.cameras.size());
  for (const VehicleCamera& camera : config.cameras) {
    const auto id = static_cast<std::uint64_t>(camera.vehicle_id);
    cameras_.push_back(CameraSlot{
        camera.vehicle_id, world_.IndexOf(camera.vehicle_id),
        ThermalCamera(common::CameraModelByName(camera.model), camera.mount, camera.options),
        MakeRng(seed, "camera.noise", id), ThermalImage{}, 0, false});
  }
  new_frames_.reserve(cameras_.size());
  fire_->AdvanceTo(0.0);
  next_fire_s_ = fire_step_s_;
}

Simulation::~Simulation() = default;

void Simulation::Step() {
  StepPhysics();
  StepFire();
  StepCameras();
}

void Simulation::StepPhysics() {
  world_.Step();
}

void Simulation::StepFire() {
  const double now_s = world_.time_s();
  if (now_s + kFrameDueToleranceS < next_fire_s_) return;
  fire_->AdvanceTo(now_s);
  while (next_fire_s_ <= now_s + kFrameDueToleranceS) next_fire_s_ += fire_step_s_;
}

void Simulation::StepCameras() {
  new_frames_.clear();
  const double now_s = world_.time_s();
  const std::span<const VehicleTruth> truths = world_.Truths();
  for (CameraSlot& slot : cameras_) {
    const double rate_hz = slot.camera.model().frame_rate_hz;
    // Frame k (k = 1, 2, ...) is exposed at the first step at or after k / rate.
    if (static_cast<double>(slot.frames + 1) / rate_hz > now_s + kFrameDueToleranceS) continue;
    // A camera that fell behind (rate above 1 / step) takes one frame, not a burst.
    slot.frames = static_cast<std::int64_t>(std::floor((now_s + kFrameDueToleranceS) * rate_hz));
    const VehicleTruth& truth = truths[slot.vehicle_index];
    if (truth.phase == FlightPhase::kLost || truth.phase == FlightPhase::kCrashed) continue;
    slot.camera.Render(truth, *field_, now_s, slot.rng, slot.image);
    slot.has_image = true;
    ++camera_frames_;
    new_frames_.push_back({slot.vehicle_id, &slot.image});
  }
}

const ThermalImage* Simulation::LatestFrame(int vehicle_id) const {
  for (const CameraSlot& slot : cameras_) {
    if (slot.vehicle_id == vehicle_id) return slot.has_image ? &slot.image : nullptr;
  }
  return nullptr;
}

const ThermalCamera* Simulation::CameraOf(int vehicle_id) const {
  for (const CameraSlot& slot : cameras_) {
    if (slot.vehicle_id == vehicle_id) return &slot.camera;
  }
  return nullptr;
}

std::uint64_t Simulation::StateHash() const {
  StateHasher hasher;
  hasher.Add(world_.StateHash());
  for (int row = 0; row < fire_->rows(); ++row) {
    for (int col = 0; col < fire_->cols(); ++col) {
      hasher.Add(static_cast<int>(fire_->StateAt({col, row})));
    }
  }
  for (const CameraSlot& slot : cameras_) {
    hasher.Add(static_cast<std::uint64_t>(slot.frames));
    for (const std::uint8_t grey : slot.image.pixels) hasher.Add(static_cast<int>(grey));
  }
  return hasher.value();
}

}  // namespace fireswarm::sim2d
