// The rate-of-spread model of one cell: a head-fire rate from the fuel and the
// wind, and an elliptical spread shape around it (private to sim2d; tested in
// tests/sim2d/fire_spread_test.cpp).
#pragma once

#include "fireswarm/sim2d/fire_config.hpp"

namespace fireswarm::sim2d {

/// Head-fire rate of spread, m/min, for `fuel` in a midflame wind of `wind_mps`:
/// no_wind + (ref - no_wind) * (wind / 5 mi/h)^exponent (a Rothermel-like power law
/// through the fuel model's 5 mi/h figure).
double HeadRosMpm(const FuelBehaviour& fuel, double wind_mps, double wind_exponent);

/// Length-to-breadth ratio of a wind-driven fire ellipse (Anderson 1983), >= 1.
double LengthToBreadth(double wind_mps);

/// Rate of spread, m/min, in a direction at angle theta from the head direction,
/// given cos(theta): the fire sits at the rear focus of an ellipse of ratio `lb`,
/// so ros = head * (1 - e) / (1 - e cos theta), e the ellipse's eccentricity.
double RosInDirectionMpm(double head_ros_mpm, double lb, double cos_from_head);

}  // namespace fireswarm::sim2d
