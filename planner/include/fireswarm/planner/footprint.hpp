// The sweep width the camera footprint allows.
#pragma once

#include "fireswarm/common/camera_model.hpp"

namespace fireswarm::planner {

struct FleetSpec;

/// The camera footprint's across-track width (common/camera_model.hpp).
using common::FootprintWidthM;

/// Lane spacing in metres: FootprintWidthM * (1 - side_overlap). Throws
/// std::invalid_argument naming the field when the fleet's camera is missing, the
/// altitude or pitch is out of range, or side_overlap is not in [0, 1).
double SweepWidthM(const FleetSpec& fleet);

}  // namespace fireswarm::planner
