// Transit between two points around no-fly zones (launch -> region, cell -> cell,
// region -> home, and the server's own legs: a lost drone's lanes joined to a
// taker's route, an investigation's approach and circle), planned with OMPL. The
// class hides OMPL (pimpl): OMPL stays inside planner/src.
#pragma once

#include <memory>

#include "fireswarm/planner/geometry.hpp"

namespace fireswarm::planner {

/// How far inside a no-fly zone a point may lie and still count as on its
/// boundary: 1 micrometre, the rounding of points computed on a zone's edge (lane
/// ends clipped against the area minus the zones) a few orders of magnitude over,
/// and the length under which InteriorLengthM ignores a piece, so a leg leaving
/// such a point adds 0 m inside.
inline constexpr double kOnBoundaryToleranceM = 1e-6;

/// Metres of `path` strictly inside the interior of `zones`. Pieces that only run
/// along a zone's boundary or touch it at a point do not count, nor do pieces
/// shorter than 1 micrometre (rounding where a segment grazes a vertex).
double InteriorLengthM(const Path& path, const MultiPolygon& zones);

class TransitPlanner {
 public:
  /// `no_fly`: zones a path must not enter; `bounds`: the box paths stay in
  /// (the area's envelope grown by a margin). Deterministic for a given seed: each
  /// Plan call seeds its own random generators from `seed` and the query.
  TransitPlanner(const MultiPolygon& no_fly, const Box& bounds, unsigned seed);
  ~TransitPlanner();
  TransitPlanner(const TransitPlanner&) = delete;
  TransitPlanner& operator=(const TransitPlanner&) = delete;

  /// A short path from `from` to `to` (both included) that enters no no-fly zone:
  /// the straight segment when it is clear, otherwise an OMPL path (RRTConnect in a
  /// RealVector(2) space, exact segment checks, then shortened greedily with exact
  /// checks). Every returned segment satisfies IsClear. Thread-compatible (const).
  /// An endpoint inside a zone but within kOnBoundaryToleranceM of its boundary is
  /// taken as on the boundary. Throws std::runtime_error when no path is found
  /// within the cap (e.g. `to` is walled in) or an endpoint lies deeper in a zone.
  Path Plan(Point from, Point to) const;

  /// True when `p` lies inside a no-fly zone's interior by more than
  /// kOnBoundaryToleranceM (on or next to the boundary is not inside).
  bool IsInside(Point p) const;

  /// True when the straight segment enters no no-fly zone's interior
  /// (InteriorLengthM == 0); touching a boundary is allowed.
  bool IsClear(Point from, Point to) const;

  /// True when the circle of `radius_m` (> 0) around `center` enters no no-fly
  /// zone's interior; touching a boundary is allowed. Exact, not sampled: over a
  /// zone (connected) the distance from `center` takes every value between the
  /// nearest and the farthest, so the circle enters it exactly when the radius
  /// lies strictly between the two.
  bool IsCircleClear(Point center, double radius_m) const;

  /// The zones this planner keeps out of.
  const MultiPolygon& NoFly() const;

  /// Length of Plan(from, to) in metres; the straight distance when it is clear.
  double DistanceM(Point from, Point to) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fireswarm::planner
