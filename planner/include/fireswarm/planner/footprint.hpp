// The camera's footprint on the ground and the sweep width it allows.
#pragma once

#include "fireswarm/common/camera_model.hpp"

namespace fireswarm::planner {

struct FleetSpec;

/// Across-track width in metres of the ground the camera sees, flying level at
/// `altitude_m` above flat ground with the camera mounted at `pitch_deg` from the
/// horizon (-90 = straight down, the image's horizontal axis across the track).
///
/// Nadir: 2 h tan(hfov / 2). Tilted: the pinhole image row that meets the ground
/// nearest the drone (the near edge) is the narrowest across the track, so its
/// width, 2 h tan(hfov / 2) / (sin d + tan(vfov / 2) cos d) with d = -pitch the
/// depression of the optical axis, is the width seen along the whole image; using
/// it keeps neighbouring lanes overlapping even at the near edge (conservative).
/// Throws std::invalid_argument naming `altitude_m` (not > 0) or
/// `camera_pitch_deg` (not in [-90, 0)).
double FootprintWidthM(const common::CameraModel& camera, double altitude_m, double pitch_deg);

/// Lane spacing in metres: FootprintWidthM * (1 - side_overlap). Throws
/// std::invalid_argument naming the field when the fleet's camera is missing, the
/// altitude or pitch is out of range, or side_overlap is not in [0, 1).
double SweepWidthM(const FleetSpec& fleet);

}  // namespace fireswarm::planner
