// Scoring a run against the simulator's truth: the only code of fireswarm that
// reads truth and the server's results side by side. Private to the runner.
//
// The runner calls Observe() after every lockstep step and Finish() once at the
// end (scoring.cpp; the `expect` checks in expectations.cpp). Approximations
// (documented in docs/scenario.md's report section):
//  * coverage: planner::CoverageGrid (the raster and footprint the server's
//    mission_status_t coverage uses too), marked every 0.5 s of simulated time
//    by each flying vehicle at its TRUE position, altitude and heading.
//  * min_separation_m: the smallest 3D distance between two flying vehicles,
//    sampled every 50 ms, and sim2d's exact near-miss minimum, which counts a
//    pair while either one flies (a drone landing next to a parked one).
//  * fires: where a fire is, for its error, is where it burns when its track last
//    got a report: the centre of its hot cells (FireHotCentre: the cells burning
//    or still >= kVisibleExcessK over ambient that connect to its ignition cell).
//    The sim burns whole 5 m cells, so a small fire is the cell its ignition
//    point lies in, up to 3.5 m from that point; a large one spreads in the wind.
//    The error to the ignition point is reported beside it.
//    A confirmed track matches the nearest true fire that had started, within
//    kFireMatchRadiusM of where it burned; the first confirmed track matched to
//    a fire is its fused position. A confirmed track farther out
//    that lies within kOnFireM of a fire cell that had ignited when it was
//    confirmed is on the spread of a real fire: it is fused position of the
//    nearest fire if that has none yet, otherwise a duplicate; never false.
//    Confirmed tracks on no fire are false.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "fireswarm/common/age_histogram.hpp"
#include "fireswarm/planner/coverage_grid.hpp"
#include "fireswarm/run/report.hpp"
#include "fireswarm/run/scenario.hpp"
#include "fireswarm/server/server.hpp"
#include "fireswarm/sim2d/simulation.hpp"

namespace fireswarm::run::internal {

inline constexpr double kFireMatchRadiusM = 30.0;
/// A confirmed track this close to an ignited fire cell is on a real fire, m.
inline constexpr double kOnFireM = 10.0;
/// A cooling cell counts toward a fire's position while it is at least this
/// much over ambient, K: the vehicles' detector floor (agents::DetectorConfig::min_excess_k).
inline constexpr double kVisibleExcessK = 10.0;

/// The centre of the hot cells (burning, or cooling but >= kVisibleExcessK over
/// ambient) 8-connected through ignited cells to the cell under `ignition_m`,
/// local ENU metres; nullopt when none is hot (not started, or burned out).
std::optional<sim2d::Vec2> FireHotCentre(const sim2d::FireGrid& grid,
                                         const sim2d::Vec2& ignition_m);

/// At most this many points of a vehicle's track are kept for the report's map:
/// when full, every other point goes and the sampling interval doubles, so a day
/// of patrols keeps the whole day, coarser.
inline constexpr std::size_t kMaxTrackPoints = 1'024;

/// The coverage series takes a point this often, s ...
inline constexpr double kCoverageSeriesS = 10.0;
/// ... and keeps at most this many: when full, every other point goes and the
/// interval doubles (past 2.8 hours).
inline constexpr std::size_t kMaxSeriesPoints = 1'024;

/// What the runner hands over at the end besides the world and the server.
struct FinalState {
  double sim_seconds = 0.0;
  double radio_busy_s = 0.0;           ///< channel airtime, overlaps once; the busiest channel's
  std::map<int, std::string> modes;    ///< receiver ID -> flight mode name
  std::uint64_t reports_queued = 0;    ///< fire reports the vehicles queued
  std::map<int, int> sorties_planned;  ///< receiver ID -> sorties in the plan
  /// receiver ID -> sorties flown in a patrol's rounds before the server's
  /// current mission (which the server itself counts).
  std::map<int, int> sorties_flown_before;
};

class Scorer {
 public:
  Scorer(const Scenario& scenario, std::vector<FireSpec> fires);

  /// After each lockstep step at simulated time `t_s`.
  void Observe(double t_s, const sim2d::Simulation& simulation, const server::Server& server);

  double coverage() const { return coverage_.Fraction(); }
  /// The raster behind coverage(): the class the server's coverage uses too.
  const planner::CoverageGrid& coverage_grid() const { return coverage_; }
  /// Confirmed tracks so far (for the progress line).
  std::size_t confirmed_tracks() const { return confirmed_.size(); }

  /// The report (wall-clock fields left 0 for the caller), expectations evaluated.
  Report Finish(const sim2d::World& world, const server::Server& server,
                const FinalState& final_state);

 private:
  struct VehicleTrace {
    double distance_m = 0.0;
    double airborne_s = 0.0;
    std::optional<sim2d::Vec2> last_position_m;
    double last_altitude_m = 0.0;
    std::vector<common::LatLon> track;  // at most kMaxTrackPoints
    int track_every = 1;                // samples per kept point (doubles when full)
    int track_skipped = 0;              // samples since the last kept point
    common::AgeHistogram telemetry_ages_s;
    int battery_swaps = 0;
  };

  void ObserveSeparation(const sim2d::World& world);
  // Collisions and battery swaps, from the world's events since the last step.
  void ObserveEvents(const sim2d::World& world);
  void ScoreFires(const server::Server& server, Report& report) const;
  void ListTracks(const server::Server& server, Report& report) const;
  void ScoreRadio(const server::Server& server, const FinalState& final_state,
                  Report& report) const;

  const Scenario& scenario_;
  std::vector<FireSpec> fires_;
  planner::CoverageGrid coverage_;
  std::vector<std::pair<double, double>> coverage_over_time_;
  std::map<int, VehicleTrace> traces_;
  // traces_'s entries in world.Truths() order, each with its vehicle's ID (map
  // nodes stay put): a lookup per vehicle and step was a map walk each.
  std::vector<std::pair<int, VehicleTrace*>> truth_traces_;
  VehicleTrace& TraceOf(std::size_t truth_index, int id);
  struct Confirmation {
    double t_s = 0.0;
    bool on_fire = false;  // near a fire cell that had ignited by then
    // Where each fire burned (FireHotCentre, by index of fires_) when the track
    // last got a report; taken again whenever its report count changes.
    std::int32_t reports_seen = 0;
    std::vector<std::optional<sim2d::Vec2>> fire_centres_m;
  };
  void TakeFireCentres(const sim2d::FireGrid& grid, Confirmation& confirmation) const;
  std::map<std::int32_t, Confirmation> confirmed_;  // track ID -> when first seen confirmed
  std::vector<Collision> collisions_;
  std::uint64_t events_seen_ = 0;  // the next world event's number
  double min_separation_m_ = 0.0;
  ClosestApproach closest_;
  bool separation_seen_ = false;
  std::vector<std::size_t> by_east_;  // ObserveSeparation's flying drones, by east
  std::int64_t steps_ = 0;
  double next_coverage_s_ = 0.0;
  double last_observed_s_ = 0.0;  // the last Observe()'s time
  double next_series_s_ = 0.0;
  double series_every_s_ = kCoverageSeriesS;  // doubled as the series fills
  double next_second_s_ = 0.0;
  double next_track_s_ = 0.0;
};

/// Each expectation the scenario states, checked against `report`.
std::vector<ExpectOutcome> EvaluateExpectations(const Expectations& expect, const Report& report);

}  // namespace fireswarm::run::internal
