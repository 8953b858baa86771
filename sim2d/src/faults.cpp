#include "fault_state.hpp"

namespace fireswarm::sim2d {

FaultState ActiveFaults(std::span<const FaultSpec> faults, double time_s) {
  FaultState state;
  for (const FaultSpec& fault : faults) {
    if (time_s < fault.start_s) continue;
    if (fault.kind == FaultKind::kTotalLoss) {
      state.lost = true;
      continue;
    }
    if (time_s >= fault.end_s) continue;
    SensorFaultState& sensor = state.sensors[static_cast<std::size_t>(fault.sensor)];
    switch (fault.kind) {
      case FaultKind::kStreamCut:
        sensor.cut = true;
        break;
      case FaultKind::kFrozen:
        sensor.frozen = true;
        break;
      case FaultKind::kBias:
        sensor.bias += fault.bias;
        break;
      case FaultKind::kExtraNoise:
        sensor.noise_factor *= fault.noise_factor;
        break;
      case FaultKind::kBallast:
        state.ballast_offset_m += fault.ballast_offset_m;
        break;
      case FaultKind::kTotalLoss:
        break;
    }
  }
  return state;
}

}  // namespace fireswarm::sim2d
