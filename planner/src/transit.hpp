// Transit between two points around no-fly zones (launch -> region, cell -> cell,
// region -> home), planned with OMPL. OMPL stays inside planner/src.
#pragma once

#include <memory>

#include "fireswarm/planner/geometry.hpp"

namespace fireswarm::planner {

class TransitPlanner {
 public:
  /// `no_fly`: zones a path must not enter; `bounds`: the box paths stay in
  /// (the area's envelope grown by a margin). Deterministic for a given seed.
  TransitPlanner(const MultiPolygon& no_fly, const Box& bounds, unsigned seed);
  ~TransitPlanner();
  TransitPlanner(const TransitPlanner&) = delete;
  TransitPlanner& operator=(const TransitPlanner&) = delete;

  /// A short path from `from` to `to` that enters no no-fly zone: the straight
  /// segment when it is clear, otherwise an OMPL path (RealVector space, simplified).
  /// Throws std::runtime_error when no path is found (e.g. `to` is walled in).
  Path Plan(Point from, Point to) const;

  /// True when the straight segment enters no no-fly zone.
  bool IsClear(Point from, Point to) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fireswarm::planner
