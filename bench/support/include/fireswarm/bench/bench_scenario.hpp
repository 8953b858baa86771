// The scenario `fireswarm sim-bench` flies: N vehicles with thermal cameras on
// simple lawnmower lanes over a square burning area. Pure construction; the
// command times the stepping.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "fireswarm/sim2d/lane_pilot.hpp"
#include "fireswarm/sim2d/simulation.hpp"

namespace fireswarm::bench {

struct BenchScenarioSpec {
  int drones = 100;
  std::string camera = "seed";  ///< a camera model name, or "none"
  double area_km2 = 4.0;        ///< a square of this area, centred on the origin
  int fires = 5;                ///< random ignitions at t = 0
  int distractors = 20;         ///< random hot rocks
  double altitude_m = 60.0;     ///< lowest lane altitude; vehicles are staggered above it
  double speed_mps = 10.0;
  std::uint64_t seed = 1;

  /// Throws std::invalid_argument naming the field and the value it got.
  void Validate() const;
};

struct BenchScenario {
  sim2d::SimulationConfig config;
  std::vector<sim2d::LanePilot> pilots;  ///< one per vehicle, in the world's vehicle order
};

/// Each vehicle gets an equal north-south strip of the square and sweeps it in
/// lanes one camera footprint apart; launch points are on the south edge, one
/// per strip, and lane altitudes are staggered in four 5 m layers.
BenchScenario MakeBenchScenario(const BenchScenarioSpec& spec);

}  // namespace fireswarm::bench
