// The coverage raster over the plan's area.
#include "command_center_coverage.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "base64.hpp"
#include "fireswarm/planner/area_io.hpp"

namespace fireswarm::server::internal {

namespace {

// As run/'s scoring grid: 5 m cells, coarser when the area would need more than
// kMaxCells of them.
constexpr double kCellM = 5.0;
constexpr double kMaxCells = 2'000'000.0;

double CameraNumber(const nlohmann::json& camera, const char* key, double low, double high) {
  const auto found = camera.find(key);
  if (found == camera.end() || !found->is_number() || !(found->get<double>() >= low) ||
      !(found->get<double>() <= high)) {
    throw std::invalid_argument(std::string("camera.") + key + ": must be a number in [" +
                                std::to_string(low) + ", " + std::to_string(high) + "]");
  }
  return found->get<double>();
}

PlanCamera ReadCamera(const nlohmann::json& plan) {
  const auto camera = plan.find("camera");
  if (camera == plan.end() || !camera->is_object()) {
    throw std::invalid_argument("camera: the plan has no camera object");
  }
  PlanCamera result;
  result.model.name = "plan";
  result.model.hfov_deg = CameraNumber(*camera, "hfov_deg", 1.0, 179.0);
  result.model.vfov_deg = CameraNumber(*camera, "vfov_deg", 1.0, 179.0);
  result.pitch_deg = CameraNumber(*camera, "pitch_deg", -90.0, 0.0);
  return result;
}

// The features of one kind, as a FeatureCollection's text for ParseSearchArea.
std::string FeaturesOfKind(const nlohmann::json& plan, const std::string& kind, bool* any) {
  nlohmann::json collection = {{"type", "FeatureCollection"},
                               {"features", nlohmann::json::array()}};
  const auto features = plan.find("features");
  if (features != plan.end() && features->is_array()) {
    for (const nlohmann::json& feature : *features) {
      const auto properties = feature.find("properties");
      if (properties == feature.end() || !properties->is_object() ||
          properties->value("kind", "") != kind) {
        continue;
      }
      collection["features"].push_back(feature);
      *any = true;
    }
  }
  return collection.dump();
}

}  // namespace

std::unique_ptr<CoverageRaster> CoverageRaster::FromPlan(const nlohmann::json& plan) {
  bool has_area = false;
  bool has_no_fly = false;
  std::string area_text = FeaturesOfKind(plan, "area", &has_area);
  if (!has_area) return nullptr;
  std::string no_fly_text = FeaturesOfKind(plan, "no_fly", &has_no_fly);
  PlanCamera camera = ReadCamera(plan);
  std::optional<planner::GeoJsonText> no_fly;
  if (has_no_fly) no_fly = planner::GeoJsonText{std::move(no_fly_text), "plan no_fly"};
  planner::SearchArea area =
      planner::ParseSearchArea(planner::GeoJsonText{std::move(area_text), "plan area"}, no_fly);
  return std::unique_ptr<CoverageRaster>(new CoverageRaster(std::move(area), camera));
}

CoverageRaster::CoverageRaster(planner::SearchArea area, PlanCamera camera)
    : area_(std::move(area)), camera_(camera) {
  // The outer rings' bounds (boost::geometry::envelope draws GCC 12's
  // maybe-uninitialized false positive, see planner/CMakeLists.txt).
  double max_east_m = -std::numeric_limits<double>::infinity();
  double max_north_m = max_east_m;
  min_east_m_ = -max_east_m;
  min_north_m_ = -max_east_m;
  for (const planner::Polygon& polygon : area_.area) {
    for (const planner::Point& point : polygon.outer()) {
      min_east_m_ = std::min(min_east_m_, point.x());
      max_east_m = std::max(max_east_m, point.x());
      min_north_m_ = std::min(min_north_m_, point.y());
      max_north_m = std::max(max_north_m, point.y());
    }
  }
  const double width_m = max_east_m - min_east_m_;
  const double height_m = max_north_m - min_north_m_;
  cell_m_ = std::max(kCellM, std::sqrt(width_m * height_m / kMaxCells));
  // A side that projection made millimetres longer than whole cells gets no
  // extra row or column.
  constexpr double kCellFractionIgnored = 1e-3;
  cols_ = std::max(1, static_cast<int>(std::ceil(width_m / cell_m_ - kCellFractionIgnored)));
  rows_ = std::max(1, static_cast<int>(std::ceil(height_m / cell_m_ - kCellFractionIgnored)));
  seen_.assign(static_cast<std::size_t>(rows_) * static_cast<std::size_t>(cols_), 0);
}

void CoverageRaster::Mark(const vehicle_state_t& /*message*/) {
  // The camera footprint is planner::CoverageGrid's (moving from run/ to planner/);
  // until it is there, no cell is marked seen.
}

nlohmann::json CoverageRaster::ToJson() const {
  std::vector<std::uint8_t> bits((seen_.size() + 7) / 8, 0);
  for (std::size_t k = 0; k < seen_.size(); ++k) {
    if (seen_[k] != 0) bits[k / 8] |= static_cast<std::uint8_t>(1U << (k % 8));
  }
  const double east_m[] = {min_east_m_, min_east_m_ + cols_ * cell_m_};
  const double north_m[] = {min_north_m_, min_north_m_ + rows_ * cell_m_};
  nlohmann::json corners = nlohmann::json::array();
  // SW, SE, NE, NW.
  for (const auto& [e, n] : {std::pair{east_m[0], north_m[0]}, std::pair{east_m[1], north_m[0]},
                             std::pair{east_m[1], north_m[1]}, std::pair{east_m[0], north_m[1]}}) {
    const common::LatLon corner = area_.frame.ToGeodetic({e, n});
    corners.push_back({corner.lat_deg, corner.lon_deg});
  }
  return {{"cell_m", cell_m_},
          {"rows", rows_},
          {"cols", cols_},
          {"corners", std::move(corners)},
          {"seen", Base64Encode(bits)}};
}

}  // namespace fireswarm::server::internal
