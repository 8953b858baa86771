// The fleet's coverage route and its split among drones. The lawnmower builds one
// route over the whole region (coverage.hpp, SweepRoute); the partition cuts it
// into contiguous shares of equal estimated flight time, each drone's transit from
// and back to its launch point included.
#pragma once

#include <functional>
#include <vector>

#include "fireswarm/planner/geometry.hpp"
#include "lanes.hpp"

namespace fireswarm::planner {

/// One boustrophedon cell with the lane frame it is swept in (each cell has its
/// own sweep direction).
struct SweptCell {
  LaneFrame frame;
  Polygon cell;  ///< in `frame`
};

/// One lane of the route, in its cell's lane frame.
struct RouteLane {
  std::size_t cell = 0;  ///< index into Route::cells
  Lane lane;
};

/// A timed polyline: points[i] reached at time_s[i]; segment i (points[i] ->
/// points[i + 1]) first spends turn_s[i] turning at points[i], then flies at speed.
struct Route {
  std::vector<SweptCell> cells;
  std::vector<RouteLane> lanes;
  std::vector<Point> points;  ///< local frame
  std::vector<double> time_s;
  std::vector<double> turn_s;     ///< per segment
  std::vector<int> segment_lane;  ///< per segment: index into lanes, -1 off lanes
  double speed_mps = 1.0;

  double TotalS() const { return time_s.empty() ? 0.0 : time_s.back(); }
  /// Where the route is at time t (clamped to [0, TotalS()]).
  Point At(double t_s) const;
  /// Index of the segment flown at time t (the last one at the end).
  std::size_t SegmentAt(double t_s) const;
  /// The piece flown between t0 and t1: At(t0), the points in between, At(t1).
  Path Slice(double t0_s, double t1_s) const;
  /// Appends a segment to `to` (skipped when of zero length, its turn carried on).
  void Extend(Point to, int lane, double turn_s);

 private:
  double pending_turn_s_ = 0.0;
};

/// One drone's share of the route.
struct Share {
  double begin_s = 0.0;  ///< route time where the share starts
  double end_s = 0.0;
  double time_s = 0.0;  ///< estimated: transit out + share + transit home
};

/// Straight-line or planned distance in metres between two points.
using DistanceFn = std::function<double(Point, Point)>;

/// Cuts `route` into launches.size() contiguous shares (in route order; drone i
/// flies from and back to launches[i]) minimising the longest estimated time,
/// by bisection on that time; the cut positions are continuous (a lane may be
/// shared by two drones). Drones are given shares in the order of the route point
/// nearest their launch point. `extra_s` (empty, or one per drone) is added to
/// each drone's estimate, e.g. the detour its transits need around no-fly zones
/// beyond `distance_m`. Returns one share per drone, in launches' order.
std::vector<Share> PartitionRoute(const Route& route, const std::vector<Point>& launches,
                                  const DistanceFn& distance_m,
                                  const std::vector<double>& extra_s = {});

/// The part of the region a share is responsible for: the lane strips it flies,
/// clipped to their cells, in the local frame. Contiguous when the share stays in
/// one cell or passes between adjacent cells.
MultiPolygon ShareRegion(const Route& route, const Share& share);

}  // namespace fireswarm::planner
