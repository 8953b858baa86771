#include "fireswarm/hil/sim_bridge.hpp"

#include <array>
#include <stdexcept>
#include <string>

#include "fireswarm/common/time.hpp"

namespace fireswarm::hil {

agents::SensorInputs ToVehicleInputs(const sim2d::SensorSample& sample) {
  agents::SensorInputs inputs;
  if (sample.gps) {
    agents::GpsInput gps;
    gps.lat_deg = sample.gps->position.lat_deg;
    gps.lon_deg = sample.gps->position.lon_deg;
    gps.altitude_m = sample.gps->altitude_m;
    gps.velocity_east_mps = sample.gps->velocity_mps.x();
    gps.velocity_north_mps = sample.gps->velocity_mps.y();
    inputs.gps = gps;
  }
  if (sample.baro) inputs.baro = agents::BaroInput{sample.baro->altitude_m};
  if (sample.attitude) {
    agents::AttitudeInput attitude;
    attitude.roll_rad = sample.attitude->roll_rad;
    attitude.pitch_rad = sample.attitude->pitch_rad;
    attitude.heading_rad = sample.attitude->heading_rad;
    attitude.roll_rate_radps = sample.attitude->roll_rate_radps;
    attitude.pitch_rate_radps = sample.attitude->pitch_rate_radps;
    attitude.yaw_rate_radps = sample.attitude->yaw_rate_radps;
    inputs.attitude = attitude;
  }
  if (sample.battery) {
    inputs.battery = agents::BatteryInput{sample.battery->voltage_v, sample.battery->fraction};
  }
  return inputs;
}

agents::CameraFrame ToCameraFrame(const sim2d::ThermalImage& image) {
  agents::CameraFrame frame;
  frame.width_px = image.width_px;
  frame.height_px = image.height_px;
  frame.pixels = image.pixels;
  frame.range_min_c = image.range_min_c;
  frame.range_max_c = image.range_max_c;
  return frame;
}

sim2d::ActuatorCommand ToActuatorCommand(const agents::ActuatorOutputs& outputs) {
  sim2d::ActuatorCommand command;
  command.roll_rad = outputs.roll_rad;
  command.pitch_rad = outputs.pitch_rad;
  command.yaw_rate_radps = outputs.yaw_rate_radps;
  command.climb_rate_mps = outputs.climb_rate_mps;
  command.armed = outputs.armed;
  return command;
}

void LockstepFleet::Add(agents::Vehicle& vehicle) {
  if (!simulation_.world().HasVehicle(vehicle.id())) {
    throw std::invalid_argument("lockstep fleet: the world has no vehicle " +
                                std::to_string(vehicle.id()));
  }
  vehicles_.push_back(&vehicle);
}

void LockstepFleet::Remove(int id) {
  std::erase_if(vehicles_, [id](const agents::Vehicle* v) { return v->id() == id; });
}

void LockstepFleet::Step() {
  simulation_.Step();
  const common::Nanos time = now();
  // This step's frames by vehicle ID (receiver IDs are 1..254).
  std::array<const sim2d::ThermalImage*, 256> images{};
  for (const sim2d::CameraFrame& taken : simulation_.new_frames()) {
    if (taken.vehicle_id >= 0 && taken.vehicle_id < static_cast<int>(images.size())) {
      images[static_cast<std::size_t>(taken.vehicle_id)] = taken.image;
    }
  }
  for (agents::Vehicle* vehicle : vehicles_) {
    const int id = vehicle->id();
    agents::SensorInputs inputs = ToVehicleInputs(simulation_.world().Sensors(id));
    agents::CameraFrame frame;
    if (const sim2d::ThermalImage* image = images[static_cast<std::size_t>(id)]) {
      frame = ToCameraFrame(*image);
      inputs.frame = &frame;
    }
    simulation_.world().SetCommand(id, ToActuatorCommand(vehicle->Step(time, inputs)));
  }
}

void LockstepFleet::RunUntil(double time_s) {
  while (simulation_.time_s() < time_s) Step();
}

}  // namespace fireswarm::hil
