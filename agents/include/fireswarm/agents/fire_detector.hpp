// The vehicle's fire detector: hot regions per frame (hot_regions.hpp), each
// located on the ground (geolocation.hpp), tracked across frames by ground
// position, and reported to the server once confirmed. Pure: time comes in
// with every frame, no clock, no I/O.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include "fireswarm/agents/geolocation.hpp"
#include "fireswarm/agents/hot_regions.hpp"
#include "fireswarm/agents/vehicle_io.hpp"
#include "fireswarm/common/local_frame.hpp"

namespace fireswarm::agents {

struct FireDetectorConfig {
  DetectorConfig regions;    ///< per-frame hot-region thresholds
  GeolocationSigmas sigmas;  ///< input errors for each fix's covariance
  /// A candidate is a fire once seen in this many consecutive frames.
  int persist_frames = 3;
  /// A fire is reported when its pass ends (the first frame it is missing from
  /// after at least persist_frames in a row), so that its position averages
  /// every frame of the pass, from the front of the image to the back: the
  /// attitude noise and the pull toward the centre of a wrong altitude cancel
  /// there, while the first three frames all lie at the front edge. One still
  /// in view this long after its run of frames began, or after its last report,
  /// is reported without waiting (a vehicle hovering or circling over it: its
  /// reports from around the circle are the investigation's second look), s.
  /// A pass at 10 m/s under the seed camera at 60 m lasts about 8 s.
  double max_pass_wait_s = 10.0;
  /// A reported fire is not reported again sooner than this, s.
  double report_interval_s = 15.0;
  /// A region joins the nearest candidate within
  /// max(gate_min_m, gate_sigmas * sqrt(largest eigenvalue of the summed covariances)).
  double gate_min_m = 15.0;
  double gate_sigmas = 3.0;
  /// Candidates unseen for this long are forgotten, s (reported ones are kept
  /// at least until report_interval_s after their report, so a fire seen again
  /// within the interval is recognised and not reported twice).
  double forget_after_s = 5.0;

  /// Throws std::invalid_argument naming the first bad field.
  void Validate() const;
};

/// The defaults, with the hot-region thresholds for `model` (DetectorConfigFor).
FireDetectorConfig FireDetectorConfigFor(const common::CameraModel& model);

/// A confirmed fire, as the vehicle reports it.
struct FireDetection {
  double time_s = 0.0;      ///< time of the frame that confirmed it
  common::LatLon position;  ///< mean of the candidate's fixes
  double sigma_north_m = 0.0;
  double sigma_east_m = 0.0;
  double correlation_ne = 0.0;  ///< north/east correlation coefficient, [-1, 1]
  common::LatLon observer;      ///< the vehicle's GPS position at time_s
  double observer_altitude_m = 0.0;
  int pixel_count = 0;              ///< size of the region in the confirming frame
  double peak_temperature_c = 0.0;  ///< hottest pixel over the confirming frames
  /// Heuristic in [0, 1]: half from persistence (consecutive frames seen, full at
  /// twice persist_frames), half from size (full at kConfidentRegionPx pixels).
  double confidence = 0.0;
};

/// Regions of at least this many pixels count fully toward a detection's confidence.
inline constexpr int kConfidentRegionPx = 4;

class FireDetector {
 public:
  /// Throws std::invalid_argument (see FireDetectorConfig::Validate).
  explicit FireDetector(FireDetectorConfig config = {});

  /// Runs one frame taken at `time_s` from `pose`; returns the fires confirmed
  /// or due for a repeat report in this frame (usually none). Frames must come
  /// in time order: throws std::invalid_argument naming "time_s" otherwise, and
  /// as FindHotRegions for a malformed frame.
  ///
  /// Averaging: a candidate's position is the mean of its fixes (at most the
  /// last kMaxAveragedFixes count fully). Only the pixel (centroid) error is
  /// independent between frames and shrinks with the number of fixes; GPS
  /// position, altitude and attitude errors drift slowly, repeat over the
  /// frames of one pass and do not average out, so the reported covariance is
  /// the mean navigation part plus the mean pixel part divided by the fixes.
  std::vector<FireDetection> Process(double time_s, const CameraFrame& frame,
                                     const ObserverPose& pose);
  /// The same, with the pose asked of `pose_at_frame` only when the frame needs
  /// it (a fire region to locate, or a candidate to report), at most once: a
  /// vehicle's pose costs a projection to latitude and longitude, and most
  /// frames are plain ground.
  std::vector<FireDetection> Process(double time_s, const CameraFrame& frame,
                                     const std::function<ObserverPose()>& pose_at_frame);

  const FireDetectorConfig& config() const { return config_; }
  /// Candidates currently tracked (confirmed or not).
  std::size_t candidate_count() const { return candidates_.size(); }

  /// Fixes beyond this count enter a candidate's mean with weight 1/kMaxAveragedFixes,
  /// so a fire that grows or drifts is followed: a little over one pass (10 s
  /// at the seed camera's 9 Hz).
  static constexpr int kMaxAveragedFixes = 100;
  /// A fire only ever seen cut by the image edge is reported after this many
  /// times persist_frames consecutive sightings.
  static constexpr int kClippedPersistFactor = 3;

 private:
  struct Candidate {
    Eigen::Vector2d east_north_m = Eigen::Vector2d::Zero();  // in anchor_
    Eigen::Matrix2d navigation_covariance_en_m2 = Eigen::Matrix2d::Zero();
    Eigen::Matrix2d pixel_covariance_en_m2 = Eigen::Matrix2d::Zero();
    int fixes = 0;                // averaged into east_north_m
    bool has_whole_fix = false;   // a fix from a region not cut by the image edge
    int streak = 0;               // consecutive frames seen, ending at last_frame
    double streak_start_s = 0.0;  // time of the streak's first frame
    std::uint64_t last_frame = 0;
    double last_seen_s = 0.0;
    bool reported = false;              // ever
    bool reported_this_streak = false;  // the streak's end is then not reported again
    double last_report_s = 0.0;
    double peak_temperature_c = 0.0;  // over the current streak
    int pixel_count = 0;              // in the last frame
  };
  struct Fix {
    Eigen::Vector2d east_north_m;  // in anchor_
    GroundFix ground;
    const HotRegion* region;
    bool clipped;  // the region touches the image edge
  };

  /// (east, north), m^2.
  Eigen::Matrix2d CovarianceOf(const Candidate& candidate) const;
  std::size_t Associate(const Fix& fix);
  void Fold(Candidate& candidate, const Fix& fix);
  bool DueForReport(const Candidate& candidate, double time_s) const;
  bool PassEnded(const Candidate& candidate) const { return candidate.last_frame + 1 == frame_; }
  FireDetection Report(const Candidate& candidate, double time_s, const ObserverPose& pose) const;
  void Forget(double time_s);

  FireDetectorConfig config_;
  std::optional<common::LocalFrame> anchor_;  // tracking frame, at the first pose seen
  std::vector<Candidate> candidates_;
  std::uint64_t frame_ = 0;
  std::optional<double> last_time_s_;
  std::vector<std::size_t> hit_this_frame_;  // scratch
};

}  // namespace fireswarm::agents
