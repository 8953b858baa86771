// Fire-report fusion: see fire_fusion.hpp for the error model (per-vehicle GPS
// bias plus independent per-report error) and why it was chosen.
#include "fireswarm/server/fire_fusion.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <map>
#include <stdexcept>
#include <string>

#include "fireswarm/common/north_east.hpp"

namespace fireswarm::server {
namespace {

// Receiver IDs that are not vehicles: the server and broadcast.
constexpr std::uint8_t kServerId = 0;
constexpr std::uint8_t kBroadcastId = 255;

bool AllFinite(const FireObservation& report) {
  return std::isfinite(report.detection_time_s) && report.position_en_m.allFinite() &&
         report.covariance_en_m2.allFinite() && report.observer_en_m.allFinite() &&
         std::isfinite(report.confidence);
}

bool IsValid(const FireObservation& report) {
  return report.vehicle_id != kServerId && report.vehicle_id != kBroadcastId && AllFinite(report);
}

// The symmetric part of `m_en` with its eigenvalues raised to at least `floor_m2`:
// the nearest (in the eigenvalues) symmetric matrix that is safely positive definite.
// Solved in (north, east) order, the order fusion was written in: Eigen's eigen
// solver is not symmetric in the axes to the last bit (39 % of random covariances
// come out different in the last bit in the other order), and such a bit moves a
// fused position and with it a whole simulated mission.
Eigen::Matrix2d WithEigenvalueFloor(const Eigen::Matrix2d& m_en, double floor_m2) {
  const Eigen::Matrix2d m = common::SwapAxes(m_en);
  const Eigen::Matrix2d symmetric = 0.5 * (m + m.transpose());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(symmetric);
  const Eigen::Vector2d clamped = solver.eigenvalues().cwiseMax(floor_m2);
  return common::SwapAxes(Eigen::Matrix2d(solver.eigenvectors() * clamped.asDiagonal() *
                                          solver.eigenvectors().transpose()));
}

double Squared(double x) {
  return x * x;
}

Eigen::Matrix2d BiasCovariance(const FireFusionConfig& config) {
  return Squared(config.vehicle_bias_sigma_m) * Eigen::Matrix2d::Identity();
}

// The part of a report's error that is independent from the vehicle's other
// reports: its covariance less the vehicle bias, kept positive definite. A
// report claiming less than the bias is thereby treated as bias + floor.
Eigen::Matrix2d IndependentCovariance(const FireObservation& report,
                                      const FireFusionConfig& config) {
  const Eigen::Matrix2d regularised =
      WithEigenvalueFloor(report.covariance_en_m2, Squared(config.min_report_sigma_m));
  return WithEigenvalueFloor(regularised - BiasCovariance(config),
                             Squared(config.min_independent_sigma_m));
}

struct Estimate {
  Eigen::Vector2d position_en_m = Eigen::Vector2d::Zero();
  Eigen::Matrix2d covariance_en_m2 = Eigen::Matrix2d::Zero();
};

// Fusion of a track's evidence, always in a fixed order (vehicles ascending),
// so that a track restored from its evidence gets bit-identical numbers. Each
// vehicle's evidence is the information sum of its reports' independent parts
// (Absorb); here each vehicle's estimate carries its bias once, and vehicles
// are fused as independent.
Estimate FuseEvidence(const std::vector<VehicleEvidence>& evidence,
                      const FireFusionConfig& config) {
  const Eigen::Matrix2d bias = BiasCovariance(config);
  Eigen::Matrix2d total_information = Eigen::Matrix2d::Zero();  // 1/m^2
  Eigen::Vector2d total_vector = Eigen::Vector2d::Zero();       // 1/m
  for (const VehicleEvidence& vehicle : evidence) {
    const Eigen::Matrix2d independent = vehicle.information_en.inverse();
    const Eigen::Vector2d position = independent * vehicle.information_vector_en;
    const Eigen::Matrix2d information = (independent + bias).inverse();
    total_information += information;
    total_vector += information * position;
  }
  Estimate estimate;
  estimate.covariance_en_m2 = total_information.inverse();
  estimate.position_en_m = estimate.covariance_en_m2 * total_vector;
  // Symmetric by construction up to rounding; meant to be made exactly so for
  // consumers. Eigen evaluates `m = 0.5 * (m + m.transpose())` in place, column
  // by column, so the (0, 1) element is averaged with the (1, 0) one already
  // replaced: the two may still differ in the last bits. Done in (north, east)
  // order, as fusion was written, so every covariance stays as it was to the bit.
  Eigen::Matrix2d covariance_ne_m2 = common::SwapAxes(estimate.covariance_en_m2);
  covariance_ne_m2 = 0.5 * (covariance_ne_m2 + covariance_ne_m2.transpose());
  estimate.covariance_en_m2 = common::SwapAxes(covariance_ne_m2);
  return estimate;
}

// Recomputes a track's position, covariance and vehicles from its evidence.
void UpdateEstimate(FireTrack& track, const FireFusionConfig& config) {
  const Estimate estimate = FuseEvidence(track.evidence, config);
  track.position_en_m = estimate.position_en_m;
  track.covariance_en_m2 = estimate.covariance_en_m2;
  track.vehicle_ids.clear();
  for (const VehicleEvidence& e : track.evidence) track.vehicle_ids.push_back(e.vehicle_id);
}

// Adds `report` to `track`: its vehicle's evidence, the counts and times, the
// kept reports; then the estimate.
void Absorb(FireTrack& track, const FireObservation& report, const FireFusionConfig& config) {
  auto vehicle =
      std::lower_bound(track.evidence.begin(), track.evidence.end(), report.vehicle_id,
                       [](const VehicleEvidence& e, std::uint8_t id) { return e.vehicle_id < id; });
  if (vehicle == track.evidence.end() || vehicle->vehicle_id != report.vehicle_id) {
    VehicleEvidence first;  // zero sums
    first.vehicle_id = report.vehicle_id;
    vehicle = track.evidence.insert(vehicle, first);
  }
  VehicleEvidence& evidence = *vehicle;
  const Eigen::Matrix2d information = IndependentCovariance(report, config).inverse();
  evidence.information_en += information;
  evidence.information_vector_en += information * report.position_en_m;
  ++evidence.report_count;
  if (track.report_count == 0) {
    track.first_seen_s = report.detection_time_s;
    track.last_seen_s = report.detection_time_s;
    track.max_confidence = report.confidence;
  } else {
    track.first_seen_s = std::min(track.first_seen_s, report.detection_time_s);
    track.last_seen_s = std::max(track.last_seen_s, report.detection_time_s);
    track.max_confidence = std::max(track.max_confidence, report.confidence);
  }
  ++track.report_count;
  track.reports.push_back(report);
  if (track.reports.size() > kKeptReportsPerTrack) track.reports.erase(track.reports.begin());
  UpdateEstimate(track, config);
}

// Two reports are independent views when two vehicles made them, or one
// vehicle on separate passes (apart both in observer position and in time).
bool IndependentViews(const FireObservation& a, const FireObservation& b,
                      const FireFusionConfig& config) {
  if (a.vehicle_id != b.vehicle_id) return true;
  return (a.observer_en_m - b.observer_en_m).norm() >= config.min_pass_separation_m &&
         std::abs(a.detection_time_s - b.detection_time_s) >= config.min_pass_interval_s;
}

// True when reports[index] and some other report are independent views.
bool ConfirmsWithOthers(const std::vector<FireObservation>& reports, std::size_t index,
                        const FireFusionConfig& config) {
  for (std::size_t other = 0; other < reports.size(); ++other) {
    if (other != index && IndependentViews(reports[index], reports[other], config)) return true;
  }
  return false;
}

bool HasIndependentViews(const std::vector<FireObservation>& reports,
                         const FireFusionConfig& config) {
  for (std::size_t index = 0; index < reports.size(); ++index) {
    if (ConfirmsWithOthers(reports, index, config)) return true;
  }
  return false;
}

void RequireFinitePositive(double value, const char* field) {
  if (!std::isfinite(value) || value <= 0.0) {
    throw std::invalid_argument(std::string("FireFusionConfig.") + field +
                                " must be finite and positive, got " + std::to_string(value));
  }
}

bool IsKnownStatus(FireTrackStatus status) {
  return status == FireTrackStatus::kTentative || status == FireTrackStatus::kConfirmed ||
         status == FireTrackStatus::kRejected;
}

[[noreturn]] void ThrowRestore(std::int32_t track_id, const std::string& problem) {
  throw std::invalid_argument("FireFusion::Restore: track " + std::to_string(track_id) + ": " +
                              problem);
}

}  // namespace

void FireFusionConfig::Validate() const {
  RequireFinitePositive(gate_chi_square, "gate_chi_square");
  RequireFinitePositive(min_gate_m, "min_gate_m");
  RequireFinitePositive(max_gate_m, "max_gate_m");
  RequireFinitePositive(vehicle_bias_sigma_m, "vehicle_bias_sigma_m");
  RequireFinitePositive(min_independent_sigma_m, "min_independent_sigma_m");
  RequireFinitePositive(min_report_sigma_m, "min_report_sigma_m");
  RequireFinitePositive(min_pass_separation_m, "min_pass_separation_m");
  RequireFinitePositive(min_pass_interval_s, "min_pass_interval_s");
  if (min_gate_m > max_gate_m) {
    throw std::invalid_argument("FireFusionConfig.min_gate_m (" + std::to_string(min_gate_m) +
                                ") must not exceed max_gate_m (" + std::to_string(max_gate_m) +
                                ")");
  }
}

std::string_view ToString(FireTrackStatus status) {
  switch (status) {
    case FireTrackStatus::kTentative:
      return "tentative";
    case FireTrackStatus::kConfirmed:
      return "confirmed";
    case FireTrackStatus::kRejected:
      return "rejected";
  }
  return "unknown";
}

std::string_view ToString(FireReportOutcome outcome) {
  switch (outcome) {
    case FireReportOutcome::kNewTrack:
      return "new_track";
    case FireReportOutcome::kUpdated:
      return "updated";
    case FireReportOutcome::kConfirmed:
      return "confirmed";
    case FireReportOutcome::kAbsorbed:
      return "absorbed";
    case FireReportOutcome::kDuplicate:
      return "duplicate";
    case FireReportOutcome::kInvalid:
      return "invalid";
  }
  return "unknown";
}

FireObservation ObservationFromReport(const radio::FireReport& report,
                                      const common::LocalFrame& frame, double detection_time_s) {
  const common::EastNorth fire = frame.ToLocal({report.lat_deg, report.lon_deg});
  const common::EastNorth observer =
      frame.ToLocal({report.observer_lat_deg, report.observer_lon_deg});
  const double cross_m2 = report.correlation * report.sigma_north_m * report.sigma_east_m;
  FireObservation observation;
  observation.vehicle_id = report.header.sender;
  observation.report_id = report.report_id;
  observation.detection_time_s = detection_time_s;
  observation.position_en_m = Eigen::Vector2d(fire.east_m, fire.north_m);
  observation.covariance_en_m2 << Squared(report.sigma_east_m), cross_m2, cross_m2,
      Squared(report.sigma_north_m);
  observation.observer_en_m = Eigen::Vector2d(observer.east_m, observer.north_m);
  observation.confidence = report.confidence;
  return observation;
}

FireFusion::FireFusion(FireFusionConfig config) : config_(config) {
  config_.Validate();
}

namespace {

// The checks of FireFusion::Restore on one track, before its estimate is
// recomputed from its evidence.
void CheckRestoredTrack(const FireTrack& track, std::int32_t next_track_id) {
  if (track.track_id <= 0) ThrowRestore(track.track_id, "track_id must be positive");
  if (track.track_id >= next_track_id) {
    ThrowRestore(track.track_id,
                 "track_id not below next_track_id " + std::to_string(next_track_id));
  }
  if (!IsKnownStatus(track.status)) ThrowRestore(track.track_id, "unknown status");
  if (track.evidence.empty()) ThrowRestore(track.track_id, "no evidence");
  std::int64_t counted = 0;
  for (std::size_t i = 0; i < track.evidence.size(); ++i) {
    const VehicleEvidence& e = track.evidence[i];
    const std::string vehicle = "evidence of vehicle " + std::to_string(e.vehicle_id);
    if (e.vehicle_id == kServerId || e.vehicle_id == kBroadcastId) {
      ThrowRestore(track.track_id, vehicle + ": not a vehicle ID");
    }
    if (i > 0 && e.vehicle_id <= track.evidence[i - 1].vehicle_id) {
      ThrowRestore(track.track_id, vehicle + ": vehicles must ascend, once each");
    }
    if (e.report_count <= 0) {
      ThrowRestore(track.track_id, vehicle + ": report_count must be positive");
    }
    if (!e.information_en.allFinite() || !e.information_vector_en.allFinite() ||
        e.information_en.determinant() <= 0.0 || e.information_en.trace() <= 0.0) {
      ThrowRestore(track.track_id, vehicle + ": information not finite and positive definite");
    }
    counted += e.report_count;
  }
  if (counted != track.report_count) {
    ThrowRestore(track.track_id, "report_count " + std::to_string(track.report_count) +
                                     " is not the evidence's " + std::to_string(counted));
  }
  if (track.reports.empty() || track.reports.size() > kKeptReportsPerTrack ||
      track.reports.size() > static_cast<std::size_t>(track.report_count)) {
    ThrowRestore(track.track_id, "keeps " + std::to_string(track.reports.size()) +
                                     " reports: 1 to min(report_count, " +
                                     std::to_string(kKeptReportsPerTrack) + ") expected");
  }
  if (!std::isfinite(track.first_seen_s) || !std::isfinite(track.last_seen_s) ||
      !std::isfinite(track.max_confidence)) {
    ThrowRestore(track.track_id, "first_seen_s, last_seen_s or max_confidence not finite");
  }
  for (const FireObservation& report : track.reports) {
    const std::string which = "report " + std::to_string(report.report_id) + " of vehicle " +
                              std::to_string(report.vehicle_id);
    if (!IsValid(report)) ThrowRestore(track.track_id, "invalid " + which);
    if (report.detection_time_s < track.first_seen_s ||
        report.detection_time_s > track.last_seen_s) {
      ThrowRestore(track.track_id, which + ": detected outside first_seen_s..last_seen_s");
    }
  }
}

}  // namespace

FireFusion FireFusion::Restore(FireFusionConfig config, FireFusionState state) {
  FireFusion fusion(config);
  if (state.next_track_id <= 0) {
    throw std::invalid_argument("FireFusion::Restore: next_track_id must be positive, got " +
                                std::to_string(state.next_track_id));
  }
  std::vector<FireTrack>& tracks = state.tracks;
  std::sort(tracks.begin(), tracks.end(),
            [](const FireTrack& a, const FireTrack& b) { return a.track_id < b.track_id; });
  for (std::size_t i = 0; i < tracks.size(); ++i) {
    FireTrack& track = tracks[i];
    if (i > 0 && tracks[i - 1].track_id == track.track_id) {
      ThrowRestore(track.track_id, "duplicate track_id");
    }
    CheckRestoredTrack(track, state.next_track_id);
    UpdateEstimate(track, fusion.config_);
    if (track.status == FireTrackStatus::kTentative &&
        HasIndependentViews(track.reports, fusion.config_)) {
      track.status = FireTrackStatus::kConfirmed;
    }
  }
  fusion.tracks_ = std::move(tracks);
  fusion.next_track_id_ = state.next_track_id;
  std::map<std::uint8_t, std::size_t> remembered;  // per vehicle
  for (const SeenReport& seen : state.seen) {
    const std::string which = "FireFusion::Restore: remembered report " +
                              std::to_string(seen.report_id) + " of vehicle " +
                              std::to_string(seen.vehicle_id);
    if (fusion.Find(seen.track_id) == nullptr) {
      throw std::invalid_argument(which + ": no track " + std::to_string(seen.track_id));
    }
    if (const auto vehicle = fusion.seen_.find(seen.vehicle_id);
        vehicle != fusion.seen_.end() && vehicle->second.TrackOf(seen.report_id)) {
      throw std::invalid_argument(which + ": appears twice");
    }
    if (++remembered[seen.vehicle_id] > kRememberedReportsPerVehicle) {
      throw std::invalid_argument(which + ": the vehicle has more than " +
                                  std::to_string(kRememberedReportsPerVehicle));
    }
    fusion.Remember(seen.vehicle_id, seen.report_id, seen.track_id);
  }
  return fusion;
}

FireFusionState FireFusion::state() const {
  FireFusionState state;
  state.tracks = tracks_;
  state.next_track_id = next_track_id_;
  for (const auto& [vehicle, remembered] : seen_) {
    const std::size_t count = remembered.ids.size();
    const std::size_t oldest = count < kRememberedReportsPerVehicle ? 0 : remembered.next;
    for (std::size_t i = 0; i < count; ++i) {
      const std::size_t slot = (oldest + i) % count;
      state.seen.push_back({vehicle, remembered.ids[slot], remembered.tracks[slot]});
    }
  }
  return state;
}

std::optional<std::int32_t> FireFusion::Remembered::TrackOf(std::uint16_t id) const {
  const auto at = std::find(ids.begin(), ids.end(), id);
  if (at == ids.end()) return std::nullopt;
  return tracks[static_cast<std::size_t>(at - ids.begin())];
}

void FireFusion::Remember(std::uint8_t vehicle, std::uint16_t report_id, std::int32_t track_id) {
  Remembered& r = seen_[vehicle];
  if (r.ids.size() < kRememberedReportsPerVehicle) {
    r.ids.push_back(report_id);
    r.tracks.push_back(track_id);
    return;
  }
  r.ids[r.next] = report_id;  // forgets the oldest
  r.tracks[r.next] = track_id;
  r.next = (r.next + 1) % kRememberedReportsPerVehicle;
}

FireReportResult FireFusion::Add(const FireObservation& report) {
  if (!IsValid(report)) return {FireReportOutcome::kInvalid, 0};
  if (const auto seen = seen_.find(report.vehicle_id); seen != seen_.end()) {
    if (const std::optional<std::int32_t> track = seen->second.TrackOf(report.report_id)) {
      return {FireReportOutcome::kDuplicate, *track};
    }
  }

  const std::optional<std::size_t> index = Associate(report);
  if (!index) {
    FireTrack track;
    track.track_id = next_track_id_++;
    track.status = FireTrackStatus::kTentative;
    Absorb(track, report, config_);
    Remember(report.vehicle_id, report.report_id, track.track_id);
    tracks_.push_back(std::move(track));
    return {FireReportOutcome::kNewTrack, tracks_.back().track_id};
  }

  FireTrack& track = tracks_[*index];
  Absorb(track, report, config_);
  Remember(report.vehicle_id, report.report_id, track.track_id);
  switch (track.status) {
    case FireTrackStatus::kRejected:
      return {FireReportOutcome::kAbsorbed, track.track_id};
    case FireTrackStatus::kTentative:
      if (ConfirmsWithOthers(track.reports, track.reports.size() - 1, config_)) {
        track.status = FireTrackStatus::kConfirmed;
        return {FireReportOutcome::kConfirmed, track.track_id};
      }
      break;
    case FireTrackStatus::kConfirmed:
      break;
  }
  return {FireReportOutcome::kUpdated, track.track_id};
}

std::optional<std::size_t> FireFusion::Associate(const FireObservation& report) const {
  // The report's covariance as its own track would have it (bias included).
  const Eigen::Matrix2d report_covariance =
      IndependentCovariance(report, config_) + BiasCovariance(config_);
  std::optional<std::size_t> best;
  double best_distance2 = 0.0;
  for (std::size_t i = 0; i < tracks_.size(); ++i) {
    const FireTrack& track = tracks_[i];
    const Eigen::Vector2d innovation = report.position_en_m - track.position_en_m;
    const double distance_m = innovation.norm();
    if (distance_m > config_.max_gate_m) continue;
    const Eigen::Matrix2d innovation_covariance = track.covariance_en_m2 + report_covariance;
    const double mahalanobis2 = innovation.dot(innovation_covariance.inverse() * innovation);
    if (mahalanobis2 > config_.gate_chi_square && distance_m > config_.min_gate_m) continue;
    // Strictly smaller: ties go to the lower track ID (tracks_ is ascending).
    if (!best || mahalanobis2 < best_distance2) {
      best = i;
      best_distance2 = mahalanobis2;
    }
  }
  return best;
}

bool FireFusion::Reject(std::int32_t track_id) {
  FireTrack* track = FindMutable(track_id);
  if (track == nullptr) return false;
  track->status = FireTrackStatus::kRejected;
  return true;
}

const FireTrack* FireFusion::Find(std::int32_t track_id) const {
  const auto it =
      std::lower_bound(tracks_.begin(), tracks_.end(), track_id,
                       [](const FireTrack& track, std::int32_t id) { return track.track_id < id; });
  return it != tracks_.end() && it->track_id == track_id ? &*it : nullptr;
}

FireTrack* FireFusion::FindMutable(std::int32_t track_id) {
  return const_cast<FireTrack*>(std::as_const(*this).Find(track_id));
}

}  // namespace fireswarm::server
