// World::Impl::Step: wind and faults, then per physics sub-step the plant
// (attitude, thrust, forces) -> Box2D -> vertical axis, ground and battery, then
// near misses and the sensors at the step's end time.
#include "battery_model.hpp"
#include "box2d_units.hpp"
#include "world_impl.hpp"

namespace fireswarm::sim2d {
namespace {

// Box2D solver iterations (its manual's recommendation); they cost only per contact.
constexpr int kVelocityIterations = 8;
constexpr int kPositionIterations = 3;

void Level(VehicleTruth& truth) {
  truth.roll_rad = 0.0;
  truth.pitch_rad = 0.0;
  truth.roll_rate_radps = 0.0;
  truth.pitch_rate_radps = 0.0;
  truth.yaw_rate_radps = 0.0;
}

// The thrust after one motor-lag step toward what the climb loop asks for;
// nothing once the battery is empty. Needs vehicle.trig of this step.
double NextThrustN(const VehicleRuntime& vehicle, const VehicleTruth& truth) {
  const double target_n = vehicle.battery_empty
                              ? 0.0
                              : CommandedThrust(vehicle.config.multirotor, vehicle.coefficients,
                                                vehicle.command, truth, vehicle.trig);
  return StepThrust(vehicle.coefficients, vehicle.thrust_n, target_n);
}

}  // namespace

void World::Impl::Step() {
  events.Trim();  // the last step's events stay readable until this one
  const double start_s = time_s();
  UpdateWindAndFaults(start_s);
  for (int substep = 0; substep < config.substeps; ++substep) {
    event_time_s = start_s + substep_s * substep;
    tracker.set_time_s(event_time_s);
    for (std::size_t i = 0; i < vehicles.size(); ++i) PrePhysics(i);
    physics.Step(static_cast<float>(substep_s), kVelocityIterations, kPositionIterations);
    for (std::size_t i = 0; i < vehicles.size(); ++i) PostPhysics(i);
    HandleCollisionCrashes();
  }
  ++steps;
  event_time_s = time_s();
  tracker.set_time_s(event_time_s);
  tracker.UpdateNearMisses();
  SampleSensors(event_time_s);
}

void World::Impl::UpdateWindAndFaults(double time_s) {
  wind_mps = steady_wind_mps;
  if (config.wind.gust_std_mps > 0.0) {
    wind_mps += Vec2(gust_east.Advance(wind_noise), gust_north.Advance(wind_noise));
  }
  for (std::size_t i = 0; i < vehicles.size(); ++i) {
    VehicleRuntime& vehicle = vehicles[i];
    if (vehicle.config.faults.empty()) continue;
    vehicle.faults = ActiveFaults(vehicle.config.faults, time_s);
    if (vehicle.faults.lost && truths[i].phase != FlightPhase::kLost) Lose(i);
  }
}

void World::Impl::PrePhysics(std::size_t index) {
  VehicleRuntime& vehicle = vehicles[index];
  VehicleTruth& truth = truths[index];
  const MultirotorParams& params = vehicle.config.multirotor;
  const MultirotorCoefficients& coefficients = vehicle.coefficients;
  switch (truth.phase) {
    case FlightPhase::kLost:
      return;
    case FlightPhase::kCrashed:
      vehicle.thrust_n = 0.0;
      if (truth.altitude_m > 0.0) {
        const Vec2 drag_n = HorizontalForce(params, truth, vehicle.trig, 0.0, wind_mps);
        vehicle.body->ApplyForceToCenter(Box2dForce(drag_n), true);
      } else {
        vehicle.body->SetLinearVelocity(b2Vec2(0.0F, 0.0F));
      }
      return;
    case FlightPhase::kOnGround: {
      Level(truth);
      vehicle.trig = AttitudeTrig::Of(truth);
      vehicle.thrust_n = NextThrustN(vehicle, truth);
      vehicle.body->SetLinearVelocity(b2Vec2(0.0F, 0.0F));
      if (vehicle.thrust_n > coefficients.hover_thrust_n) {
        truth.phase = FlightPhase::kFlying;
        Record(EventKind::kTakeOff, index);
      }
      return;
    }
    case FlightPhase::kFlying: {
      StepAttitude(params, coefficients, vehicle.command, vehicle.faults.ballast_offset_m, truth);
      vehicle.trig = AttitudeTrig::Of(truth);
      vehicle.thrust_n = NextThrustN(vehicle, truth);
      const Vec2 force_n = HorizontalForce(params, truth, vehicle.trig, vehicle.thrust_n, wind_mps);
      vehicle.body->ApplyForceToCenter(Box2dForce(force_n), true);
      return;
    }
  }
}

void World::Impl::PostPhysics(std::size_t index) {
  VehicleTruth& truth = truths[index];
  if (truth.phase == FlightPhase::kLost) return;
  VehicleRuntime& vehicle = vehicles[index];
  const MultirotorParams& params = vehicle.config.multirotor;
  truth.position_m = MetresOf(vehicle.body->GetPosition());
  truth.velocity_mps = MetresOf(vehicle.body->GetLinearVelocity());
  double impact_speed_mps = 0.0;
  if (truth.phase == FlightPhase::kFlying) {
    const Touchdown touchdown = StepVertical(params, vehicle.coefficients, vehicle.trig,
                                             vehicle.thrust_n, truth, impact_speed_mps);
    if (touchdown == Touchdown::kLanded) {
      truth.phase = FlightPhase::kOnGround;
      Level(truth);
      Record(EventKind::kLanding, index, impact_speed_mps);
      if (config.battery_swap_s > 0.0) vehicle.swap_due_s = event_time_s + config.battery_swap_s;
    } else if (touchdown == Touchdown::kCrashed) {
      Crash(index, impact_speed_mps, 0);
    }
  } else if (truth.phase == FlightPhase::kCrashed && truth.altitude_m > 0.0) {
    StepVertical(params, vehicle.coefficients, vehicle.trig, 0.0, truth, impact_speed_mps);
  }
  vehicle.power_w = BatteryPowerW(params.battery, vehicle.thrust_n);
  vehicle.energy_j = DrainBatteryJ(vehicle.energy_j, vehicle.power_w, substep_s);
  if (truth.phase != FlightPhase::kOnGround) {
    vehicle.swap_due_s = -1.0;  // off the ground (or wrecked) before the crew came
  } else if (vehicle.swap_due_s >= 0.0 && event_time_s >= vehicle.swap_due_s) {
    vehicle.energy_j = vehicle.capacity_j;
    vehicle.battery_empty = false;
    vehicle.swap_due_s = -1.0;
    Record(EventKind::kBatterySwap, index);
  }
  truth.battery_fraction = vehicle.energy_j / vehicle.capacity_j;
  if (vehicle.energy_j <= 0.0 && !vehicle.battery_empty) {
    // Defined behaviour: at zero charge the motors stop for good; an airborne
    // vehicle falls and crashes unless it was within centimetres of the ground.
    vehicle.battery_empty = true;
    Record(EventKind::kBatteryEmpty, index);
  }
}

void World::Impl::HandleCollisionCrashes() {
  for (const CollisionCrash& crash : tracker.crashes()) {
    const int id_a = truths[crash.vehicle_a].id;
    const int id_b = truths[crash.vehicle_b].id;
    Crash(crash.vehicle_a, crash.relative_speed_mps, id_b);
    Crash(crash.vehicle_b, crash.relative_speed_mps, id_a);
  }
  tracker.ClearCrashes();
}

void World::Impl::SampleSensors(double time_s) {
  for (std::size_t i = 0; i < vehicles.size(); ++i) {
    VehicleRuntime& vehicle = vehicles[i];
    if (!vehicle.config.faults.empty()) {
      vehicle.faults = ActiveFaults(vehicle.config.faults, time_s);
      if (vehicle.faults.lost && truths[i].phase != FlightPhase::kLost) Lose(i);
    }
    const BatteryParams& battery = vehicle.config.multirotor.battery;
    BatteryTruth battery_truth;
    battery_truth.fraction = truths[i].battery_fraction;
    battery_truth.voltage_v = BatteryVoltageV(battery, battery_truth.fraction);
    battery_truth.current_a = vehicle.power_w / battery_truth.voltage_v;
    vehicle.sensors.Sample(time_s, truths[i], battery_truth, vehicle.faults, frame, samples[i]);
  }
}

void World::Impl::Crash(std::size_t index, double impact_speed_mps, int other_id) {
  VehicleTruth& truth = truths[index];
  if (truth.phase == FlightPhase::kCrashed || truth.phase == FlightPhase::kLost) return;
  truth.phase = FlightPhase::kCrashed;
  vehicles[index].thrust_n = 0.0;
  Record(EventKind::kCrash, index, impact_speed_mps, other_id);
}

void World::Impl::Lose(std::size_t index) {
  VehicleTruth& truth = truths[index];
  truth.phase = FlightPhase::kLost;
  // The truth keeps where it was lost; it no longer moves.
  truth.velocity_mps = Vec2::Zero();
  truth.climb_rate_mps = 0.0;
  Level(truth);
  VehicleRuntime& vehicle = vehicles[index];
  vehicle.thrust_n = 0.0;
  vehicle.power_w = 0.0;
  // Out of the broadphase: no contacts, no near misses (Box2D ends them now).
  vehicle.body->SetEnabled(false);
  Record(EventKind::kLoss, index);
}

void World::Impl::Record(EventKind kind, std::size_t index, double speed_mps, int other_id) {
  WorldEvent event;
  event.kind = kind;
  event.time_s = event_time_s;
  event.vehicle_a = truths[index].id;
  event.vehicle_b = other_id;
  event.relative_speed_mps = speed_mps;
  events.Add(event);
}

}  // namespace fireswarm::sim2d
