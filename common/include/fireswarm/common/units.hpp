// Physical constants and unit factors, one way for the whole tree. Quantities
// carry their unit in their name (altitude_m, speed_mps, area_km2).
#pragma once

namespace fireswarm::common {

/// Standard gravity, m/s^2.
inline constexpr double kGravityMps2 = 9.80665;
/// Square metres in a square kilometre.
inline constexpr double kSquareMetresPerKm2 = 1e6;

}  // namespace fireswarm::common
