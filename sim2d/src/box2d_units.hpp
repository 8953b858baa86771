// The length unit Box2D works in (private to sim2d): ten metres, not one.
//
// Box2D 2.4's broadphase keeps each fixture in a box b2_aabbExtension (0.1 unit,
// compiled into Debian's library) larger than the fixture, stretched four steps'
// motion ahead, and takes it out of its tree and puts it back whenever the
// fixture leaves that box. In metres a drone at 10 m/s left its box every fifth
// 10 ms step, and that was most of Box2D's time with hundreds of drones. In
// units of 10 m the box is 1 m larger and the drone leaves it about every
// fourteenth step. Masses and times stay kg and s; a force in N is 1/10 of it in
// Box2D's kg unit/s^2. Box2D's other tolerances scale too: its contact slop is
// 5 cm (against a drone's radius of tens of centimetres) and its restitution
// threshold is set on each fixture in m/s. Float precision is the same: a position
// 10 km out is 1,000 units, to 0.6 mm.
#pragma once

#include <box2d/box2d.h>

#include "fireswarm/sim2d/vehicle_state.hpp"

namespace fireswarm::sim2d {

inline constexpr double kMetresPerBox2dUnit = 10.0;

/// Metres (or m/s) to Box2D units (or units/s).
inline float Box2dLength(double metres) {
  return static_cast<float>(metres / kMetresPerBox2dUnit);
}
inline b2Vec2 Box2dVector(const Vec2& metres) {
  return b2Vec2(Box2dLength(metres.x()), Box2dLength(metres.y()));
}
/// A force in N to Box2D's kg unit/s^2.
inline b2Vec2 Box2dForce(const Vec2& force_n) {
  return Box2dVector(force_n);
}
/// A Box2D position or velocity in metres (m/s).
inline Vec2 MetresOf(const b2Vec2& units) {
  return Vec2(static_cast<double>(units.x) * kMetresPerBox2dUnit,
              static_cast<double>(units.y) * kMetresPerBox2dUnit);
}

}  // namespace fireswarm::sim2d
