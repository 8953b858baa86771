#include "scoring.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <unordered_set>
#include <utility>

#include "fireswarm/common/north_east.hpp"
#include "fireswarm/server/vehicle_task.hpp"

namespace fireswarm::run::internal {
namespace {

constexpr double kCoverageSampleS = 0.5;
constexpr double kSeparationSampleS = 0.05;
constexpr double kTrackSampleS = 5.0;

// A series that filled up: every other point goes (the first stays); the
// caller doubles its interval.
template <typename Point>
void KeepEveryOther(std::vector<Point>& points) {
  std::size_t kept = 0;
  for (std::size_t k = 0; k < points.size(); k += 2) points[kept++] = points[k];
  points.resize(kept);
}

bool Flying(const sim2d::VehicleTruth& truth) {
  return truth.phase == sim2d::FlightPhase::kFlying;
}

common::LatLon ToLatLon(const common::LocalFrame& frame, const Eigen::Vector2d& east_north) {
  return frame.ToGeodetic({east_north.x(), east_north.y()});
}

std::vector<int> ToInts(const std::vector<std::uint8_t>& ids) {
  return std::vector<int>(ids.begin(), ids.end());
}

// True when a fire cell within kOnFireM of `position_m` had ignited by `t_s`.
bool OnFire(const sim2d::FireGrid& grid, const sim2d::Vec2& position_m, double t_s) {
  const double cell_m = grid.config().cell_size_m;
  const int reach = static_cast<int>(std::ceil(kOnFireM / cell_m));
  const std::optional<sim2d::CellIndex> centre = grid.CellAt(position_m);
  if (!centre) return false;
  for (int dr = -reach; dr <= reach; ++dr) {
    for (int dc = -reach; dc <= reach; ++dc) {
      const sim2d::CellIndex cell{centre->col + dc, centre->row + dr};
      if (cell.col < 0 || cell.row < 0 || cell.col >= grid.cols() || cell.row >= grid.rows()) {
        continue;
      }
      if ((grid.CellCenter(cell) - position_m).norm() > kOnFireM + cell_m / 2.0) continue;
      const std::optional<double> ignited_s = grid.IgnitionTimeS(cell);
      if (ignited_s && *ignited_s <= t_s) return true;
    }
  }
  return false;
}

}  // namespace

std::optional<sim2d::Vec2> FireHotCentre(const sim2d::FireGrid& grid,
                                         const sim2d::Vec2& ignition_m) {
  const std::optional<sim2d::CellIndex> start = grid.CellAt(ignition_m);
  if (!start || !grid.IgnitionTimeS(*start)) return std::nullopt;
  const double ambient_c = grid.config().ambient_c;
  // Only the fire's own cells are visited: no bitmap of the whole grid.
  const auto flat = [&](sim2d::CellIndex cell) {
    return static_cast<std::size_t>(cell.row) * static_cast<std::size_t>(grid.cols()) +
           static_cast<std::size_t>(cell.col);
  };
  std::unordered_set<std::size_t> seen{flat(*start)};
  std::vector<sim2d::CellIndex> open{*start};
  sim2d::Vec2 sum = sim2d::Vec2::Zero();
  int hot = 0;
  while (!open.empty()) {
    const sim2d::CellIndex cell = open.back();
    open.pop_back();
    if (grid.CellTemperatureC(cell) - ambient_c >= kVisibleExcessK) {
      sum += grid.CellCenter(cell);
      ++hot;
    }
    for (int dr = -1; dr <= 1; ++dr) {
      for (int dc = -1; dc <= 1; ++dc) {
        const sim2d::CellIndex next{cell.col + dc, cell.row + dr};
        if (next.col < 0 || next.row < 0 || next.col >= grid.cols() || next.row >= grid.rows() ||
            !grid.IgnitionTimeS(next) || !seen.insert(flat(next)).second) {
          continue;
        }
        open.push_back(next);
      }
    }
  }
  if (hot == 0) return std::nullopt;
  return sum / static_cast<double>(hot);
}

Scorer::Scorer(const Scenario& scenario, std::vector<FireSpec> fires)
    : scenario_(scenario),
      fires_(std::move(fires)),
      coverage_(scenario.area.area, scenario.area.no_fly) {
  for (const int id : scenario.fleet.ReceiverIds()) traces_[id] = VehicleTrace{};
}

Scorer::VehicleTrace& Scorer::TraceOf(std::size_t truth_index, int id) {
  if (truth_index >= truth_traces_.size()) truth_traces_.resize(truth_index + 1, {0, nullptr});
  std::pair<int, VehicleTrace*>& entry = truth_traces_[truth_index];
  if (entry.second == nullptr || entry.first != id) entry = {id, &traces_[id]};
  return *entry.second;
}

void Scorer::Observe(double t_s, const sim2d::Simulation& simulation,
                     const server::Server& server) {
  constexpr double kEps = 1e-9;
  const sim2d::World& world = simulation.world();
  ++steps_;
  const std::span<const sim2d::VehicleTruth> truths = world.Truths();
  for (std::size_t i = 0; i < truths.size(); ++i) {
    const sim2d::VehicleTruth& truth = truths[i];
    VehicleTrace& trace = TraceOf(i, truth.id);
    if (trace.last_position_m) {
      const double dh = (truth.position_m - *trace.last_position_m).norm();
      const double dv = truth.altitude_m - trace.last_altitude_m;
      trace.distance_m += std::hypot(dh, dv);
      if (Flying(truth)) trace.airborne_s += t_s - last_observed_s_;
    }
    trace.last_position_m = truth.position_m;
    trace.last_altitude_m = truth.altitude_m;
  }
  last_observed_s_ = t_s;
  if (t_s + kEps >= next_coverage_s_) {
    next_coverage_s_ += kCoverageSampleS;
    for (const sim2d::VehicleTruth& truth : world.Truths()) {
      // A vehicle on the ground, crashed or lost sees nothing to search.
      if (truth.phase != sim2d::FlightPhase::kFlying) continue;
      coverage_.Mark(truth.position_m, truth.heading_rad, truth.altitude_m, *scenario_.fleet.camera,
                     scenario_.fleet.camera_pitch_deg);
    }
  }
  if (t_s + kEps >= next_series_s_) {
    coverage_over_time_.emplace_back(t_s, coverage_.Fraction());
    next_series_s_ += series_every_s_;
    if (coverage_over_time_.size() >= kMaxSeriesPoints) {
      KeepEveryOther(coverage_over_time_);
      series_every_s_ *= 2.0;
    }
  }
  if (t_s + kEps >= next_track_s_) {
    next_track_s_ += kTrackSampleS;
    for (std::size_t i = 0; i < truths.size(); ++i) {
      VehicleTrace& trace = TraceOf(i, truths[i].id);
      if (++trace.track_skipped < trace.track_every) continue;
      trace.track_skipped = 0;
      trace.track.push_back(ToLatLon(world.frame(), truths[i].position_m));
      if (trace.track.size() < kMaxTrackPoints) continue;
      KeepEveryOther(trace.track);
      trace.track_every *= 2;
    }
  }
  if (t_s + kEps >= next_second_s_) {
    next_second_s_ += 1.0;
    for (const sim2d::VehicleTruth& truth : world.Truths()) {
      if (!Flying(truth)) continue;
      const auto id = static_cast<std::uint8_t>(truth.id);
      if (!server.registry().Contains(id)) continue;
      if (const std::optional<double> age = server.registry().TelemetryAgeS(id, t_s)) {
        traces_[truth.id].telemetry_ages_s.Add(*age);
      }
    }
  }
  ObserveSeparation(world);
  ObserveEvents(world);
  for (const server::FireTrack& track : server.fusion().tracks()) {
    if (track.status != server::FireTrackStatus::kConfirmed) continue;
    auto it = confirmed_.find(track.track_id);
    if (it == confirmed_.end()) {
      const sim2d::Vec2 position = track.position_en_m;
      Confirmation confirmation;
      confirmation.t_s = t_s;
      confirmation.on_fire = OnFire(simulation.fire(), position, t_s);
      it = confirmed_.emplace(track.track_id, confirmation).first;
    }
    if (it->second.reports_seen != track.report_count) {
      it->second.reports_seen = track.report_count;
      TakeFireCentres(simulation.fire(), it->second);
    }
  }
}

void Scorer::TakeFireCentres(const sim2d::FireGrid& grid, Confirmation& confirmation) const {
  confirmation.fire_centres_m.clear();
  for (const FireSpec& fire : fires_) {
    const common::EastNorth ignition = scenario_.area.frame.ToLocal(fire.position);
    confirmation.fire_centres_m.push_back(
        FireHotCentre(grid, sim2d::Vec2(ignition.east_m, ignition.north_m)));
  }
}

void Scorer::ObserveSeparation(const sim2d::World& world) {
  const auto stride = std::max<std::int64_t>(1, std::llround(kSeparationSampleS / world.step_s()));
  if (steps_ % stride != 0) return;
  const std::span<const sim2d::VehicleTruth> truths = world.Truths();
  // A sweep along east: only pairs closer in east than the closest pair so
  // far can be closer, so each drone meets its few neighbours, not all of them.
  by_east_.clear();
  for (std::size_t i = 0; i < truths.size(); ++i) {
    if (Flying(truths[i])) by_east_.push_back(i);
  }
  std::ranges::sort(by_east_, [&](std::size_t a, std::size_t b) {
    return std::pair(truths[a].position_m.x(), a) < std::pair(truths[b].position_m.x(), b);
  });
  // The closest pair of this sample, ties to the lower index pair (as a scan
  // over all pairs in index order would find it).
  std::optional<std::pair<std::size_t, std::size_t>> best;
  double best_m = separation_seen_ ? min_separation_m_ : std::numeric_limits<double>::infinity();
  for (std::size_t a = 0; a < by_east_.size(); ++a) {
    const sim2d::VehicleTruth& first = truths[by_east_[a]];
    for (std::size_t b = a + 1; b < by_east_.size(); ++b) {
      const sim2d::VehicleTruth& second = truths[by_east_[b]];
      if (second.position_m.x() - first.position_m.x() > best_m) break;
      const double dh = (first.position_m - second.position_m).norm();
      const double d = std::hypot(dh, first.altitude_m - second.altitude_m);
      const std::pair<std::size_t, std::size_t> pair = std::minmax(by_east_[a], by_east_[b]);
      if (d < best_m || (best && d == best_m && pair < *best)) {
        best_m = d;
        best = pair;
      }
    }
  }
  if (!best) return;
  // Across samples the earliest of equal minima stays.
  if (separation_seen_ && !(best_m < min_separation_m_)) return;
  const sim2d::VehicleTruth& i = truths[best->first];
  const sim2d::VehicleTruth& j = truths[best->second];
  min_separation_m_ = best_m;
  closest_ = {world.time_s(), i.id, j.id, best_m, i.altitude_m, j.altitude_m};
  separation_seen_ = true;
}

void Scorer::ObserveEvents(const sim2d::World& world) {
  const sim2d::EventLog& events = world.events();
  // Observed every step, so none is missed (the log keeps the latest 1,000).
  for (events_seen_ = std::max(events_seen_, events.first()); events_seen_ < events.total();
       ++events_seen_) {
    const sim2d::WorldEvent& event = events.at(events_seen_);
    if (event.kind == sim2d::EventKind::kBatterySwap) {
      ++traces_[event.vehicle_a].battery_swaps;
      continue;
    }
    if (event.kind != sim2d::EventKind::kCollision) continue;
    Collision collision;
    collision.t_s = event.time_s;
    collision.vehicle_a = event.vehicle_a;
    collision.vehicle_b = event.vehicle_b;
    const Eigen::Vector2d middle =
        (world.Truth(event.vehicle_a).position_m + world.Truth(event.vehicle_b).position_m) / 2.0;
    collision.position = ToLatLon(world.frame(), middle);
    collisions_.push_back(collision);
  }
}

void Scorer::ScoreFires(const server::Server& server, Report& report) const {
  const common::LocalFrame& frame = scenario_.area.frame;
  for (const FireSpec& fire : fires_) {
    FireOutcome outcome;
    outcome.truth = fire.position;
    outcome.ignition = fire.position;
    outcome.start_s = fire.start_s;
    report.fires.push_back(outcome);
  }
  // Confirmed tracks in the order they were confirmed (ties by track ID).
  std::vector<std::pair<double, std::int32_t>> order;
  for (const auto& [id, confirmation] : confirmed_) order.emplace_back(confirmation.t_s, id);
  std::sort(order.begin(), order.end());
  for (const auto& [confirmed_s, track_id] : order) {
    const server::FireTrack* track = server.fusion().Find(track_id);
    if (track == nullptr) continue;
    const Confirmation& confirmation = confirmed_.at(track_id);
    const sim2d::Vec2 fused_m = track->position_en_m;
    // The nearest fire that had started by the confirmation, where it burned.
    std::optional<std::size_t> nearest;
    double nearest_m = std::numeric_limits<double>::infinity();
    sim2d::Vec2 nearest_truth_m = sim2d::Vec2::Zero();
    for (std::size_t i = 0; i < fires_.size(); ++i) {
      if (fires_[i].start_s > confirmed_s) continue;
      const common::EastNorth ignition = frame.ToLocal(fires_[i].position);
      sim2d::Vec2 truth_m(ignition.east_m, ignition.north_m);
      if (i < confirmation.fire_centres_m.size() && confirmation.fire_centres_m[i]) {
        truth_m = *confirmation.fire_centres_m[i];
      }
      const double d = (fused_m - truth_m).norm();
      if (d < nearest_m) {
        nearest_m = d;
        nearest = i;
        nearest_truth_m = truth_m;
      }
    }
    const bool real = nearest && (nearest_m <= kFireMatchRadiusM || confirmation.on_fire);
    const common::LatLon fused = ToLatLon(frame, fused_m);
    if (!real) {
      FalseTrack false_track;
      false_track.track_id = track_id;
      false_track.position = fused;
      false_track.confirmed_s = confirmed_s;
      false_track.vehicles = ToInts(track->vehicle_ids);
      report.false_tracks.push_back(false_track);
      continue;
    }
    FireOutcome& outcome = report.fires[*nearest];
    if (outcome.fused) continue;  // a duplicate track of a fire already matched
    const common::EastNorth ignition = frame.ToLocal(outcome.ignition);
    outcome.truth = ToLatLon(frame, nearest_truth_m);
    outcome.fused = fused;
    outcome.error_m = nearest_m;
    outcome.ignition_error_m = (fused_m - sim2d::Vec2(ignition.east_m, ignition.north_m)).norm();
    outcome.first_report_s = track->first_seen_s;
    outcome.confirmed_s = confirmed_s;
    outcome.vehicles = ToInts(track->vehicle_ids);
    outcome.covariance_ne_m2 = common::NorthEastTriangle(track->covariance_en_m2);
  }
}

void Scorer::ListTracks(const server::Server& server, Report& report) const {
  const common::LocalFrame& frame = scenario_.area.frame;
  for (const server::FireTrack& track : server.fusion().tracks()) {
    TrackOutcome out;
    out.track_id = track.track_id;
    out.status = std::string(server::ToString(track.status));
    out.position = frame.ToGeodetic({track.position_en_m.x(), track.position_en_m.y()});
    out.covariance_ne_m2 = common::NorthEastTriangle(track.covariance_en_m2);
    out.report_count = track.report_count;
    out.vehicles = ToInts(track.vehicle_ids);
    out.first_seen_s = track.first_seen_s;
    out.last_seen_s = track.last_seen_s;
    report.tracks.push_back(out);
  }
  for (const server::Investigation& investigation : server.investigations()) {
    InvestigationOutcome out;
    out.vehicle = investigation.vehicle;
    out.track_id = investigation.track_id;
    out.started_s = investigation.started_s;
    out.until_s = investigation.until_s;
    if (std::isfinite(investigation.closest_m)) out.closest_m = investigation.closest_m;
    out.judged = investigation.judged;
    report.investigations.push_back(out);
  }
}

void Scorer::ScoreRadio(const server::Server& server, const FinalState& final_state,
                        Report& report) const {
  RadioOutcome& radio = report.radio;
  radio.busy_fraction =
      final_state.sim_seconds > 0.0 ? final_state.radio_busy_s / final_state.sim_seconds : 0.0;
  for (const auto& [id, trace] : traces_) {
    if (trace.telemetry_ages_s.empty()) continue;
    radio.telemetry_age_p50_p99_s[id] = {trace.telemetry_ages_s.Percentile(0.5),
                                         trace.telemetry_ages_s.Percentile(0.99)};
  }
  radio.retries = server.scheduler().stats().retries;
  const server::ReportStats& fused = server.report_stats();
  if (!fused.latency_s.empty()) {
    radio.report_latency_p50_s = fused.latency_s.Percentile(0.5);
    radio.report_latency_p99_s = fused.latency_s.Percentile(0.99);
  }
  radio.reports_sent = final_state.reports_queued;
  radio.reports_received = fused.fused;
  radio.reports_lost =
      radio.reports_sent > radio.reports_received ? radio.reports_sent - radio.reports_received : 0;
}

Report Scorer::Finish(const sim2d::World& world, const server::Server& server,
                      const FinalState& final_state) {
  Report report;
  report.scenario = scenario_.name;
  report.seed = scenario_.seed;
  ScoreFires(server, report);
  ListTracks(server, report);
  report.coverage = coverage_.Fraction();
  report.coverage_over_time = coverage_over_time_;
  if (report.coverage_over_time.empty() ||
      report.coverage_over_time.back().first < final_state.sim_seconds) {
    report.coverage_over_time.emplace_back(final_state.sim_seconds, report.coverage);
  }
  report.collisions = collisions_;
  const double world_min = world.min_separation_m();
  if (separation_seen_) {
    report.min_separation_m = min_separation_m_;
    report.separation.closest = closest_;
  }
  if (std::isfinite(world_min)) {
    report.min_separation_m = std::min(report.min_separation_m.value_or(world_min), world_min);
  }
  ScoreRadio(server, final_state, report);
  for (const auto& [id, trace] : traces_) {
    VehicleOutcome vehicle;
    vehicle.distance_m = trace.distance_m;
    vehicle.airborne_s = trace.airborne_s;
    vehicle.battery_used = 1.0 - world.Truth(id).battery_fraction;
    const auto mode = final_state.modes.find(id);
    vehicle.final_state = mode != final_state.modes.end() ? mode->second : "unknown";
    const auto planned = final_state.sorties_planned.find(id);
    vehicle.sorties_planned = planned != final_state.sorties_planned.end() ? planned->second : 0;
    const server::TaskView task =
        server::TaskOf(server, static_cast<std::uint8_t>(id), final_state.sim_seconds);
    const auto before = final_state.sorties_flown_before.find(id);
    vehicle.sorties_flown = task.sorties_flown +
                            (before != final_state.sorties_flown_before.end() ? before->second : 0);
    vehicle.sortie = task.sortie;
    vehicle.battery_swaps = trace.battery_swaps;
    vehicle.track = trace.track;
    vehicle.track.push_back(ToLatLon(world.frame(), world.Truth(id).position_m));
    report.vehicles[id] = vehicle;
  }
  report.sim_seconds = final_state.sim_seconds;
  report.expect = EvaluateExpectations(scenario_.expect, report);
  return report;
}

}  // namespace fireswarm::run::internal
