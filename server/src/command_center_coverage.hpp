// The command center's coverage raster (GET /api/coverage): the plan's area in
// square cells, each seen or not by a drone's camera, from vehicle_state_t.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "fireswarm/common/camera_model.hpp"
#include "fireswarm/planner/coverage_grid.hpp"
#include "fireswarm/planner/plan.hpp"
#include "fireswarm/vehicle_state_t.hpp"

namespace fireswarm::server::internal {

/// The plan's camera: its "camera" member {"hfov_deg", "vfov_deg", "pitch_deg"}.
struct PlanCamera {
  common::CameraModel model;  ///< only the fields of view are known
  double pitch_deg = -90.0;   ///< mount pitch from the horizon, -90 straight down
};

class CoverageRaster {
 public:
  /// The raster of a plan_t's GeoJSON: the area is its features of kind "area"
  /// less those of kind "no_fly", projected with planner::ParseSearchArea (local
  /// frame origin: the centre of the area's latitude/longitude bounding box).
  /// nullptr when the plan has no area feature. Throws std::invalid_argument
  /// naming the problem for a malformed area or camera. `current`, the raster of
  /// the plan before, is returned as it is (its cells seen kept) when the new plan
  /// has the same area, no-fly zones and camera: a plan changes with the lanes.
  static std::unique_ptr<CoverageRaster> FromPlan(
      const nlohmann::json& plan, std::unique_ptr<CoverageRaster> current = nullptr);

  /// Marks the cells the vehicle's camera sees now (nothing unless it is airborne
  /// with a position). A state that repeats the telemetry sample already marked
  /// (the same vehicle_time_ms: states are published at 5 Hz, telemetry comes at
  /// 1-2 Hz) marks nothing again.
  void Mark(const vehicle_state_t& message);

  /// {"cell_m", "rows", "cols", "corners": [[lat, lon] x 4: SW, SE, NE, NW],
  /// "seen": base64 bitset}: cell (row r from the south, column c from the west)
  /// is bit (k mod 8) of byte k / 8, k = r * cols + c, least significant bit first.
  nlohmann::json ToJson() const;

  std::size_t seen_cells() const { return grid_.seen_cells(); }
  int rows() const { return grid_.rows(); }
  int cols() const { return grid_.cols(); }

 private:
  CoverageRaster(planner::SearchArea area, PlanCamera camera, std::string source);

  std::string source_;  // the area's, no-fly zones' and camera's JSON it was made from
  planner::SearchArea area_;
  PlanCamera camera_;
  // The same raster and footprint the server's coverage_fraction and a run's
  // report count (planner::CoverageGrid), here marked from vehicle_state_t.
  planner::CoverageGrid grid_;
  std::map<std::int16_t, std::int64_t> marked_sample_ms_;  // receiver ID -> vehicle_time_ms
};

}  // namespace fireswarm::server::internal
