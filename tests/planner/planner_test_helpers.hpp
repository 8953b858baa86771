// Small shapes and fleets shared by the planner tests (local metres).
#pragma once

#include <boost/geometry/algorithms/correct.hpp>

#include "fireswarm/common/camera_model.hpp"
#include "fireswarm/planner/geometry.hpp"
#include "fireswarm/planner/plan.hpp"

namespace fireswarm::planner::testing {

/// The axis-aligned rectangle [x0, x1] x [y0, y1], oriented as Boost expects.
inline Polygon Rect(double x0, double y0, double x1, double y1) {
  Polygon p{{{x0, y0}, {x0, y1}, {x1, y1}, {x1, y0}, {x0, y0}}};
  boost::geometry::correct(p);
  return p;
}

/// `drones` drones with receiver IDs 1..N, one launch point, the seed camera at
/// the default altitude, and endurance so long that no plan is split into sorties.
inline FleetSpec Fleet(int drones, Point launch) {
  FleetSpec fleet;
  for (int i = 1; i <= drones; ++i) fleet.receiver_ids.push_back(i);
  fleet.launch_points = {launch};
  fleet.camera = &common::CameraModelByName("seed");
  fleet.endurance_s = 1e6;
  return fleet;
}

}  // namespace fireswarm::planner::testing
