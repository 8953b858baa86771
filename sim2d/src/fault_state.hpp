// Which scheduled faults are active at a given time, folded into one state the
// plant and the sensors read. Pure.
#pragma once

#include <array>
#include <span>

#include "fireswarm/sim2d/faults.hpp"

namespace fireswarm::sim2d {

inline constexpr std::size_t kSensorKindCount = 4;

/// The faults acting on one sensor now.
struct SensorFaultState {
  bool cut = false;
  bool frozen = false;
  Eigen::Vector3d bias = Eigen::Vector3d::Zero();
  double noise_factor = 1.0;
};

/// The faults acting on one vehicle now. Overlapping biases and ballasts add;
/// noise factors multiply.
struct FaultState {
  std::array<SensorFaultState, kSensorKindCount> sensors{};
  Vec2 ballast_offset_m = Vec2::Zero();
  bool lost = false;

  const SensorFaultState& sensor(SensorKind kind) const {
    return sensors[static_cast<std::size_t>(kind)];
  }
};

/// Folds the faults active at `time_s` (start_s <= t < end_s; a total loss from
/// start_s on) into one state.
FaultState ActiveFaults(std::span<const FaultSpec> faults, double time_s);

}  // namespace fireswarm::sim2d
