// The planner's contract: a search area and a fleet in, one search plan per
// drone out. Pure computation; the `fireswarm plan` command and the server call
// PlanSearch.
#pragma once

#include <string>
#include <vector>

#include "fireswarm/common/camera_model.hpp"
#include "fireswarm/common/local_frame.hpp"
#include "fireswarm/planner/geometry.hpp"

namespace fireswarm::planner {

/// The area to search, projected to one local frame (see area_io.hpp to read it
/// from GeoJSON). `area` is what must be covered; `no_fly` must never be entered.
struct SearchArea {
  common::LocalFrame frame{common::LatLon{}};
  MultiPolygon area;
  MultiPolygon no_fly;
};

/// The fleet and how it flies.
struct FleetSpec {
  std::vector<int> receiver_ids;        ///< one per drone, 1..254, distinct
  std::vector<Point> launch_points;     ///< local metres; one for all, or one per drone
  double altitude_m = 60.0;             ///< above ground
  double speed_mps = 10.0;              ///< cruise speed along lanes and in transit
  double endurance_s = 1'800.0;         ///< flight time per sortie, reserve excluded
  const common::CameraModel* camera = nullptr;
  double camera_pitch_deg = -90.0;      ///< mount pitch from the horizon, -90 = straight down
  double side_overlap = 0.10;           ///< fraction of the footprint shared by neighbouring lanes
  double turn_cost_s = 4.0;             ///< time lost at each lane turn (decelerate, turn, accelerate)
};

enum class PlannerKind { kLawnmower, kOmpl };

/// One waypoint in local metres and WGS84.
struct Waypoint {
  Point local;
  common::LatLon geodetic;
  bool is_return = false;  ///< a return-to-launch point between sorties
};

/// One drone's plan: its region, the path (launch -> coverage -> home, split into
/// sorties when it exceeds the endurance) and its estimates.
struct DronePlan {
  int receiver_id = 0;
  MultiPolygon region;
  std::vector<Waypoint> waypoints;
  int sorties = 1;
  double length_m = 0.0;
  double time_s = 0.0;
};

/// The fleet's plan and its figures.
struct Plan {
  std::vector<DronePlan> drones;
  double sweep_width_m = 0.0;     ///< lane spacing: footprint width times (1 - side overlap)
  double coverage = 0.0;          ///< fraction of the area inside the union of footprints, 0..1
  double makespan_s = 0.0;        ///< the slowest drone's time
  double lower_bound_s = 0.0;     ///< area / (N * sweep width * speed) + unavoidable transit
  double nofly_violation_m = 0.0; ///< path metres inside no-fly zones (0 when correct)
  double planning_seconds = 0.0;  ///< wall time PlanSearch took
};

/// Plans the search. Deterministic for a given `seed`. Throws std::invalid_argument
/// with a message naming the field when the fleet is unusable (no drones, speed or
/// altitude <= 0, no camera, a launch point inside a no-fly zone), and
/// std::runtime_error when the plan cannot fit the endurance even with sorties.
Plan PlanSearch(const SearchArea& area, const FleetSpec& fleet,
                PlannerKind kind = PlannerKind::kLawnmower, unsigned seed = 1);

}  // namespace fireswarm::planner
