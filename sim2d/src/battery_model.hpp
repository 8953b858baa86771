// The battery: electrical power from thrust (momentum theory, P ~ T^1.5), the
// energy left, and the pack's open-circuit voltage. Pure functions.
#pragma once

#include "fireswarm/sim2d/multirotor.hpp"

namespace fireswarm::sim2d {

/// Electrical power (W) drawn at `thrust_n`: the avionics plus the motors, whose
/// power scales as (thrust / reference_thrust_n)^1.5 from reference_power_w.
double BatteryPowerW(const BatteryParams& params, double thrust_n);

/// Energy (J) of a full pack.
double BatteryCapacityJ(const BatteryParams& params);

/// The energy left after drawing `power_w` for dt_s, never below 0.
double DrainBatteryJ(double energy_j, double power_w, double dt_s);

/// Open-circuit voltage (V) at a charge fraction in [0, 1], linear between empty and full.
double BatteryVoltageV(const BatteryParams& params, double fraction);

}  // namespace fireswarm::sim2d
