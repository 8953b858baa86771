// What a `fireswarm run` found: the scenario's outcome scored against the
// simulator's truth. The runner fills it; report_json writes the report file
// (docs/scenario.md lists its keys: a contract for tools), the SVG map and the
// JUnit file are drawn from it. Positions are WGS84 degrees, times simulated
// seconds from the scenario's start.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "fireswarm/common/local_frame.hpp"

namespace fireswarm::run {

/// One true fire and what the fleet made of it.
struct FireOutcome {
  /// Where the fire burned when its track last got a report (the centre of its
  /// hot cells); the ignition point when it was never confirmed.
  common::LatLon truth;
  common::LatLon ignition;  ///< the scenario's fire position
  double start_s = 0.0;
  /// The confirmed track matched to it (nearest within the match radius); absent
  /// when it was never confirmed.
  std::optional<common::LatLon> fused;
  std::optional<double> error_m;           ///< fused to true distance
  std::optional<double> ignition_error_m;  ///< fused to ignition point distance
  std::optional<double> first_report_s;    ///< first report that went into its track
  std::optional<double> confirmed_s;       ///< when its track was confirmed
  std::vector<int> vehicles;               ///< receiver IDs that reported it, ascending
  /// Fused covariance, (north, east) m^2: [nn, ne, ee]; for the map's ellipse.
  std::optional<std::array<double, 3>> covariance_ne_m2;
};

/// A confirmed track that matches no true fire.
struct FalseTrack {
  std::int32_t track_id = 0;
  common::LatLon position;
  double confirmed_s = 0.0;
  std::vector<int> vehicles;
};

/// Every track the server's fusion ended with, whatever its status: what the
/// operator saw, including tentative and rejected ones.
struct TrackOutcome {
  std::int32_t track_id = 0;
  std::string status;  ///< "tentative", "confirmed" or "rejected"
  common::LatLon position;
  /// Fused covariance, (north, east) m^2: [nn, ne, ee].
  std::array<double, 3> covariance_ne_m2{};
  int report_count = 0;
  std::vector<int> vehicles;  ///< receiver IDs that reported it, ascending
  double first_seen_s = 0.0;
  double last_seen_s = 0.0;
};

/// An investigation the server ordered (a vehicle sent to circle a point).
struct InvestigationOutcome {
  int vehicle = 0;
  std::int32_t track_id = 0;  ///< 0: an operator's point
  double started_s = 0.0;
  double until_s = 0.0;
  /// Closest the vehicle's telemetry came to the point; absent when it never reported.
  std::optional<double> closest_m;
  bool judged = false;
};

struct Collision {
  double t_s = 0.0;
  int vehicle_a = 0;
  int vehicle_b = 0;
  common::LatLon position;
};

struct RadioOutcome {
  /// Share of the run the channel carried a transmission (with several channels:
  /// the busiest one).
  double busy_fraction = 0.0;
  /// Per receiver ID: telemetry age (time since the latest telemetry, sampled every
  /// second while the vehicle flew) p50 and p99, s.
  std::map<int, std::pair<double, double>> telemetry_age_p50_p99_s;
  std::uint64_t retries = 0;
  /// Detection on the vehicle to first receipt at the server, p50 and p99, s
  /// (common::AgeHistogram's: to 10 ms below 10 s, to 1 s above).
  std::optional<double> report_latency_p50_s;
  std::optional<double> report_latency_p99_s;
  std::uint64_t reports_sent = 0;      ///< reports the vehicles queued
  std::uint64_t reports_received = 0;  ///< distinct reports the server received and fused
  std::uint64_t reports_lost = 0;      ///< queued but never received by the run's end
};

/// The closest two flying vehicles came, as the scorer sampled them (truth).
struct ClosestApproach {
  double t_s = 0.0;
  int vehicle_a = 0;
  int vehicle_b = 0;
  double distance_m = 0.0;  ///< 3-D
  double altitude_a_m = 0.0;
  double altitude_b_m = 0.0;
};

/// How the server kept the drones apart (server/airspace.hpp, server/traffic.hpp).
struct SeparationOutcome {
  std::string rule;             ///< the strategic rule the plan used, in words
  double separation_m = 0.0;    ///< the limit
  std::uint64_t conflicts = 0;  ///< predicted by the tactical watch
  std::uint64_t orders = 0;     ///< resolutions sent over the radio
  std::uint64_t resolved = 0;   ///< passed apart
  std::uint64_t lost_separation = 0;  ///< passed closer than the limit, as reported
  std::uint64_t takeoffs_held = 0;    ///< take-off clearances refused (asked again)
  std::uint64_t releases = 0;         ///< level orders ended once their conflict closed
  std::uint64_t not_taken = 0;        ///< orders and releases the vehicle never acknowledged
  std::optional<ClosestApproach> closest;  ///< where min_separation_m was sampled
  /// The conflicts that lost separation: when detected, the pair, the closest
  /// they were reported, what was first predicted (how close, how soon: a late
  /// detection shows as a short lead), what was ordered ("climb", "descend",
  /// "level", "none").
  struct Lost {
    double detected_s = 0.0;
    int vehicle_a = 0;
    int vehicle_b = 0;
    double reported_min_m = 0.0;
    double predicted_m = 0.0;        ///< the closest approach first predicted
    double time_to_closest_s = 0.0;  ///< from detection to that approach
    std::string resolution;
    int mover = 0;
  };
  std::vector<Lost> lost;
};

struct VehicleOutcome {
  double distance_m = 0.0;    ///< flown, truth
  double airborne_s = 0.0;    ///< time in the air, truth
  double battery_used = 0.0;  ///< fraction of a full charge of the pack in at the end, truth
  int sorties_planned = 0;    ///< in the plan (DronePlan::sorties)
  /// Ended with a landing, by the server's count (a sortie cut short counts, and
  /// its rest is one more); a handed-over mission's sorties included.
  int sorties_flown = 0;
  int sortie = 0;                     ///< in the air at the end: the one flown, from 1; else 0
  int battery_swaps = 0;              ///< packs the simulator's ground crew put in, truth
  std::string final_state;            ///< flight mode at the end ("landed", "search", ...)
  std::vector<common::LatLon> track;  ///< truth positions every few seconds, for the map
};

/// One `expect` assertion.
struct ExpectOutcome {
  std::string name;  ///< the scenario key, e.g. "max_fused_error_m"
  double value = 0.0;
  double limit = 0.0;
  bool passed = false;
  std::string detail;  ///< why it failed, for people and JUnit
};

struct Report {
  std::string scenario;  ///< its name
  std::uint64_t seed = 0;
  std::vector<FireOutcome> fires;
  std::vector<FalseTrack> false_tracks;
  std::vector<TrackOutcome> tracks;
  std::vector<InvestigationOutcome> investigations;
  double coverage = 0.0;  ///< fraction 0..1 of the search area seen by a camera
  std::vector<std::pair<double, double>> coverage_over_time;  ///< (t_s, fraction)
  std::vector<Collision> collisions;
  std::optional<double> min_separation_m;  ///< between any two airborne vehicles
  SeparationOutcome separation;
  RadioOutcome radio;
  std::map<int, VehicleOutcome> vehicles;  ///< by receiver ID
  double sim_seconds = 0.0;
  double wall_seconds = 0.0;
  double real_time_factor = 0.0;
  std::vector<ExpectOutcome> expect;

  bool AllExpectationsHold() const {
    for (const ExpectOutcome& e : expect) {
      if (!e.passed) return false;
    }
    return true;
  }
};

}  // namespace fireswarm::run
