// FireFusion: association and gating, confirmation by independent views,
// rejection, idempotent resends, the per-vehicle bias guard against
// double-counting (with a Monte-Carlo consistency check against a naive
// fusion), restoring from a snapshot, and a track's and the duplicate check's
// fixed size however many reports come.
#include "fireswarm/server/fire_fusion.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "fireswarm/fire_track_t.hpp"

namespace fireswarm::server {
namespace {

constexpr double kReportSigmaM = 3.0;  // 1-sigma per axis of a typical report
constexpr double kTightM = 1e-9;       // numerical agreement

// A report of `vehicle` at (north, east) seen from (observer_north, observer_east).
FireObservation Report(int vehicle, int report_id, double time_s, double north_m, double east_m,
                       double observer_north_m = 0.0, double observer_east_m = 0.0,
                       double sigma_m = kReportSigmaM) {
  FireObservation report;
  report.vehicle_id = static_cast<std::uint8_t>(vehicle);
  report.report_id = static_cast<std::uint16_t>(report_id);
  report.detection_time_s = time_s;
  report.position_en_m = Eigen::Vector2d(east_m, north_m);
  report.covariance_en_m2 = sigma_m * sigma_m * Eigen::Matrix2d::Identity();
  report.observer_en_m = Eigen::Vector2d(observer_east_m, observer_north_m);
  report.confidence = 0.8;
  return report;
}

double MinEigenvalue(const Eigen::Matrix2d& m) {
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(m).eigenvalues().minCoeff();
}
double MaxEigenvalue(const Eigen::Matrix2d& m) {
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(m).eigenvalues().maxCoeff();
}

TEST(FireFusion, SingleReportStartsTentativeTrackAtTheReport) {
  FireFusion fusion;
  const FireObservation report = Report(3, 7, 12.5, 40.0, -20.0);
  const FireReportResult result = fusion.Add(report);

  EXPECT_EQ(result.outcome, FireReportOutcome::kNewTrack);
  EXPECT_EQ(result.track_id, 1);
  ASSERT_EQ(fusion.tracks().size(), 1U);
  const FireTrack& track = fusion.tracks().front();
  EXPECT_EQ(track.track_id, 1);
  EXPECT_EQ(track.status, FireTrackStatus::kTentative);
  EXPECT_NEAR((track.position_en_m - report.position_en_m).norm(), 0.0, kTightM);
  // A report wider than the vehicle bias keeps its own covariance.
  EXPECT_NEAR((track.covariance_en_m2 - report.covariance_en_m2).norm(), 0.0, kTightM);
  EXPECT_EQ(track.report_count, 1);
  EXPECT_EQ(track.vehicle_ids, std::vector<std::uint8_t>{3});
  EXPECT_DOUBLE_EQ(track.first_seen_s, 12.5);
  EXPECT_DOUBLE_EQ(track.last_seen_s, 12.5);
  EXPECT_DOUBLE_EQ(track.max_confidence, 0.8);
  EXPECT_EQ(fusion.next_track_id(), 2);
}

TEST(FireFusion, SecondDroneConfirmsTrack) {
  FireFusion fusion;
  fusion.Add(Report(1, 1, 10.0, 0.0, 0.0));
  const FireReportResult second = fusion.Add(Report(2, 1, 11.0, 2.0, 1.0, 80.0, 80.0));

  EXPECT_EQ(second.outcome, FireReportOutcome::kConfirmed);
  EXPECT_EQ(second.track_id, 1);
  ASSERT_EQ(fusion.tracks().size(), 1U);
  const FireTrack& track = fusion.tracks().front();
  EXPECT_EQ(track.status, FireTrackStatus::kConfirmed);
  EXPECT_EQ(track.vehicle_ids, (std::vector<std::uint8_t>{1, 2}));
  EXPECT_EQ(track.report_count, 2);
  // Two equal covariances: the fused position is the midpoint.
  EXPECT_NEAR(track.position_en_m.x(), 0.5, kTightM);  // east
  EXPECT_NEAR(track.position_en_m.y(), 1.0, kTightM);  // north
  // A further report keeps it confirmed.
  EXPECT_EQ(fusion.Add(Report(1, 2, 12.0, 1.0, 0.0)).outcome, FireReportOutcome::kUpdated);
  EXPECT_EQ(fusion.tracks().front().status, FireTrackStatus::kConfirmed);
}

TEST(FireFusion, SameDroneSamePassStaysTentative) {
  const FireFusionConfig config;
  FireFusion fusion(config);
  fusion.Add(Report(1, 1, 100.0, 0.0, 0.0, 0.0, 0.0));
  // Close in time and place: the same pass.
  EXPECT_EQ(fusion.Add(Report(1, 2, 105.0, 1.0, 0.0, 10.0, 0.0)).outcome,
            FireReportOutcome::kUpdated);
  ASSERT_EQ(fusion.tracks().size(), 1U);
  EXPECT_EQ(fusion.tracks().front().status, FireTrackStatus::kTentative);
  EXPECT_EQ(fusion.tracks().front().report_count, 2);
}

TEST(FireFusion, SameDroneNeedsBothDistanceAndTimeBetweenPasses) {
  const FireFusionConfig config;
  // Far in place but not in time (a fast fly-by).
  FireFusion fly_by(config);
  fly_by.Add(Report(1, 1, 100.0, 0.0, 0.0, 0.0, 0.0));
  EXPECT_EQ(fly_by
                .Add(Report(1, 2, 100.0 + 0.9 * config.min_pass_interval_s, 0.0, 1.0,
                            2.0 * config.min_pass_separation_m, 0.0))
                .outcome,
            FireReportOutcome::kUpdated);
  EXPECT_EQ(fly_by.tracks().front().status, FireTrackStatus::kTentative);

  // Late but from nearly the same place (hovering over it).
  FireFusion hover(config);
  hover.Add(Report(1, 1, 100.0, 0.0, 0.0, 0.0, 0.0));
  EXPECT_EQ(hover
                .Add(Report(1, 2, 100.0 + 3.0 * config.min_pass_interval_s, 1.0, 1.0, 0.0,
                            0.9 * config.min_pass_separation_m))
                .outcome,
            FireReportOutcome::kUpdated);
  EXPECT_EQ(hover.tracks().front().status, FireTrackStatus::kTentative);
}

TEST(FireFusion, SameDroneSeparatedPassConfirms) {
  const FireFusionConfig config;
  FireFusion fusion(config);
  fusion.Add(Report(4, 1, 100.0, 0.0, 0.0, 0.0, -30.0));
  const FireReportResult next_lane =
      fusion.Add(Report(4, 2, 100.0 + config.min_pass_interval_s + 1.0, 1.0, -1.0,
                        config.min_pass_separation_m + 1.0, -30.0));
  EXPECT_EQ(next_lane.outcome, FireReportOutcome::kConfirmed);
  EXPECT_EQ(fusion.tracks().front().status, FireTrackStatus::kConfirmed);
  EXPECT_EQ(fusion.tracks().front().vehicle_ids, std::vector<std::uint8_t>{4});
}

TEST(FireFusion, TwoFiresSixtyMetresApartStayTwoTracks) {
  FireFusion fusion;
  constexpr double kSeparationM = 60.0;
  int report_id = 0;
  for (int vehicle = 1; vehicle <= 3; ++vehicle) {
    const double offset_m = 1.5 * (vehicle - 2);  // each vehicle a little off
    fusion.Add(Report(vehicle, ++report_id, 10.0 * vehicle, offset_m, -offset_m));
    fusion.Add(
        Report(vehicle, ++report_id, 10.0 * vehicle + 1.0, kSeparationM - offset_m, offset_m));
  }
  ASSERT_EQ(fusion.tracks().size(), 2U);
  for (const FireTrack& track : fusion.tracks()) {
    EXPECT_EQ(track.report_count, 3);
    EXPECT_EQ(track.status, FireTrackStatus::kConfirmed);
  }
  EXPECT_NEAR(fusion.tracks()[0].position_en_m.norm(), 0.0, 1.0);
  EXPECT_NEAR((fusion.tracks()[1].position_en_m - Eigen::Vector2d(0.0, kSeparationM)).norm(), 0.0,
              1.0);
}

TEST(FireFusion, OutlierOutsideGateStartsItsOwnTrack) {
  FireFusion fusion;
  fusion.Add(Report(1, 1, 0.0, 0.0, 0.0));
  fusion.Add(Report(2, 1, 1.0, 0.5, 0.5));
  const Eigen::Vector2d before = fusion.tracks().front().position_en_m;

  // Beyond the minimum gate with 3 m sigmas: far outside the chi-square gate too.
  const double off_m = fusion.config().min_gate_m + 5.0;
  const FireReportResult outlier = fusion.Add(Report(3, 1, 2.0, off_m, 0.0));
  EXPECT_EQ(outlier.outcome, FireReportOutcome::kNewTrack);
  EXPECT_EQ(outlier.track_id, 2);
  EXPECT_EQ(fusion.tracks().front().position_en_m, before);  // not pulled by the outlier
  EXPECT_EQ(fusion.tracks().front().report_count, 2);
}

TEST(FireFusion, MinimumGateKeepsTinyCovariancesTogether) {
  FireFusionConfig config;
  config.min_report_sigma_m = 0.01;
  config.min_independent_sigma_m = 0.01;
  config.vehicle_bias_sigma_m = 0.01;
  FireFusion fusion(config);
  constexpr double kTinySigmaM = 0.05;
  fusion.Add(Report(1, 1, 0.0, 0.0, 0.0, 0.0, 0.0, kTinySigmaM));
  // Thousands of sigmas away, but within min_gate_m: the same fire.
  const FireReportResult near =
      fusion.Add(Report(2, 1, 1.0, 0.8 * config.min_gate_m, 0.0, 0.0, 0.0, kTinySigmaM));
  EXPECT_EQ(near.outcome, FireReportOutcome::kConfirmed);
  EXPECT_EQ(fusion.tracks().size(), 1U);
}

TEST(FireFusion, MaximumGateKeepsWideCovariancesApart) {
  FireFusion fusion;
  constexpr double kWideSigmaM = 100.0;
  fusion.Add(Report(1, 1, 0.0, 0.0, 0.0, 0.0, 0.0, kWideSigmaM));
  // Well inside the chi-square gate of such covariances, but beyond max_gate_m.
  const FireReportResult far =
      fusion.Add(Report(2, 1, 1.0, fusion.config().max_gate_m + 5.0, 0.0, 0.0, 0.0, kWideSigmaM));
  EXPECT_EQ(far.outcome, FireReportOutcome::kNewTrack);
  EXPECT_EQ(fusion.tracks().size(), 2U);
}

TEST(FireFusion, ReportJoinsTheNearestOfTwoGatedTracks) {
  FireFusion fusion;
  const double apart_m = fusion.config().min_gate_m + 10.0;
  fusion.Add(Report(1, 1, 0.0, 0.0, 0.0));
  fusion.Add(Report(1, 2, 1.0, 0.0, apart_m));
  ASSERT_EQ(fusion.tracks().size(), 2U);
  // In the minimum gate of both; nearer to the second.
  EXPECT_EQ(fusion.Add(Report(2, 1, 2.0, 0.0, apart_m / 2.0 + 2.0)).track_id, 2);
}

TEST(FireFusion, DuplicateReportIsIgnored) {
  FireFusion fusion;
  const FireObservation report = Report(5, 42, 3.0, 10.0, 10.0);
  fusion.Add(report);
  const std::vector<FireTrack> before = fusion.tracks();

  // A resend, even with slightly different content, changes nothing.
  FireObservation resend = report;
  resend.position_en_m += Eigen::Vector2d(1.0, 1.0);
  resend.detection_time_s = 9.0;
  const FireReportResult result = fusion.Add(resend);
  EXPECT_EQ(result.outcome, FireReportOutcome::kDuplicate);
  EXPECT_EQ(result.track_id, 1);
  EXPECT_EQ(fusion.tracks(), before);
  EXPECT_EQ(fusion.next_track_id(), 2);

  // The same report ID from another vehicle is another report.
  EXPECT_EQ(fusion.Add(Report(6, 42, 4.0, 10.0, 10.0)).outcome, FireReportOutcome::kConfirmed);
}

TEST(FireFusion, RejectedTrackAbsorbsReportsAndNeverReopens) {
  FireFusion fusion;
  fusion.Add(Report(1, 1, 0.0, 0.0, 0.0));
  fusion.Add(Report(2, 1, 1.0, 1.0, 0.0));
  ASSERT_EQ(fusion.tracks().front().status, FireTrackStatus::kConfirmed);
  EXPECT_TRUE(fusion.Reject(1));
  EXPECT_TRUE(fusion.Reject(1));  // again: no-op
  EXPECT_FALSE(fusion.Reject(99));

  // New reports in the gate, from a new vehicle and from a separate pass.
  const FireReportResult absorbed = fusion.Add(Report(3, 1, 100.0, 0.5, 0.5, 200.0, 0.0));
  EXPECT_EQ(absorbed.outcome, FireReportOutcome::kAbsorbed);
  EXPECT_EQ(absorbed.track_id, 1);
  EXPECT_EQ(fusion.Add(Report(1, 2, 500.0, 2.0, 2.0, -300.0, 0.0)).outcome,
            FireReportOutcome::kAbsorbed);
  ASSERT_EQ(fusion.tracks().size(), 1U);
  const FireTrack& track = fusion.tracks().front();
  EXPECT_EQ(track.status, FireTrackStatus::kRejected);
  EXPECT_EQ(track.report_count, 4);
  EXPECT_EQ(track.vehicle_ids, (std::vector<std::uint8_t>{1, 2, 3}));
  EXPECT_DOUBLE_EQ(track.last_seen_s, 500.0);
}

TEST(FireFusion, RejectingATentativeTrackKeepsItRejected) {
  FireFusion fusion;
  fusion.Add(Report(1, 1, 0.0, 0.0, 0.0));
  EXPECT_TRUE(fusion.Reject(1));
  EXPECT_EQ(fusion.Add(Report(2, 1, 1.0, 0.0, 0.0)).outcome, FireReportOutcome::kAbsorbed);
  EXPECT_EQ(fusion.tracks().front().status, FireTrackStatus::kRejected);
  // Outside its gate a new fire still gets a new track.
  EXPECT_EQ(fusion.Add(Report(2, 2, 2.0, 200.0, 0.0)).outcome, FireReportOutcome::kNewTrack);
}

TEST(FireFusion, OneDroneNeverShrinksBelowItsBiasWhileThreeDronesDo) {
  const FireFusionConfig config;
  const Eigen::Matrix2d bias =
      config.vehicle_bias_sigma_m * config.vehicle_bias_sigma_m * Eigen::Matrix2d::Identity();
  constexpr int kReports = 50;

  FireFusion one_drone(config);
  for (int i = 0; i < kReports; ++i) one_drone.Add(Report(1, i, i, 0.1 * (i % 3), 0.0));
  ASSERT_EQ(one_drone.tracks().size(), 1U);
  const Eigen::Matrix2d one = one_drone.tracks().front().covariance_en_m2;
  // The double-count guard: covariance - bias stays positive semi-definite.
  EXPECT_GE(MinEigenvalue(one - bias), -kTightM);
  // A naive fusion would have reached sigma^2 / kReports, far below the bias.
  EXPECT_GT(MinEigenvalue(one), 10.0 * kReportSigmaM * kReportSigmaM / kReports);

  FireFusion three_drones(config);
  for (int vehicle = 1; vehicle <= 3; ++vehicle)
    three_drones.Add(Report(vehicle, 1, 0.0, 0.0, 0.0));
  ASSERT_EQ(three_drones.tracks().size(), 1U);
  const Eigen::Matrix2d three = three_drones.tracks().front().covariance_en_m2;
  EXPECT_LT(MaxEigenvalue(three), MinEigenvalue(bias));
  // Independent vehicles: the information adds up exactly.
  EXPECT_NEAR(MaxEigenvalue(three), kReportSigmaM * kReportSigmaM / 3.0, 1e-9);
}

// Monte Carlo with known truth: three drones, each with its own constant GPS
// bias, plus independent noise per report. The fusion's normalised estimation
// error squared (NEES) must average the state dimension (2); a naive fusion
// that treats every report as independent is overconfident and fails.
TEST(FireFusion, MonteCarloNeesIsConsistentWhereNaiveFusionIsNot) {
  constexpr int kTrials = 200;
  constexpr int kDrones = 3;
  constexpr int kReportsPerDrone = 8;
  constexpr double kBiasSigmaM = 2.5;   // per drone, per axis, constant over the trial
  constexpr double kNoiseSigmaM = 1.5;  // per report, per axis, independent
  // 99 % interval of the mean of 200 chi-square(2) draws (sum ~ chi-square(400)).
  constexpr double kNeesLow = 1.65;
  constexpr double kNeesHigh = 2.38;

  FireFusionConfig config;
  config.vehicle_bias_sigma_m = kBiasSigmaM;
  config.min_gate_m = 25.0;  // so that no trial's biases split the one fire
  std::mt19937 rng(20261121U);
  std::normal_distribution<double> unit(0.0, 1.0);
  std::uniform_real_distribution<double> place(-500.0, 500.0);
  const double report_variance = kBiasSigmaM * kBiasSigmaM + kNoiseSigmaM * kNoiseSigmaM;
  const Eigen::Matrix2d report_covariance = report_variance * Eigen::Matrix2d::Identity();

  double nees_sum = 0.0;
  double naive_nees_sum = 0.0;
  for (int trial = 0; trial < kTrials; ++trial) {
    const Eigen::Vector2d truth(place(rng), place(rng));
    FireFusion fusion(config);
    Eigen::Matrix2d naive_information = Eigen::Matrix2d::Zero();
    Eigen::Vector2d naive_vector = Eigen::Vector2d::Zero();
    for (int drone = 1; drone <= kDrones; ++drone) {
      const Eigen::Vector2d bias(kBiasSigmaM * unit(rng), kBiasSigmaM * unit(rng));
      for (int k = 0; k < kReportsPerDrone; ++k) {
        const Eigen::Vector2d noise(kNoiseSigmaM * unit(rng), kNoiseSigmaM * unit(rng));
        FireObservation report = Report(drone, k, 10.0 * k, 0.0, 0.0);
        report.position_en_m = truth + bias + noise;
        report.covariance_en_m2 = report_covariance;
        fusion.Add(report);
        naive_information += report_covariance.inverse();
        naive_vector += report_covariance.inverse() * report.position_en_m;
      }
    }
    ASSERT_EQ(fusion.tracks().size(), 1U) << "trial " << trial;
    const FireTrack& track = fusion.tracks().front();
    ASSERT_EQ(track.report_count, kDrones * kReportsPerDrone);
    const Eigen::Vector2d error = track.position_en_m - truth;
    nees_sum += error.dot(track.covariance_en_m2.inverse() * error);

    const Eigen::Matrix2d naive_covariance = naive_information.inverse();
    const Eigen::Vector2d naive_error = naive_covariance * naive_vector - truth;
    naive_nees_sum += naive_error.dot(naive_information * naive_error);
  }
  const double nees_mean = nees_sum / kTrials;
  const double naive_nees_mean = naive_nees_sum / kTrials;
  EXPECT_GT(nees_mean, kNeesLow);
  EXPECT_LT(nees_mean, kNeesHigh);
  // The naive fusion is overconfident by far (about 6x here).
  EXPECT_GT(naive_nees_mean, 2.0 * kNeesHigh);
}

// A deterministic stream of reports around a few fires, for the restore test.
std::vector<FireObservation> ReportStream(std::uint32_t seed, int first_report_id, int count,
                                          double start_s) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> fire(0, 3);
  std::uniform_int_distribution<int> vehicle(1, 4);
  std::normal_distribution<double> noise(0.0, 2.0);
  const std::vector<Eigen::Vector2d> fires = {
      {0.0, 0.0}, {80.0, 0.0}, {0.0, 150.0}, {-120.0, -90.0}};
  std::vector<FireObservation> stream;
  for (int i = 0; i < count; ++i) {
    const Eigen::Vector2d at = fires[static_cast<std::size_t>(fire(rng))];
    const double time_s = start_s + 7.0 * i;
    FireObservation report =
        Report(vehicle(rng), first_report_id + i, time_s, at.x() + noise(rng), at.y() + noise(rng),
               at.x() + 10.0 * noise(rng), at.y() + 10.0 * noise(rng), 2.5 + 0.2 * noise(rng));
    stream.push_back(report);
  }
  return stream;
}

TEST(FireFusion, RestoreFromSnapshotBehavesIdentically) {
  FireFusion original;
  for (const FireObservation& report : ReportStream(1U, 1, 12, 0.0)) original.Add(report);
  ASSERT_GE(original.tracks().size(), 2U);
  original.Reject(original.tracks()[1].track_id);

  // The journal's view. Derived fields are not trusted.
  FireFusionState snapshot = original.state();
  for (FireTrack& track : snapshot.tracks) {
    track.position_en_m.setZero();
    track.covariance_en_m2.setZero();
    track.vehicle_ids.clear();
  }
  std::reverse(snapshot.tracks.begin(), snapshot.tracks.end());  // order does not matter either
  FireFusion restored = FireFusion::Restore(original.config(), snapshot);
  EXPECT_EQ(restored.tracks(), original.tracks());
  EXPECT_EQ(restored.state(), original.state());

  // Resends of old reports plus new ones: the same results and the same tracks.
  std::vector<FireObservation> next = ReportStream(2U, 100, 30, 200.0);
  const std::vector<FireObservation> old = ReportStream(1U, 1, 12, 0.0);
  next.insert(next.begin() + 5, old.begin(), old.begin() + 4);
  int duplicates = 0;
  for (const FireObservation& report : next) {
    const FireReportResult result = original.Add(report);
    EXPECT_EQ(restored.Add(report), result);
    if (result.outcome == FireReportOutcome::kDuplicate) ++duplicates;
  }
  EXPECT_EQ(duplicates, 4);
  EXPECT_EQ(restored.state(), original.state());
  EXPECT_EQ(original.tracks()[1].status, FireTrackStatus::kRejected);
}

// A fire reported for days: the track keeps its latest kKeptReportsPerTrack
// reports, and its estimate is that of every report: three vehicles' 200 each
// shrink the independent part 200-fold, which 64 reports could not.
TEST(FireFusion, ATrackKeepsItsLatestReportsAndFusesThemAll) {
  FireFusion fusion;
  constexpr int kPerVehicle = 200;
  for (int i = 0; i < kPerVehicle; ++i) {
    for (int vehicle = 1; vehicle <= 3; ++vehicle) {
      fusion.Add(Report(vehicle, i, 10.0 * i + vehicle, 0.0, 0.0));
    }
  }
  ASSERT_EQ(fusion.tracks().size(), 1U);
  const FireTrack& track = fusion.tracks().front();
  EXPECT_EQ(track.report_count, 3 * kPerVehicle);
  ASSERT_EQ(track.reports.size(), kKeptReportsPerTrack);
  EXPECT_EQ(track.reports.back().report_id, kPerVehicle - 1);
  EXPECT_EQ(track.reports.back().vehicle_id, 3);
  EXPECT_DOUBLE_EQ(track.first_seen_s, 1.0);
  EXPECT_DOUBLE_EQ(track.last_seen_s, 10.0 * (kPerVehicle - 1) + 3);
  ASSERT_EQ(track.evidence.size(), 3U);
  for (const VehicleEvidence& e : track.evidence) EXPECT_EQ(e.report_count, kPerVehicle);
  // Per axis: each vehicle (N / n + B), three of them fused as independent.
  const FireFusionConfig& config = fusion.config();
  const double bias_m2 = config.vehicle_bias_sigma_m * config.vehicle_bias_sigma_m;
  const double independent_m2 = kReportSigmaM * kReportSigmaM - bias_m2;
  const double want_m2 = (independent_m2 / kPerVehicle + bias_m2) / 3.0;
  EXPECT_NEAR(track.covariance_en_m2(0, 0), want_m2, kTightM);
  EXPECT_NEAR(track.covariance_en_m2(1, 1), want_m2, kTightM);
  EXPECT_NEAR(track.covariance_en_m2(0, 1), 0.0, kTightM);
}

// The duplicate check remembers each vehicle's latest kRememberedReportsPerVehicle
// report IDs: a resend of one of them is dropped, and a vehicle's 16-bit report
// IDs wrapping after 65,536 reports start new reports, not resends (a server
// that remembered every ID dropped all of them).
TEST(FireFusion, TheDuplicateCheckRemembersTheLatestIdsSoWrappedIdsAreNewReports) {
  FireFusion fusion;
  constexpr int kReports = 70'000;
  int fused = 0;
  for (int i = 0; i < kReports; ++i) {
    const FireReportResult result = fusion.Add(Report(1, i % 65'536, i, 0.0, 0.0));
    if (result.outcome != FireReportOutcome::kDuplicate) ++fused;
  }
  EXPECT_EQ(fused, kReports);
  EXPECT_EQ(fusion.tracks().front().report_count, kReports);
  EXPECT_EQ(fusion.Add(Report(1, (kReports - 1) % 65'536, 0.0, 0.0, 0.0)).outcome,
            FireReportOutcome::kDuplicate);
  constexpr int kRemembered = static_cast<int>(kRememberedReportsPerVehicle);
  const FireReportResult oldest = fusion.Add(Report(1, (kReports - kRemembered) % 65'536, 0, 0, 0));
  EXPECT_EQ(oldest.outcome, FireReportOutcome::kDuplicate);
  EXPECT_EQ(oldest.track_id, 1);
  EXPECT_NE(fusion.Add(Report(1, (kReports - kRemembered - 1) % 65'536, 0, 0, 0)).outcome,
            FireReportOutcome::kDuplicate)
      << "forgotten: fused as a new report";
  EXPECT_EQ(fusion.state().seen.size(), kRememberedReportsPerVehicle);
}

// Each refusal names what is wrong.
TEST(FireFusion, RestoreRefusesInconsistentSnapshots) {
  FireFusion fusion;
  fusion.Add(Report(1, 1, 0.0, 0.0, 0.0));
  fusion.Add(Report(1, 2, 0.0, 100.0, 0.0));
  fusion.Add(Report(2, 1, 1.0, 100.0, 0.0));
  const FireFusionState good = fusion.state();
  EXPECT_NO_THROW(FireFusion::Restore({}, good));
  EXPECT_NO_THROW(FireFusion::Restore({}, FireFusionState{}));

  const auto refusal = [](const FireFusionState& state) -> std::string {
    try {
      FireFusion::Restore({}, state);
    } catch (const std::invalid_argument& e) {
      return e.what();
    }
    return "accepted";
  };
  const auto refused = [&](const std::function<void(FireFusionState&)>& spoil,
                           const std::string& why) {
    FireFusionState state = good;
    spoil(state);
    const std::string message = refusal(state);
    EXPECT_NE(message.find(why), std::string::npos) << message;
  };
  refused([](FireFusionState& s) { s.next_track_id = 2; }, "track 2: track_id not below");
  refused([](FireFusionState& s) { s.next_track_id = 0; }, "next_track_id must be positive");
  refused([](FireFusionState& s) { s.tracks[1].track_id = 1; }, "duplicate track_id");
  refused([](FireFusionState& s) { s.tracks[0].status = static_cast<FireTrackStatus>(7); },
          "unknown status");
  refused([](FireFusionState& s) { s.tracks[0].evidence.clear(); }, "track 1: no evidence");
  refused([](FireFusionState& s) { s.tracks[1].evidence[1].vehicle_id = 1; },
          "vehicle 1: vehicles must ascend");
  refused([](FireFusionState& s) { s.tracks[1].evidence[0].vehicle_id = 255; }, "not a vehicle ID");
  refused([](FireFusionState& s) { s.tracks[0].evidence[0].information_en *= -1.0; },
          "positive definite");
  refused([](FireFusionState& s) { s.tracks[0].report_count = 2; }, "report_count 2");
  refused([](FireFusionState& s) { s.tracks[0].reports.clear(); }, "keeps 0 reports");
  refused([](FireFusionState& s) { s.tracks[0].reports[0].vehicle_id = 0; }, "invalid report");
  refused([](FireFusionState& s) { s.tracks[1].last_seen_s = 0.5; }, "outside first_seen_s");
  refused([](FireFusionState& s) { s.seen[0].track_id = 9; }, "no track 9");
  refused([](FireFusionState& s) { s.seen.push_back(s.seen[0]); }, "appears twice");
}

TEST(FireFusion, RestoreConfirmsATentativeTrackItsReportsConfirm) {
  FireFusion fusion;
  fusion.Add(Report(1, 1, 0.0, 0.0, 0.0));
  fusion.Add(Report(2, 1, 1.0, 0.0, 0.0));
  FireFusionState snapshot = fusion.state();
  snapshot.tracks[0].status = FireTrackStatus::kTentative;
  const FireFusion restored = FireFusion::Restore({}, snapshot);
  EXPECT_EQ(restored.tracks()[0].status, FireTrackStatus::kConfirmed);
}

TEST(FireFusion, TrackIdsIncreaseAndFindLooksThemUp) {
  FireFusion fusion;
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(fusion.Add(Report(1, i, i, 100.0 * i, 0.0)).track_id, i + 1);
  }
  for (std::size_t i = 1; i < fusion.tracks().size(); ++i) {
    EXPECT_LT(fusion.tracks()[i - 1].track_id, fusion.tracks()[i].track_id);
  }
  ASSERT_NE(fusion.Find(3), nullptr);
  EXPECT_EQ(fusion.Find(3)->track_id, 3);
  EXPECT_EQ(fusion.Find(0), nullptr);
  EXPECT_EQ(fusion.Find(6), nullptr);
}

TEST(FireFusion, OutOfOrderReportsSpanFirstAndLastSeen) {
  FireFusion fusion;
  fusion.Add(Report(1, 1, 50.0, 0.0, 0.0));
  fusion.Add(Report(2, 1, 20.0, 0.0, 0.0));
  fusion.Add(Report(3, 1, 35.0, 0.0, 0.0));
  EXPECT_DOUBLE_EQ(fusion.tracks().front().first_seen_s, 20.0);
  EXPECT_DOUBLE_EQ(fusion.tracks().front().last_seen_s, 50.0);
}

TEST(FireFusion, InvalidReportsAreIgnored) {
  FireFusion fusion;
  FireObservation not_finite = Report(1, 1, 0.0, 0.0, 0.0);
  not_finite.position_en_m.x() = std::nan("");
  EXPECT_EQ(fusion.Add(not_finite).outcome, FireReportOutcome::kInvalid);
  EXPECT_EQ(fusion.Add(Report(0, 1, 0.0, 0.0, 0.0)).outcome, FireReportOutcome::kInvalid);
  EXPECT_EQ(fusion.Add(Report(255, 1, 0.0, 0.0, 0.0)).outcome, FireReportOutcome::kInvalid);
  EXPECT_TRUE(fusion.tracks().empty());
  // A zero covariance (sigma 0 on the wire) is regularised, not refused.
  FireObservation zero = Report(1, 2, 0.0, 0.0, 0.0);
  zero.covariance_en_m2.setZero();
  EXPECT_EQ(fusion.Add(zero).outcome, FireReportOutcome::kNewTrack);
  EXPECT_TRUE(fusion.tracks().front().covariance_en_m2.allFinite());
  EXPECT_GT(MinEigenvalue(fusion.tracks().front().covariance_en_m2), 0.0);
}

TEST(FireFusion, ConfigValidateNamesTheBadField) {
  FireFusionConfig config;
  EXPECT_NO_THROW(config.Validate());
  config.min_gate_m = config.max_gate_m + 1.0;
  EXPECT_THROW(FireFusion{config}, std::invalid_argument);
  config = {};
  config.vehicle_bias_sigma_m = -1.0;
  try {
    config.Validate();
    ADD_FAILURE() << "no throw";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("vehicle_bias_sigma_m"), std::string::npos);
  }
}

TEST(FireFusion, ObservationFromRadioReportUsesTheLocalFrame) {
  const common::LocalFrame frame({47.0, 8.0});
  radio::FireReport report;
  report.header.sender = 9;
  report.report_id = 321;
  const common::LatLon fire = frame.ToGeodetic({30.0, 40.0});  // east, north
  const common::LatLon observer = frame.ToGeodetic({-10.0, 5.0});
  report.lat_deg = fire.lat_deg;
  report.lon_deg = fire.lon_deg;
  report.observer_lat_deg = observer.lat_deg;
  report.observer_lon_deg = observer.lon_deg;
  report.sigma_north_m = 2.0;
  report.sigma_east_m = 3.0;
  report.correlation = 0.5;
  report.confidence = 0.9;

  const FireObservation observation = ObservationFromReport(report, frame, 77.0);
  EXPECT_EQ(observation.vehicle_id, 9);
  EXPECT_EQ(observation.report_id, 321);
  EXPECT_DOUBLE_EQ(observation.detection_time_s, 77.0);
  EXPECT_NEAR(observation.position_en_m.x(), 30.0, 1e-6);  // east
  EXPECT_NEAR(observation.position_en_m.y(), 40.0, 1e-6);  // north
  EXPECT_NEAR(observation.observer_en_m.x(), -10.0, 1e-6);
  EXPECT_NEAR(observation.observer_en_m.y(), 5.0, 1e-6);
  EXPECT_DOUBLE_EQ(observation.covariance_en_m2(0, 0), 9.0);  // east: sigma_east_m squared
  EXPECT_DOUBLE_EQ(observation.covariance_en_m2(1, 1), 4.0);
  EXPECT_DOUBLE_EQ(observation.covariance_en_m2(0, 1), 3.0);
  EXPECT_DOUBLE_EQ(observation.covariance_en_m2(1, 0), 3.0);
  EXPECT_DOUBLE_EQ(observation.confidence, 0.9);
}

// The LCM adapter casts the status straight into fire_track_t.status.
static_assert(static_cast<std::int8_t>(FireTrackStatus::kTentative) ==
              fire_track_t::STATUS_TENTATIVE);
static_assert(static_cast<std::int8_t>(FireTrackStatus::kConfirmed) ==
              fire_track_t::STATUS_CONFIRMED);
static_assert(static_cast<std::int8_t>(FireTrackStatus::kRejected) ==
              fire_track_t::STATUS_REJECTED);

TEST(FireFusion, StatusAndOutcomeNames) {
  EXPECT_EQ(ToString(FireTrackStatus::kTentative), "tentative");
  EXPECT_EQ(ToString(FireTrackStatus::kConfirmed), "confirmed");
  EXPECT_EQ(ToString(FireTrackStatus::kRejected), "rejected");
  EXPECT_EQ(ToString(FireReportOutcome::kAbsorbed), "absorbed");
}

}  // namespace
}  // namespace fireswarm::server
