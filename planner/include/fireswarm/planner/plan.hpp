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

/// The documented ranges of FleetSpec's numbers (docs/limits.md): PlanSearch
/// refuses values outside them, and the scenario keys and command-line flags that
/// set them check the same ranges up front.
inline constexpr double kMaxAltitudeM = 1'000.0;     ///< altitude_m in (0, 1000]
inline constexpr double kMaxSpeedMps = 100.0;        ///< speed_mps in (0, 100]
inline constexpr double kMaxEnduranceS = 86'400.0;   ///< endurance_s in (0, one day]
inline constexpr double kMaxSwapS = 3'600.0;         ///< swap_s in [0, 3600]
inline constexpr double kMaxVerticalMps = 50.0;      ///< climb_mps, descent_mps in (0, 50]
inline constexpr double kMaxTurnCostS = 600.0;       ///< turn_cost_s in [0, 600]
/// At most this many lanes across the area in any sweep direction, estimated as
/// the diagonal of the area's bounding box over the lane spacing before any lane
/// is generated: a tiny spacing (side_overlap near 1) would otherwise take
/// unbounded memory and time (planning grows faster than the square of the lanes:
/// scenarios/areas/convex.geojson, 4 drones, took 4.9 s and 64 MB with 1000
/// lanes, 29 s and 200 MB with 2000; 9300 lanes passed 4 GB). The largest area
/// (kMaxSearchAreaKm2, 141 km across) at the default 60 m and 10 % overlap needs
/// about 1700.
inline constexpr double kMaxPlanLanes = 2'000.0;

/// The fleet and how it flies.
struct FleetSpec {
  std::vector<int> receiver_ids;  ///< one per drone, 1..254, distinct
  /// Launch sites, local metres, at least one. The planner spreads the drones over
  /// them (DronePlan::launch says where each flies from) unless `site_drones` fixes
  /// how many each site has.
  std::vector<Point> launch_points;
  /// Empty, or one count per launch site (>= 0, summing to the number of drones).
  std::vector<int> site_drones;
  double altitude_m = 60.0;      ///< above ground
  double speed_mps = 10.0;       ///< cruise speed along lanes and in transit
  double endurance_s = 1'800.0;  ///< flight time per sortie, reserve excluded
  /// Take-off climb to altitude_m and landing descent rates, m/s: every sortie
  /// spends altitude_m / climb_mps + altitude_m / descent_mps going up and down
  /// over its site (APOne: 3 m/s, safety.land_descent_mps 1 m/s), in its time and
  /// out of its endurance.
  double climb_mps = 3.0;
  double descent_mps = 1.0;
  /// On the ground between two sorties (battery swap, checks); the landing and
  /// the take-off are climb_mps' and descent_mps'.
  double swap_s = 300.0;
  const common::CameraModel* camera = nullptr;
  double camera_pitch_deg = -90.0;  ///< mount pitch from the horizon, -90 = straight down
  double side_overlap = 0.10;       ///< fraction of the footprint shared by neighbouring lanes
  double turn_cost_s = 4.0;         ///< time lost at each lane turn (decelerate, turn, accelerate)
};

enum class PlannerKind { kLawnmower, kOmpl };

/// One waypoint in local metres and WGS84.
struct Waypoint {
  Point local;
  common::LatLon geodetic;
  bool is_return = false;    ///< the landing at the launch site that ends a sortie (not the last)
  bool starts_lane = false;  ///< the leg from here to the next waypoint is a search lane
};

/// One drone's plan: its region, the path (launch -> coverage -> home, split into
/// sorties when it exceeds the endurance) and its estimates.
struct DronePlan {
  int receiver_id = 0;
  std::size_t site = 0;  ///< index into FleetSpec::launch_points
  Point launch;          ///< that site: every sortie starts and ends here
  MultiPolygon region;
  /// Each sortie's part of `region`: one polygon where the sortie's work is one
  /// connected piece of ground.
  std::vector<MultiPolygon> sortie_regions;
  std::vector<Waypoint> waypoints;
  int sorties = 1;
  double length_m = 0.0;
  /// From the first take-off to the last landing: flight (vertical_s included)
  /// plus the swaps between sorties ((sorties - 1) * FleetSpec::swap_s).
  double time_s = 0.0;
  /// time_s split by what the drone does: flying lanes, turning at lane ends
  /// (turn_cost_s each), and flying anything else (lane-to-lane connections,
  /// cell-to-cell and launch/home transits, returns between sorties).
  double sweep_s = 0.0;
  double turn_s = 0.0;
  double transit_s = 0.0;
  double ground_s = 0.0;          ///< on the ground between sorties
  double vertical_s = 0.0;        ///< climbing after each take-off and descending to each landing
  double longest_sortie_s = 0.0;  ///< the longest single flight, <= FleetSpec::endurance_s
};

/// The fleet's plan and its figures. "Region" below is the searchable part:
/// `area` minus `no_fly`.
struct Plan {
  std::vector<DronePlan> drones;
  double sweep_width_m = 0.0;  ///< lane spacing: footprint width times (1 - side overlap)
  /// Fraction 0..1 of the region seen: the region rasterised (cells of 1 m up to
  /// sweep / 10, about 4 million at most), a cell seen when its centre lies within
  /// half the footprint width of any flown segment (lanes, turns and transits).
  double coverage = 0.0;
  double makespan_s = 0.0;  ///< the slowest drone's time, all sorties, turns included
  /// A lower bound on the makespan from the region, the sites and the fleet alone
  /// (planner/src/lower_bound.hpp): the largest of the busiest drone's sweep with
  /// the swaps its sorties force, the busiest far drone's at every distance from
  /// the nearest site, and the fleet's flight counted layer by layer (sorties that
  /// must reach beyond each distance fly out to it and back), swaps included.
  double lower_bound_s = 0.0;
  std::string lower_bound_basis;   ///< which term of the bound gave lower_bound_s, in words
  double nofly_violation_m = 0.0;  ///< path metres strictly inside no-fly zones (0 when correct)
  double planning_seconds = 0.0;   ///< wall time PlanSearch took
};

/// Plans the search. Lanes are laid over the whole region (one sweep direction at
/// a time), grouped into stripes, walked as a snake and cut into sortie units (a
/// lane may be split between two sorties); units go to drones and drones to launch
/// sites so that the fleet finishes together; each sortie flies out of its site
/// and back, every transit around the no-fly zones (TransitPlanner), with a swap
/// of swap_s between sorties. The sweep direction, the sorties per drone, the
/// stripe height and the cut with the shortest makespan are kept. With kOmpl
/// each sortie's region is covered by the OMPL variant instead of its lanes.
/// Deterministic for a given `seed`. Throws std::invalid_argument with a message
/// naming the field when the fleet is unusable (receiver_ids empty, repeated or
/// outside 1..254; no launch_points, or one inside a no-fly zone; site_drones
/// not one count >= 0 per site adding up to the fleet; speed_mps, endurance_s or
/// altitude_m <= 0; swap_s or turn_cost_s < 0; any number beyond the kMax*
/// above; no camera; camera_pitch_deg outside [-90, 0); side_overlap outside
/// [0, 1); more than kMaxPlanLanes lanes, the message then starting with
/// "side_overlap") or the area is empty, and
/// std::runtime_error naming endurance_s, the farthest point (lat, lon) and the
/// range needed when some point is out of reach from every site.
Plan PlanSearch(const SearchArea& area, const FleetSpec& fleet,
                PlannerKind kind = PlannerKind::kLawnmower, unsigned seed = 1);

}  // namespace fireswarm::planner
