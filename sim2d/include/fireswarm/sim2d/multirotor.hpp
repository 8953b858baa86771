// Parameters of the simulated multirotor and its battery. Defaults describe the
// seed's 1.2 kg quadcopter (seed 7.5.1: aluminium frame, four SunnySky X2212
// KV980 motors of ~400 W peak, so a thrust-to-weight ratio of about 2.5).
#pragma once

namespace fireswarm::sim2d {

/// The battery: energy drawn by the motors (growing with thrust, momentum theory)
/// and the avionics. At zero charge the motors stop.
struct BatteryParams {
  double capacity_wh = 40.0;          ///< usable energy (4S 2.7 Ah pack)
  double reference_power_w = 160.0;   ///< motor electrical power at reference_thrust_n
  double reference_thrust_n = 11.77;  ///< total thrust of that power (1.2 kg hovering)
  double avionics_power_w = 4.0;      ///< autopilot, radio, camera; drawn always
  double full_voltage_v = 16.8;       ///< open-circuit voltage when full
  double empty_voltage_v = 13.2;      ///< open-circuit voltage when empty
  double initial_fraction = 1.0;      ///< charge at launch, (0, 1]
};

/// The plant: mass, geometry, limits and time constants of one multirotor.
///
/// Model (see multirotor_dynamics.hpp): roll and pitch follow the command through
/// a first-order lag with a rate limit, the yaw rate likewise; thrust follows an
/// inner climb-rate loop through a motor lag; the tilted thrust vector, linear and
/// quadratic drag and the wind push the vehicle in the horizontal plane (Box2D);
/// altitude and climb rate are integrated beside it.
struct MultirotorParams {
  double mass_kg = 1.2;
  double roll_pitch_inertia_kgm2 = 0.015;  ///< sets the attitude loop's stiffness
  double radius_m = 0.25;                  ///< collision disc (rotor tips)
  double height_m = 0.15;                  ///< thickness of the altitude band
  double max_thrust_n = 30.0;
  double thrust_time_constant_s = 0.05;  ///< motor spool-up lag
  double climb_gain_per_s = 3.0;         ///< climb loop: accel = gain * rate error
  double max_climb_rate_mps = 5.0;       ///< commands are clamped to this
  double max_descent_rate_mps = 3.0;     ///< commands are clamped to this
  double max_tilt_rad = 0.61;            ///< 35 deg; roll/pitch commands clamped
  double attitude_time_constant_s = 0.15;
  double max_attitude_rate_radps = 3.5;  ///< 200 deg/s
  double yaw_time_constant_s = 0.2;
  double max_yaw_rate_radps = 2.0;
  double linear_drag_n_per_mps = 0.1;       ///< on air-relative velocity
  double quadratic_drag_n_per_mps2 = 0.04;  ///< on air-relative velocity
  double crash_vertical_speed_mps = 2.5;    ///< touching down faster than this crashes
  double crash_horizontal_speed_mps = 3.0;  ///< touching down faster than this crashes
  BatteryParams battery;
};

}  // namespace fireswarm::sim2d
