#include "fireswarm/agents/fire_detector.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string_view>

#include "fireswarm/common/north_east.hpp"

namespace fireswarm::agents {
namespace {

[[noreturn]] void Reject(std::string_view field, double value, std::string_view rule) {
  std::ostringstream message;
  message << "fire detector: " << field << " = " << value << " " << rule;
  throw std::invalid_argument(message.str());
}

void RequirePositive(std::string_view field, double value) {
  if (!(value > 0.0) || !std::isfinite(value)) Reject(field, value, "must be a finite number > 0");
}

void RequireNonNegative(std::string_view field, double value) {
  if (!(value >= 0.0) || !std::isfinite(value)) {
    Reject(field, value, "must be a finite number >= 0");
  }
}

}  // namespace

void FireDetectorConfig::Validate() const {
  regions.Validate();
  RequireNonNegative("sigmas.horizontal_m", sigmas.horizontal_m);
  RequireNonNegative("sigmas.altitude_m", sigmas.altitude_m);
  RequireNonNegative("sigmas.roll_rad", sigmas.roll_rad);
  RequireNonNegative("sigmas.pitch_rad", sigmas.pitch_rad);
  RequireNonNegative("sigmas.heading_rad", sigmas.heading_rad);
  RequireNonNegative("sigmas.pixel_px", sigmas.pixel_px);
  if (persist_frames < 1) Reject("persist_frames", persist_frames, "must be >= 1");
  RequirePositive("max_pass_wait_s", max_pass_wait_s);
  RequireNonNegative("report_interval_s", report_interval_s);
  RequirePositive("gate_min_m", gate_min_m);
  RequireNonNegative("gate_sigmas", gate_sigmas);
  RequirePositive("forget_after_s", forget_after_s);
}

FireDetectorConfig FireDetectorConfigFor(const common::CameraModel& model) {
  FireDetectorConfig config;
  config.regions = DetectorConfigFor(model);
  return config;
}

FireDetector::FireDetector(FireDetectorConfig config) : config_(config) {
  config_.Validate();
}

std::vector<FireDetection> FireDetector::Process(double time_s, const CameraFrame& frame,
                                                 const ObserverPose& pose) {
  return Process(time_s, frame, [&pose] { return pose; });
}

std::vector<FireDetection> FireDetector::Process(
    double time_s, const CameraFrame& frame, const std::function<ObserverPose()>& pose_at_frame) {
  std::optional<ObserverPose> pose_once;
  const auto pose = [&]() -> const ObserverPose& {
    if (!pose_once) pose_once = pose_at_frame();
    return *pose_once;
  };
  if (!std::isfinite(time_s) || (last_time_s_ && time_s < *last_time_s_)) {
    Reject("time_s", time_s, "must be finite and not before the previous frame's");
  }
  last_time_s_ = time_s;
  ++frame_;
  const std::vector<HotRegion> regions = FindHotRegions(frame, config_.regions);

  // Largest regions first: when two regions of one fire fall in one gate, the
  // larger one founds or moves the candidate.
  std::vector<const HotRegion*> fires;
  for (const HotRegion& region : regions) {
    if (region.is_fire) fires.push_back(&region);
  }
  std::stable_sort(fires.begin(), fires.end(), [](const HotRegion* a, const HotRegion* b) {
    return a->pixel_count > b->pixel_count;
  });

  hit_this_frame_.clear();
  for (const HotRegion* region : fires) {
    const std::optional<GroundFix> ground =
        GeolocatePixel(pose(), region->centroid, config_.sigmas);
    if (!ground) continue;  // above the horizon: no ground position
    if (!anchor_) anchor_.emplace(ground->position);
    const common::EastNorth local = anchor_->ToLocal(ground->position);
    // A region cut by the image edge has its centroid pulled inward.
    const bool clipped = region->min_col == 0 || region->min_row == 0 ||
                         region->max_col == frame.width_px - 1 ||
                         region->max_row == frame.height_px - 1;
    const Fix fix{Eigen::Vector2d(local.east_m, local.north_m), *ground, region, clipped};
    const std::size_t index = Associate(fix);
    Candidate& candidate = candidates_[index];
    if (std::find(hit_this_frame_.begin(), hit_this_frame_.end(), index) != hit_this_frame_.end()) {
      // A second region of the same fire in this frame: one sighting, not two.
      candidate.pixel_count += region->pixel_count;
      candidate.peak_temperature_c =
          std::max(candidate.peak_temperature_c, region->peak_temperature_c);
      continue;
    }
    hit_this_frame_.push_back(index);
    Fold(candidate, fix);
  }

  // Candidates seen in this frame, and those whose pass ended with the last one.
  std::vector<FireDetection> detections;
  for (Candidate& candidate : candidates_) {
    if (candidate.last_frame != frame_ && !PassEnded(candidate)) continue;
    if (!DueForReport(candidate, time_s)) continue;
    detections.push_back(Report(candidate, time_s, pose()));
    candidate.reported = true;
    candidate.reported_this_streak = true;
    candidate.last_report_s = time_s;
  }
  Forget(time_s);
  return detections;
}

Eigen::Matrix2d FireDetector::CovarianceOf(const Candidate& candidate) const {
  const int averaged = std::min(candidate.fixes, kMaxAveragedFixes);
  return candidate.navigation_covariance_en_m2 + candidate.pixel_covariance_en_m2 / averaged;
}

std::size_t FireDetector::Associate(const Fix& fix) {
  std::size_t best = candidates_.size();
  double best_distance_m = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < candidates_.size(); ++i) {
    const Candidate& candidate = candidates_[i];
    const double distance_m = (candidate.east_north_m - fix.east_north_m).norm();
    const Eigen::Matrix2d summed_en_m2 = CovarianceOf(candidate) + fix.ground.covariance_en_m2;
    // Solved in (north, east) order, as before the tree went east-first: Eigen's
    // eigenvalues of the axis-swapped matrix may differ in the last bit, and
    // with them the gate.
    const double largest_m2 = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(
                                  common::SwapAxes(summed_en_m2), Eigen::EigenvaluesOnly)
                                  .eigenvalues()
                                  .maxCoeff();
    const double gate_m =
        std::max(config_.gate_min_m, config_.gate_sigmas * std::sqrt(std::max(largest_m2, 0.0)));
    if (distance_m <= gate_m && distance_m < best_distance_m) {
      best = i;
      best_distance_m = distance_m;
    }
  }
  if (best == candidates_.size()) candidates_.emplace_back();
  return best;
}

void FireDetector::Fold(Candidate& candidate, const Fix& fix) {
  const bool continues = candidate.streak > 0 && candidate.last_frame + 1 == frame_;
  candidate.streak = continues ? candidate.streak + 1 : 1;
  if (!continues) {
    candidate.reported_this_streak = false;
    candidate.streak_start_s = *last_time_s_;
    candidate.peak_temperature_c = fix.region->peak_temperature_c;
  } else {
    candidate.peak_temperature_c =
        std::max(candidate.peak_temperature_c, fix.region->peak_temperature_c);
  }
  candidate.last_frame = frame_;
  candidate.last_seen_s = *last_time_s_;
  candidate.pixel_count = fix.region->pixel_count;

  // A fix from a region cut by the image edge is biased: it is kept only until
  // the first whole region replaces it, and never mixed with whole ones.
  if (fix.clipped && candidate.has_whole_fix) return;
  if (!fix.clipped && !candidate.has_whole_fix) {
    candidate.has_whole_fix = true;
    candidate.fixes = 0;
  }
  // Running means (weight 1/n, at least 1/kMaxAveragedFixes).
  candidate.fixes += 1;
  const double weight = 1.0 / std::min(candidate.fixes, kMaxAveragedFixes);
  const Eigen::Matrix2d navigation_en_m2 =
      fix.ground.covariance_en_m2 - fix.ground.pixel_covariance_en_m2;
  candidate.east_north_m += weight * (fix.east_north_m - candidate.east_north_m);
  candidate.navigation_covariance_en_m2 +=
      weight * (navigation_en_m2 - candidate.navigation_covariance_en_m2);
  candidate.pixel_covariance_en_m2 +=
      weight * (fix.ground.pixel_covariance_en_m2 - candidate.pixel_covariance_en_m2);
}

bool FireDetector::DueForReport(const Candidate& candidate, double time_s) const {
  if (candidate.streak < config_.persist_frames) return false;
  // Wait for a whole view of the fire, unless it stays cut by the edge (a fire
  // larger than the view).
  if (!candidate.has_whole_fix &&
      candidate.streak < kClippedPersistFactor * config_.persist_frames) {
    return false;
  }
  if (candidate.reported && time_s - candidate.last_report_s < config_.report_interval_s) {
    return false;
  }
  if (PassEnded(candidate)) return !candidate.reported_this_streak;
  // Still in view (a vehicle circling over it): every max_pass_wait_s of it.
  const double since_s =
      candidate.reported_this_streak ? candidate.last_report_s : candidate.streak_start_s;
  return candidate.last_seen_s - since_s >= config_.max_pass_wait_s;
}

FireDetection FireDetector::Report(const Candidate& candidate, double time_s,
                                   const ObserverPose& pose) const {
  FireDetection detection;
  detection.time_s = time_s;
  detection.position = anchor_->ToGeodetic(
      common::EastNorth{candidate.east_north_m.x(), candidate.east_north_m.y()});
  const auto [north_north_m2, north_east_m2, east_east_m2] =
      common::NorthEastTriangle(CovarianceOf(candidate));
  detection.sigma_north_m = std::sqrt(north_north_m2);
  detection.sigma_east_m = std::sqrt(east_east_m2);
  const double product = detection.sigma_north_m * detection.sigma_east_m;
  detection.correlation_ne = product > 0.0 ? north_east_m2 / product : 0.0;
  detection.observer = pose.position;
  detection.observer_altitude_m = pose.altitude_m;
  detection.pixel_count = candidate.pixel_count;
  detection.peak_temperature_c = candidate.peak_temperature_c;
  const double persistence = std::min(1.0, candidate.streak / (2.0 * config_.persist_frames));
  const double size =
      std::min(1.0, static_cast<double>(candidate.pixel_count) / kConfidentRegionPx);
  detection.confidence = 0.5 * persistence + 0.5 * size;
  return detection;
}

void FireDetector::Forget(double time_s) {
  std::erase_if(candidates_, [&](const Candidate& candidate) {
    const bool unseen = time_s - candidate.last_seen_s > config_.forget_after_s;
    const bool repeat_barred =
        candidate.reported && time_s - candidate.last_report_s < config_.report_interval_s;
    return unseen && !repeat_barred;
  });
}

}  // namespace fireswarm::agents
