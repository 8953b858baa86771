// The coverage raster over the plan's area.
#include "command_center_coverage.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "base64.hpp"
#include "fireswarm/common/angles.hpp"
#include "fireswarm/planner/area_io.hpp"

namespace fireswarm::server::internal {

namespace {

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

std::unique_ptr<CoverageRaster> CoverageRaster::FromPlan(const nlohmann::json& plan,
                                                         std::unique_ptr<CoverageRaster> current) {
  bool has_area = false;
  bool has_no_fly = false;
  std::string area_text = FeaturesOfKind(plan, "area", &has_area);
  if (!has_area) return nullptr;
  std::string no_fly_text = FeaturesOfKind(plan, "no_fly", &has_no_fly);
  const auto camera_member = plan.find("camera");
  std::string source = area_text + "\n" + no_fly_text + "\n" +
                       (camera_member == plan.end() ? "" : camera_member->dump());
  if (current && current->source_ == source) return current;
  PlanCamera camera = ReadCamera(plan);
  std::optional<planner::GeoJsonText> no_fly;
  if (has_no_fly) no_fly = planner::GeoJsonText{std::move(no_fly_text), "plan no_fly"};
  planner::SearchArea area =
      planner::ParseSearchArea(planner::GeoJsonText{std::move(area_text), "plan area"}, no_fly);
  return std::unique_ptr<CoverageRaster>(
      new CoverageRaster(std::move(area), camera, std::move(source)));
}

CoverageRaster::CoverageRaster(planner::SearchArea area, PlanCamera camera, std::string source)
    : source_(std::move(source)),
      area_(std::move(area)),
      camera_(camera),
      grid_(area_.area, area_.no_fly) {}

void CoverageRaster::Mark(const vehicle_state_t& message) {
  // Not heard yet, or no GPS fix: no position to see from.
  if (message.telemetry_age_s < 0.0 || !message.has_position) return;
  const auto [marked, first] =
      marked_sample_ms_.try_emplace(message.receiver_id, message.vehicle_time_ms);
  if (!first) {
    if (marked->second == message.vehicle_time_ms) return;
    marked->second = message.vehicle_time_ms;
  }
  const common::EastNorth position = area_.frame.ToLocal({message.lat_deg, message.lon_deg});
  grid_.Mark(Eigen::Vector2d(position.east_m, position.north_m),
             message.heading_deg * common::kRadPerDeg, message.altitude_m, camera_.model,
             camera_.pitch_deg);
}

nlohmann::json CoverageRaster::ToJson() const {
  const int rows = grid_.rows();
  const int cols = grid_.cols();
  const double cell_m = grid_.cell_m();
  const std::vector<std::uint8_t> bits = grid_.SeenBitset();
  const Eigen::Vector2d south_west = grid_.south_west_en_m();
  const double east_m[] = {south_west.x(), south_west.x() + cols * cell_m};
  const double north_m[] = {south_west.y(), south_west.y() + rows * cell_m};
  nlohmann::json corners = nlohmann::json::array();
  // SW, SE, NE, NW.
  for (const auto& [e, n] : {std::pair{east_m[0], north_m[0]}, std::pair{east_m[1], north_m[0]},
                             std::pair{east_m[1], north_m[1]}, std::pair{east_m[0], north_m[1]}}) {
    const common::LatLon corner = area_.frame.ToGeodetic({e, n});
    corners.push_back({corner.lat_deg, corner.lon_deg});
  }
  return {{"cell_m", cell_m},
          {"rows", rows},
          {"cols", cols},
          {"corners", std::move(corners)},
          {"seen", Base64Encode(bits)}};
}

}  // namespace fireswarm::server::internal
