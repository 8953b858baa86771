#include <algorithm>
#include <cmath>
#include <limits>

#include "box2d_units.hpp"
#include "collision_tracker.hpp"

namespace fireswarm::sim2d {
namespace {

struct Tag {
  std::size_t index = 0;
  bool near_miss_sensor = false;
};

Tag ReadTag(b2Fixture& fixture) {
  const std::uintptr_t tag = fixture.GetUserData().pointer;
  return Tag{static_cast<std::size_t>(tag >> 1U), (tag & 1U) != 0U};
}

// Both vehicles' sensor (or both solid) fixtures, ordered by vehicle index.
bool ReadPair(b2Contact& contact, Tag& a, Tag& b) {
  a = ReadTag(*contact.GetFixtureA());
  b = ReadTag(*contact.GetFixtureB());
  if (a.near_miss_sensor != b.near_miss_sensor || a.index == b.index) return false;
  if (b.index < a.index) std::swap(a, b);
  return true;
}

double Separation3dM(const VehicleTruth& a, const VehicleTruth& b) {
  const Vec2 horizontal = a.position_m - b.position_m;
  const double vertical = a.altitude_m - b.altitude_m;
  return std::sqrt(horizontal.squaredNorm() + vertical * vertical);
}

bool Counts(const VehicleTruth& a, const VehicleTruth& b) {
  if (a.phase == FlightPhase::kLost || b.phase == FlightPhase::kLost) return false;
  return a.phase == FlightPhase::kFlying || b.phase == FlightPhase::kFlying;
}

}  // namespace

std::uintptr_t FixtureTag(std::size_t vehicle_index, bool near_miss_sensor) {
  return (static_cast<std::uintptr_t>(vehicle_index) << 1U) | (near_miss_sensor ? 1U : 0U);
}

CollisionTracker::CollisionTracker(const CollisionParams& params,
                                   const std::vector<VehicleTruth>& truths,
                                   const std::vector<double>& half_heights_m, EventLog& events)
    : params_(params),
      truths_(truths),
      half_heights_m_(half_heights_m),
      events_(events),
      min_separation_m_(std::numeric_limits<double>::infinity()) {
  // Room for the usual numbers of close pairs; growing is allowed, just rare.
  constexpr std::size_t kExpectedPairs = 256;
  near_pairs_.reserve(kExpectedPairs);
  colliding_.reserve(kExpectedPairs);
  crashes_.reserve(kExpectedPairs);
}

bool CollisionTracker::BandsOverlap(std::size_t a, std::size_t b) const {
  const double gap_m = std::abs(truths_[a].altitude_m - truths_[b].altitude_m);
  return gap_m < half_heights_m_[a] + half_heights_m_[b];
}

double CollisionTracker::RelativeSpeed(const b2Body& body_a, const b2Body& body_b, std::size_t a,
                                       std::size_t b) const {
  const Vec2 dv = MetresOf(body_a.GetLinearVelocity() - body_b.GetLinearVelocity());
  const double dz = truths_[a].climb_rate_mps - truths_[b].climb_rate_mps;
  const double dx = dv.x();
  const double dy = dv.y();
  return std::sqrt(dx * dx + dy * dy + dz * dz);
}

void CollisionTracker::BeginContact(b2Contact* contact) {
  Tag a;
  Tag b;
  if (!ReadPair(*contact, a, b) || !a.near_miss_sensor) return;
  near_pairs_.push_back(
      NearPair{static_cast<std::uint32_t>(a.index), static_cast<std::uint32_t>(b.index)});
}

void CollisionTracker::EndContact(b2Contact* contact) {
  Tag a;
  Tag b;
  if (!ReadPair(*contact, a, b)) return;
  if (a.near_miss_sensor) {
    const auto it = std::find_if(near_pairs_.begin(), near_pairs_.end(), [&](const NearPair& p) {
      return p.a == a.index && p.b == b.index;
    });
    if (it == near_pairs_.end()) return;
    if (it->in_encounter) CloseEncounter(*it);
    *it = near_pairs_.back();
    near_pairs_.pop_back();
    return;
  }
  std::erase_if(colliding_, [&](const Pair& p) { return p.a == a.index && p.b == b.index; });
}

void CollisionTracker::PreSolve(b2Contact* contact, const b2Manifold* /*old_manifold*/) {
  Tag a;
  Tag b;
  if (!ReadPair(*contact, a, b) || a.near_miss_sensor) return;
  const auto matches = [&](const Pair& p) { return p.a == a.index && p.b == b.index; };
  if (!BandsOverlap(a.index, b.index)) {
    contact->SetEnabled(false);
    std::erase_if(colliding_, matches);
    return;
  }
  if (std::any_of(colliding_.begin(), colliding_.end(), matches)) return;
  colliding_.push_back(
      Pair{static_cast<std::uint32_t>(a.index), static_cast<std::uint32_t>(b.index)});
  const b2Body& body_a = *contact->GetFixtureA()->GetBody();
  const b2Body& body_b = *contact->GetFixtureB()->GetBody();
  // The fixtures' order in the contact is Box2D's; the speed does not care.
  const double speed_mps = RelativeSpeed(body_a, body_b, a.index, b.index);
  WorldEvent event;
  event.kind = EventKind::kCollision;
  event.time_s = time_s_;
  event.vehicle_a = truths_[a.index].id;
  event.vehicle_b = truths_[b.index].id;
  if (event.vehicle_b < event.vehicle_a) std::swap(event.vehicle_a, event.vehicle_b);
  event.relative_speed_mps = speed_mps;
  event.min_separation_m = Separation3dM(truths_[a.index], truths_[b.index]);
  events_.Add(event);
  if (speed_mps > params_.crash_relative_speed_mps) {
    crashes_.push_back(CollisionCrash{a.index, b.index, speed_mps});
  }
}

void CollisionTracker::CloseEncounter(NearPair& pair) {
  pair.in_encounter = false;
  events_.at(pair.event_index).open = false;
}

void CollisionTracker::UpdateNearMisses() {
  const double separation_m = params_.near_miss_separation_m;
  for (NearPair& pair : near_pairs_) {
    const VehicleTruth& a = truths_[pair.a];
    const VehicleTruth& b = truths_[pair.b];
    if (!Counts(a, b)) {
      if (pair.in_encounter) CloseEncounter(pair);
      continue;
    }
    const double distance_m = Separation3dM(a, b);
    min_separation_m_ = std::min(min_separation_m_, distance_m);
    if (pair.in_encounter) {
      WorldEvent& event = events_.at(pair.event_index);
      event.min_separation_m = std::min(event.min_separation_m, distance_m);
      if (distance_m > kNearMissExitFactor * separation_m) CloseEncounter(pair);
      continue;
    }
    if (distance_m >= separation_m) continue;
    WorldEvent event;
    event.kind = EventKind::kNearMiss;
    event.time_s = time_s_;
    event.vehicle_a = std::min(a.id, b.id);
    event.vehicle_b = std::max(a.id, b.id);
    event.min_separation_m = distance_m;
    event.open = true;
    pair.in_encounter = true;
    pair.event_index = events_.Add(event);
  }
}

}  // namespace fireswarm::sim2d
