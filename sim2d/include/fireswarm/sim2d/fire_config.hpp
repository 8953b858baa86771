// Configuration of the fire simulation: the grid over the area, the fuel
// behaviour (rate of spread, burn time), the wind, and the temperatures the
// thermal cameras see (flame, embers, cooling). Plain data plus Validate().
#pragma once

#include <cstdint>

#include "fireswarm/sim2d/vehicle_state.hpp"

namespace fireswarm::sim2d {

/// What a grid cell can burn. kNone is water, rock, road: it never burns.
enum class Fuel : std::uint8_t {
  kForest,  ///< timber litter under canopy (the default everywhere)
  kOpen,    ///< grass and open land: burns fast and briefly
  kNone,    ///< water or bare ground: never ignites, fire does not cross it
};

/// How one fuel burns. Rates of spread are head-fire rates on flat ground.
struct FuelBehaviour {
  double no_wind_ros_mpm = 0.0;   ///< rate of spread with no wind, m/min
  double head_ros_ref_mpm = 0.0;  ///< head-fire rate of spread at the reference wind, m/min
  double burn_duration_s = 0.0;   ///< flaming time of one cell once ignited, s
};

/// 5 mi/h in m/s: the midflame wind at which the standard fuel-model rates are quoted.
inline constexpr double kReferenceWindMps = 2.2352;

/// The fire grid, fuels, wind and scene temperatures. Defaults are documented in
/// docs/thermal_camera.md: forest litter between Anderson fuel models 8 and 9
/// (1.5 m/min at a 5 mi/h midflame wind), grass like fuel model 1 (25 m/min).
struct FireConfig {
  Vec2 origin_m = Vec2::Zero();  ///< south-west corner of the area, local ENU
  double width_m = 1000.0;       ///< east-west extent
  double height_m = 1000.0;      ///< north-south extent
  double cell_size_m = 5.0;      ///< side of one square cell

  double wind_speed_mps = kReferenceWindMps;  ///< midflame wind speed (not the 10 m wind)
  double wind_from_deg = 270.0;               ///< where the wind blows from, clockwise from north
  /// Exponent b of the wind term: ros = no_wind + (ref - no_wind) * (U / U_ref)^b.
  double wind_exponent = 1.5;
  /// Each neighbour's travel time is scaled by a uniform factor in [1 - j, 1 + j].
  double jitter_fraction = 0.1;

  FuelBehaviour forest{0.3, 1.5, 600.0};
  FuelBehaviour open{3.0, 25.0, 60.0};

  double ambient_c = 25.0;          ///< unburned ground, water, burned-out cold ground
  double flame_c = 700.0;           ///< a burning cell as seen from above through canopy
  double ember_c = 300.0;           ///< a cell just burned out; cools from here
  double cooling_tau_s = 600.0;     ///< exponential cooling time constant toward ambient
  double cooled_threshold_k = 0.5;  ///< below this excess over ambient a cell counts as cold

  /// Throws std::invalid_argument naming the first bad field and its value.
  void Validate() const;

  /// The behaviour of `fuel`; kNone has zero rates (never ignites).
  const FuelBehaviour& Behaviour(Fuel fuel) const;
};

/// A fire start: a place and a time. Used for configuration and as truth for scoring.
struct Ignition {
  Vec2 position_m = Vec2::Zero();  ///< local ENU
  double time_s = 0.0;             ///< simulated time from the scenario start
};

}  // namespace fireswarm::sim2d
