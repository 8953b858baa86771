#include "fireswarm/sim2d/world.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "battery_model.hpp"
#include "box2d_units.hpp"
#include "fireswarm/common/angles.hpp"
#include "world_hash.hpp"
#include "world_impl.hpp"

namespace fireswarm::sim2d {
namespace {

WorldConfig WithoutVehicles(const WorldConfig& config) {
  config.Validate();
  WorldConfig copy = config;
  copy.vehicles.clear();
  return copy;
}

// Where the air moves to (local ENU) for a wind blowing from `from_deg`.
Vec2 SteadyWind(const WindParams& wind) {
  const double from_rad = common::DegToRad(wind.from_deg);
  return -wind.speed_mps * Vec2(std::sin(from_rad), std::cos(from_rad));
}

std::out_of_range UnknownVehicle(int id) {
  return std::out_of_range("no vehicle with id " + std::to_string(id));
}

// Box2D's restitution threshold, m/s: its default (1 unit/s) when a unit was a metre.
constexpr double kRestitutionThresholdMps = 1.0;

// A dynamic disc body with two fixtures: the solid disc (mass_kg spread over it)
// and the near-miss sensor disc (see collision_tracker.hpp).
b2Body* CreateVehicleBody(b2World& physics, const VehicleConfig& vehicle,
                          const CollisionParams& collision, std::size_t index) {
  const MultirotorParams& params = vehicle.multirotor;
  b2BodyDef body_def;
  body_def.type = b2_dynamicBody;
  body_def.position = Box2dVector(vehicle.launch_position_m);
  body_def.fixedRotation = true;  // heading is the plant's, not Box2D's
  body_def.allowSleep = false;
  body_def.userData.pointer = index;
  b2Body* body = physics.CreateBody(&body_def);

  b2CircleShape solid;
  solid.m_radius = Box2dLength(params.radius_m);
  b2FixtureDef solid_def;
  solid_def.shape = &solid;
  // Density per square Box2D unit, so that the disc weighs mass_kg.
  const double disc_area_units2 = std::numbers::pi * std::pow(Box2dLength(params.radius_m), 2);
  solid_def.density = static_cast<float>(params.mass_kg / disc_area_units2);
  solid_def.friction = static_cast<float>(collision.friction);
  solid_def.restitution = static_cast<float>(collision.restitution);
  // Box2D's default, 1 m/s, in its units (below it contacts do not bounce).
  solid_def.restitutionThreshold = Box2dLength(kRestitutionThresholdMps);
  solid_def.filter.categoryBits = kSolidCategory;
  solid_def.filter.maskBits = kSolidCategory;
  solid_def.userData.pointer = FixtureTag(index, false);
  body->CreateFixture(&solid_def);

  b2CircleShape zone;
  zone.m_radius = Box2dLength(kNearMissExitFactor * collision.near_miss_separation_m / 2.0);
  b2FixtureDef zone_def;
  zone_def.shape = &zone;
  zone_def.isSensor = true;
  zone_def.density = 0.0F;
  zone_def.filter.categoryBits = kNearMissCategory;
  zone_def.filter.maskBits = kNearMissCategory;
  zone_def.userData.pointer = FixtureTag(index, true);
  body->CreateFixture(&zone_def);
  return body;
}

}  // namespace

VehicleRuntime::VehicleRuntime(const VehicleConfig& vehicle, b2Body* vehicle_body, double substep_s,
                               std::uint64_t seed)
    : config(vehicle),
      coefficients(MakeCoefficients(vehicle.multirotor, substep_s)),
      body(vehicle_body),
      energy_j(BatteryCapacityJ(vehicle.multirotor.battery) *
               vehicle.multirotor.battery.initial_fraction),
      capacity_j(BatteryCapacityJ(vehicle.multirotor.battery)),
      sensors(vehicle.sensors, vehicle.id, seed) {}

World::Impl::Impl(const WorldConfig& world_config)
    : config(WithoutVehicles(world_config)),
      frame(config.origin),
      substep_s(config.step_s / config.substeps),
      tracker(config.collision, truths, half_heights_m, events),
      physics(b2Vec2(0.0F, 0.0F)),
      wind_noise(MakeRng(config.seed, "wind")),
      steady_wind_mps(SteadyWind(config.wind)),
      wind_mps(steady_wind_mps) {
  physics.SetAllowSleeping(false);
  // Vehicles are slow discs against each other; no time-of-impact sub-stepping.
  physics.SetContinuousPhysics(false);
  physics.SetContactListener(&tracker);
  const WindParams& wind = config.wind;
  if (wind.gust_std_mps > 0.0) {
    gust_east =
        GaussMarkov(wind.gust_std_mps, wind.gust_time_constant_s, config.step_s, wind_noise);
    gust_north =
        GaussMarkov(wind.gust_std_mps, wind.gust_time_constant_s, config.step_s, wind_noise);
  }
  for (const VehicleConfig& vehicle : world_config.vehicles) Add(vehicle);
}

void World::Impl::Add(const VehicleConfig& vehicle) {
  ValidateVehicle(vehicle, config.step_s);
  if (index_of.contains(vehicle.id)) {
    throw std::invalid_argument("vehicle " + std::to_string(vehicle.id) +
                                ": duplicate receiver id");
  }
  const std::size_t index = vehicles.size();
  const MultirotorParams& params = vehicle.multirotor;

  b2Body* body = CreateVehicleBody(physics, vehicle, config.collision, index);

  VehicleTruth truth;
  truth.id = vehicle.id;
  truth.position_m = vehicle.launch_position_m;
  truth.heading_rad = WrapTwoPi(vehicle.launch_heading_rad);
  truth.battery_fraction = params.battery.initial_fraction;

  vehicles.emplace_back(vehicle, body, substep_s, config.seed);
  truths.push_back(truth);
  half_heights_m.push_back(params.height_m / 2.0);
  samples.emplace_back();
  index_of.emplace(vehicle.id, index);
}

std::size_t World::Impl::IndexOf(int id) const {
  const auto it = index_of.find(id);
  if (it == index_of.end()) throw UnknownVehicle(id);
  return it->second;
}

std::uint64_t World::Impl::Hash() const {
  StateHasher hasher;
  hasher.Add(static_cast<std::uint64_t>(steps));
  hasher.Add(wind_mps);
  for (std::size_t i = 0; i < vehicles.size(); ++i) {
    const VehicleTruth& t = truths[i];
    hasher.Add(t.id);
    hasher.Add(t.position_m);
    hasher.Add(t.altitude_m);
    hasher.Add(t.velocity_mps);
    hasher.Add(t.climb_rate_mps);
    hasher.Add(t.roll_rad);
    hasher.Add(t.pitch_rad);
    hasher.Add(t.heading_rad);
    hasher.Add(t.roll_rate_radps);
    hasher.Add(t.pitch_rate_radps);
    hasher.Add(t.yaw_rate_radps);
    hasher.Add(t.battery_fraction);
    hasher.Add(static_cast<int>(t.phase));
    hasher.Add(vehicles[i].thrust_n);
    hasher.Add(vehicles[i].energy_j);
    hasher.Add(vehicles[i].swap_due_s);
    vehicles[i].sensors.HashInto(hasher);
  }
  hasher.Add(static_cast<double>(events.total()));
  for (const WorldEvent& e : events) {
    hasher.Add(static_cast<int>(e.kind));
    hasher.Add(e.time_s);
    hasher.Add(e.vehicle_a);
    hasher.Add(e.vehicle_b);
    hasher.Add(e.relative_speed_mps);
    hasher.Add(e.min_separation_m);
  }
  return hasher.value();
}

World::World(const WorldConfig& config) : impl_(std::make_unique<Impl>(config)) {}
World::~World() = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

void World::AddVehicle(const VehicleConfig& vehicle) {
  impl_->Add(vehicle);
}

void World::AddVehicle(int id, Vec2 launch_position_m) {
  VehicleConfig vehicle;
  vehicle.id = id;
  vehicle.launch_position_m = launch_position_m;
  impl_->Add(vehicle);
}

void World::ScheduleFault(int id, const FaultSpec& fault) {
  const std::size_t index = impl_->IndexOf(id);
  ValidateFault(id, fault);
  impl_->vehicles[index].config.faults.push_back(fault);
}

void World::SetCommand(int id, const ActuatorCommand& command) {
  impl_->vehicles[impl_->IndexOf(id)].command = command;
}

void World::SetCommandAt(std::size_t index, const ActuatorCommand& command) {
  impl_->vehicles.at(index).command = command;
}

void World::Step() {
  impl_->Step();
}

void World::RunFor(double duration_s) {
  const auto count = static_cast<std::int64_t>(std::llround(duration_s / impl_->config.step_s));
  for (std::int64_t i = 0; i < count; ++i) impl_->Step();
}

double World::time_s() const {
  return impl_->time_s();
}
double World::step_s() const {
  return impl_->config.step_s;
}
std::int64_t World::step_count() const {
  return impl_->steps;
}
std::size_t World::vehicle_count() const {
  return impl_->vehicles.size();
}
std::size_t World::IndexOf(int id) const {
  return impl_->IndexOf(id);
}
bool World::HasVehicle(int id) const {
  return impl_->index_of.contains(id);
}
const VehicleTruth& World::Truth(int id) const {
  return impl_->truths[impl_->IndexOf(id)];
}
std::span<const VehicleTruth> World::Truths() const {
  return impl_->truths;
}
const SensorSample& World::Sensors(int id) const {
  return impl_->samples[impl_->IndexOf(id)];
}
std::span<const SensorSample> World::AllSensors() const {
  return impl_->samples;
}
std::uint64_t EventLog::Add(const WorldEvent& event) {
  kept_.push_back(event);
  ++counts_[static_cast<std::size_t>(event.kind)];
  return total() - 1;
}

void EventLog::Trim() {
  while (kept_.size() > kKeptWorldEvents && !kept_.front().open) {
    kept_.pop_front();
    ++first_;
  }
}

const EventLog& World::events() const {
  return impl_->events;
}
double World::min_separation_m() const {
  return impl_->tracker.min_separation_m();
}
Vec2 World::wind_mps() const {
  return impl_->wind_mps;
}
const common::LocalFrame& World::frame() const {
  return impl_->frame;
}
std::uint64_t World::StateHash() const {
  return impl_->Hash();
}

}  // namespace fireswarm::sim2d

// Box2D 2.4.1 times every b2World::Step for its b2Profile (the step, collide,
// solve and TOI phases, and three phases of every island: each vehicle is an
// island of its own) with b2Timer, which on Linux calls gettimeofday twice per
// measurement: about fifty clock reads per World::Step with ten vehicles, a
// tenth of a whole mission's CPU time. fireswarm never reads the profile (and
// a wall clock has no place in a deterministic core), so these definitions
// replace the library's timer with the one Box2D itself compiles on platforms
// without a clock (b2_timer.cpp's last branch): no clock read, 0 ms.
//
// They take effect by ELF symbol interposition: libbox2d.so calls its timer
// through the PLT, and a definition in the executable comes first. They live
// in this file because it is the one that creates the b2World, so every
// program that steps one links them. Linked statically, Box2D would report a
// duplicate definition instead of silently keeping its own timer.
// tests/sim2d/world_test.cpp checks that they are the ones in use.
b2Timer::b2Timer() = default;
void b2Timer::Reset() {}
float b2Timer::GetMilliseconds() const {
  return 0.0F;
}
