// The server's fire-report fusion: geolocated fire reports from every vehicle
// become fire tracks (gating, association, covariance-weighted fusion,
// confirmation by independent views, rejection). Pure: no I/O, no clock, no
// randomness; time comes in with every report as seconds of mission time.
//
// Frame: positions are metres in a local frame held by the caller
// (common::LocalFrame); vectors and covariances are ordered (east, north),
// index 0 = east, 1 = north, as common::EastNorth and the planner. The vehicles'
// reports and fire_track_t give sigmas and covariances north first: converted
// in ObservationFromReport and common/north_east.hpp.
//
// Why a per-vehicle bias term (and not covariance intersection, nor treating
// every report as independent):
// A report's covariance (agents::FireDetector) is the vehicle's navigation
// error (GPS position, altitude, attitude) plus its pixel error. The GPS part
// is a slowly drifting bias: it repeats in every report one vehicle sends, so
// fusing ten reports of one vehicle as independent would shrink the covariance
// ten-fold while the error stays the vehicle's bias. Each report's covariance
// R is therefore split into a vehicle bias B (vehicle_bias_sigma_m, the same
// for every report of that vehicle) and an independent part N = R - B. Reports
// of one vehicle are combined with the weights N^-1 into a per-vehicle estimate
// whose covariance is (sum N^-1)^-1 + B: it never falls below B, however many
// reports the vehicle sends. Different vehicles have independent GPS errors,
// so the per-vehicle estimates are then fused as independent (information
// sum): three vehicles do shrink the covariance. Covariance intersection would
// also be consistent, but it never lets independent vehicles shrink the
// covariance below the best single one, so confirmation by several vehicles
// would not sharpen the fire position. Treating a vehicle's passes as one bias
// is conservative: a GPS bias that drifts between passes makes the fused
// covariance slightly too large, never too small.
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

#include "fireswarm/common/local_frame.hpp"
#include "fireswarm/radio/messages.hpp"

namespace fireswarm::server {

/// Tuning of FireFusion. Every default is named here with its unit.
struct FireFusionConfig {
  /// Association gate on the squared Mahalanobis distance between a report and
  /// a track, with the report's plus the track's covariance: 9.21 is the 99 %
  /// point of a chi-square with 2 degrees of freedom.
  double gate_chi_square = 9.21;
  /// A report within this distance of a track is in its gate whatever the
  /// covariances say, m. A report's covariance is its geolocation error only,
  /// but a vehicle reports the centroid of the hot region it sees, and on a fire
  /// of some size that is wherever the front burns hottest from its view: the
  /// demo's 15 m fire, spreading in the wind, was reported up to 31 m apart by
  /// four vehicles and split into three tracks with a 15 m gate. Fires closer
  /// than this become one track (one incident for the crews).
  double min_gate_m = 35.0;
  /// A report farther than this from a track is never in its gate, m: very
  /// wide covariances must not merge separate fires.
  double max_gate_m = 60.0;
  /// One vehicle's GPS error that repeats in all its reports, 1-sigma per axis, m.
  /// 2.12 m is a 2.5 m CEP (agents::GeolocationSigmas::horizontal_m).
  double vehicle_bias_sigma_m = 2.12;
  /// Lower bound of the independent (per-report) part of a report's error,
  /// 1-sigma per axis, m; keeps the per-vehicle weights finite.
  double min_independent_sigma_m = 0.5;
  /// Lower bound of a report's covariance, 1-sigma per axis, m; a report with
  /// a zero or not positive-definite covariance is regularised to it.
  double min_report_sigma_m = 0.5;
  /// Two reports of the same vehicle are independent views (separate passes)
  /// when the observer positions are at least this far apart, m, ...
  double min_pass_separation_m = 25.0;
  /// ... and the detection times at least this far apart, s.
  double min_pass_interval_s = 30.0;

  /// Throws std::invalid_argument naming the first field that is not finite,
  /// not positive, or min_gate_m > max_gate_m.
  void Validate() const;
};

/// Status of a fire track; the values are fire_track_t's STATUS_* constants.
enum class FireTrackStatus : std::int8_t {
  kTentative = 0,  ///< seen, not yet confirmed by independent views
  kConfirmed = 1,  ///< seen by two vehicles, or one vehicle on separate passes
  kRejected = 2,   ///< judged false (operator, or investigation found nothing); never re-opens
};

/// "tentative", "confirmed" or "rejected".
std::string_view ToString(FireTrackStatus status);

/// One fire report, as the fusion takes it.
struct FireObservation {
  std::uint8_t vehicle_id = 0;    ///< reporting vehicle's receiver ID, 1..254
  std::uint16_t report_id = 0;    ///< per vehicle; a resend keeps its ID
  double detection_time_s = 0.0;  ///< mission time, server clock, s
  /// Estimated fire position (east, north), m, in the caller's local frame.
  Eigen::Vector2d position_en_m = Eigen::Vector2d::Zero();
  /// Covariance of position_en_m, (east, north), m^2; includes the vehicle's GPS error.
  Eigen::Matrix2d covariance_en_m2 = Eigen::Matrix2d::Zero();
  /// Vehicle position at detection (east, north), m, in the same frame.
  Eigen::Vector2d observer_en_m = Eigen::Vector2d::Zero();
  double confidence = 0.0;  ///< detector's confidence, [0, 1]

  friend bool operator==(const FireObservation&, const FireObservation&) = default;
};

/// `report` in `frame`: positions projected to local metres, the covariance
/// built from sigma_north_m, sigma_east_m and correlation. `detection_time_s`
/// is the detection time on the server's mission clock (the report's time_ms
/// is the vehicle's clock; the caller maps it).
FireObservation ObservationFromReport(const radio::FireReport& report,
                                      const common::LocalFrame& frame, double detection_time_s);

/// One vehicle's evidence on a track: the information-weighted sum of the
/// independent parts of its reports (the error model above), in fixed memory
/// however many reports it sent. Summed in arrival order, so a track restored
/// from its evidence gets bit-identical numbers.
struct VehicleEvidence {
  std::uint8_t vehicle_id = 0;
  std::int32_t report_count = 0;  ///< this vehicle's reports on the track
  /// Sum of N^-1 over its reports (N: a report's independent covariance), 1/m^2.
  Eigen::Matrix2d information_en = Eigen::Matrix2d::Zero();
  /// Sum of N^-1 z over its reports (z: the report's position), 1/m.
  Eigen::Vector2d information_vector_en = Eigen::Vector2d::Zero();

  friend bool operator==(const VehicleEvidence&, const VehicleEvidence&) = default;
};

/// A track keeps its latest this many reports (for confirmation by separate
/// passes and for the record); its estimate comes from every report it absorbed
/// through its VehicleEvidence, so a fire reported for days keeps a fixed size.
inline constexpr std::size_t kKeptReportsPerTrack = 64;

/// The duplicate check remembers each vehicle's latest this many report IDs (6
/// bytes each: at most 6 KiB per vehicle). A vehicle
/// re-sends only reports it still holds, at most
/// radio::VehicleEndpointConfig::max_queued_reports (256) of its latest, so an
/// older ID can come again only as a new report after the 16-bit ID wrapped
/// (65,536 reports on): then it is fused, not dropped as a resend.
inline constexpr std::size_t kRememberedReportsPerVehicle = 1'024;

/// One fire track: the plain state the journal persists and FireFusion::Restore
/// takes back. Fields are compatible with lcmtypes/fire_track_t.lcm (times here
/// are mission seconds; the LCM adapter converts to utime and lat/lon).
struct FireTrack {
  std::int32_t track_id = 0;  ///< unique, increasing in creation order, never reused
  FireTrackStatus status = FireTrackStatus::kTentative;
  /// Fused fire position (east, north), m, local frame.
  Eigen::Vector2d position_en_m = Eigen::Vector2d::Zero();
  /// Covariance of position_en_m, (east, north), m^2.
  Eigen::Matrix2d covariance_en_m2 = Eigen::Matrix2d::Zero();
  std::int32_t report_count = 0;          ///< reports absorbed, all of them
  std::vector<std::uint8_t> vehicle_ids;  ///< distinct reporting vehicles, ascending
  double first_seen_s = 0.0;              ///< earliest detection time, s
  double last_seen_s = 0.0;               ///< latest detection time, s
  double max_confidence = 0.0;            ///< highest report confidence, [0, 1]
  /// Per reporting vehicle, ascending by vehicle_id: position_en_m,
  /// covariance_en_m2 and vehicle_ids are computed from these.
  std::vector<VehicleEvidence> evidence;
  /// The latest kKeptReportsPerTrack reports absorbed, in arrival order.
  std::vector<FireObservation> reports;

  friend bool operator==(const FireTrack&, const FireTrack&) = default;
};

/// A report the duplicate check remembers: (vehicle, report ID) and its track.
struct SeenReport {
  std::uint8_t vehicle_id = 0;
  std::uint16_t report_id = 0;
  std::int32_t track_id = 0;
  friend bool operator==(const SeenReport&, const SeenReport&) = default;
};

/// Everything a FireFusion holds, as plain data: what a journal snapshot keeps
/// (FireFusion::state, FireFusion::Restore).
struct FireFusionState {
  std::vector<FireTrack> tracks;  ///< ascending track_id
  std::int32_t next_track_id = 1;
  /// Per vehicle (ascending) its remembered reports, oldest first.
  std::vector<SeenReport> seen;
  friend bool operator==(const FireFusionState&, const FireFusionState&) = default;
};

/// What FireFusion::Add did with a report.
enum class FireReportOutcome : std::uint8_t {
  kNewTrack,   ///< started a new tentative track
  kUpdated,    ///< fused into an existing active track (its status unchanged)
  kConfirmed,  ///< fused into a tentative track, which it confirmed
  kAbsorbed,   ///< fell into a rejected track's gate: counted there, nothing re-opened
  kDuplicate,  ///< same vehicle and report ID seen before (a radio resend): ignored
  kInvalid,    ///< not finite, or vehicle ID 0 or 255: ignored
};

/// "new_track", "updated", "confirmed", "absorbed", "duplicate" or "invalid".
std::string_view ToString(FireReportOutcome outcome);

/// The outcome and the track that now holds the report (for kDuplicate the
/// track that got the first copy; 0 for kInvalid). Every outcome but kInvalid
/// means the server has the report and may acknowledge it.
struct FireReportResult {
  FireReportOutcome outcome = FireReportOutcome::kInvalid;
  std::int32_t track_id = 0;
  friend bool operator==(const FireReportResult&, const FireReportResult&) = default;
};

/// Fuses fire reports from every vehicle into fire tracks.
///
/// Association: a report goes to the track (of any status) with the smallest
/// squared Mahalanobis distance among those whose gate it falls in (see
/// FireFusionConfig: chi-square gate, widened to min_gate_m, capped at
/// max_gate_m), ties to the lower track ID; in no gate, it starts a new track.
/// A report in a rejected track's gate is absorbed there, so a hot rock once
/// rejected is not reported again. Tracks are never merged or deleted. Memory:
/// a track's size is fixed by its reporting vehicles (kKeptReportsPerTrack
/// reports and one VehicleEvidence each), the duplicate check's by the vehicles
/// (kRememberedReportsPerVehicle each); the track count grows only with fires.
class FireFusion {
 public:
  /// An empty fusion; the first track gets ID 1. Throws as FireFusionConfig::Validate.
  explicit FireFusion(FireFusionConfig config = {});

  /// The fusion as it was when `state` was taken (state()). Each track's
  /// position, covariance and vehicle_ids are recomputed from its evidence; the
  /// other fields are taken as saved (a tentative track its kept reports confirm
  /// becomes confirmed). Throws std::invalid_argument as the constructor, and
  /// naming the track or report when track IDs are not positive and unique,
  /// next_track_id is not above every track ID, a status is unknown, a track
  /// has no evidence, evidence of an invalid or repeated vehicle, counts that do
  /// not add up to report_count, more than kKeptReportsPerTrack reports or an
  /// invalid one, first/last seen times that are not finite or do not span
  /// its reports; or a remembered report names no track, comes twice, or a
  /// vehicle has more than kRememberedReportsPerVehicle.
  static FireFusion Restore(FireFusionConfig config, FireFusionState state);

  /// Everything this fusion holds; Restore(config(), state()) behaves the same.
  FireFusionState state() const;

  /// Fuses one report. Idempotent for resends (kDuplicate changes nothing): a
  /// (vehicle, report ID) pair among the vehicle's latest
  /// kRememberedReportsPerVehicle is a resend. Reports may arrive out of
  /// detection-time order.
  FireReportResult Add(const FireObservation& report);

  /// Marks a track rejected (operator, or an investigation found nothing); it
  /// never re-opens. Returns false when no track has this ID; rejecting a
  /// rejected track again is a no-op that returns true.
  bool Reject(std::int32_t track_id);

  /// Every track, ascending by track_id.
  const std::vector<FireTrack>& tracks() const { return tracks_; }
  /// The track with this ID, nullptr when there is none.
  const FireTrack* Find(std::int32_t track_id) const;
  /// The ID the next new track will get.
  std::int32_t next_track_id() const { return next_track_id_; }
  const FireFusionConfig& config() const { return config_; }

 private:
  // One vehicle's remembered report IDs: a ring of the latest
  // kRememberedReportsPerVehicle with their tracks, searched from end to end
  // (a scan of at most 2 KiB per report).
  struct Remembered {
    std::vector<std::uint16_t> ids;    // ring, oldest at `next` once full
    std::vector<std::int32_t> tracks;  // the track of ids[i]
    std::size_t next = 0;              // the slot the next ID goes to once full
    // The track of `id` when it is remembered.
    std::optional<std::int32_t> TrackOf(std::uint16_t id) const;
  };

  FireTrack* FindMutable(std::int32_t track_id);
  std::optional<std::size_t> Associate(const FireObservation& report) const;
  // Remembers `vehicle`'s `report_id` as absorbed into `track_id`, forgetting the
  // vehicle's oldest beyond kRememberedReportsPerVehicle.
  void Remember(std::uint8_t vehicle, std::uint16_t report_id, std::int32_t track_id);

  FireFusionConfig config_;
  std::vector<FireTrack> tracks_;  // ascending track_id (creation order)
  std::int32_t next_track_id_ = 1;
  std::map<std::uint8_t, Remembered> seen_;  // per vehicle
};

}  // namespace fireswarm::server
