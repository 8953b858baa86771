#include "fireswarm/planner/footprint.hpp"

#include <stdexcept>
#include <string>

#include "fireswarm/planner/plan.hpp"

namespace fireswarm::planner {

double SweepWidthM(const FleetSpec& fleet) {
  if (fleet.camera == nullptr) throw std::invalid_argument("camera: no camera model given");
  if (!(fleet.side_overlap >= 0.0 && fleet.side_overlap < 1.0)) {
    throw std::invalid_argument("side_overlap must be in [0, 1), got " +
                                std::to_string(fleet.side_overlap));
  }
  return FootprintWidthM(*fleet.camera, fleet.altitude_m, fleet.camera_pitch_deg) *
         (1.0 - fleet.side_overlap);
}

}  // namespace fireswarm::planner
