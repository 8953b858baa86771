#include "fireswarm/run/report_json.hpp"

#include <cmath>
#include <string>

namespace fireswarm::run {
namespace {

using Json = nlohmann::ordered_json;

Json Number(double value) {
  return std::isfinite(value) ? Json(value) : Json(nullptr);
}

Json Optional(const std::optional<double>& value) {
  return value ? Number(*value) : Json(nullptr);
}

Json FireJson(const FireOutcome& fire) {
  Json j;
  j["true_lat"] = fire.truth.lat_deg;
  j["true_lon"] = fire.truth.lon_deg;
  j["fused_lat"] = fire.fused ? Json(fire.fused->lat_deg) : Json(nullptr);
  j["fused_lon"] = fire.fused ? Json(fire.fused->lon_deg) : Json(nullptr);
  j["error_m"] = Optional(fire.error_m);
  j["first_report_s"] = Optional(fire.first_report_s);
  j["confirmed_s"] = Optional(fire.confirmed_s);
  j["vehicles"] = fire.vehicles;
  j["ignition_lat"] = fire.ignition.lat_deg;
  j["ignition_lon"] = fire.ignition.lon_deg;
  j["ignition_error_m"] = Optional(fire.ignition_error_m);
  j["start_s"] = Number(fire.start_s);
  return j;
}

Json RadioJson(const RadioOutcome& radio) {
  Json j;
  j["busy_fraction"] = Number(radio.busy_fraction);
  Json ages = Json::object();
  for (const auto& [id, p50_p99] : radio.telemetry_age_p50_p99_s) {
    ages[std::to_string(id)] = {{"p50", Number(p50_p99.first)}, {"p99", Number(p50_p99.second)}};
  }
  j["telemetry_age_s"] = ages;
  j["retries"] = radio.retries;
  j["report_latency_s"] = {{"p50", Optional(radio.report_latency_p50_s)},
                           {"p99", Optional(radio.report_latency_p99_s)}};
  j["reports_lost"] = radio.reports_lost;
  return j;
}

}  // namespace

nlohmann::ordered_json ToJson(const Report& report) {
  Json j;
  Json fires = Json::array();
  for (const FireOutcome& fire : report.fires) fires.push_back(FireJson(fire));
  j["fires"] = fires;
  Json false_tracks = Json::array();
  for (const FalseTrack& track : report.false_tracks) {
    false_tracks.push_back({{"track_id", track.track_id},
                            {"lat", track.position.lat_deg},
                            {"lon", track.position.lon_deg},
                            {"confirmed_s", Number(track.confirmed_s)},
                            {"vehicles", track.vehicles}});
  }
  j["false_tracks"] = false_tracks;
  Json tracks = Json::array();
  for (const TrackOutcome& track : report.tracks) {
    tracks.push_back({{"track_id", track.track_id},
                      {"status", track.status},
                      {"lat", track.position.lat_deg},
                      {"lon", track.position.lon_deg},
                      {"covariance_ne_m2", track.covariance_ne_m2},
                      {"reports", track.report_count},
                      {"vehicles", track.vehicles},
                      {"first_seen_s", Number(track.first_seen_s)},
                      {"last_seen_s", Number(track.last_seen_s)}});
  }
  j["tracks"] = tracks;
  Json investigations = Json::array();
  for (const InvestigationOutcome& inv : report.investigations) {
    investigations.push_back({{"vehicle", inv.vehicle},
                              {"track_id", inv.track_id},
                              {"started_s", Number(inv.started_s)},
                              {"until_s", Number(inv.until_s)},
                              {"closest_m", Optional(inv.closest_m)},
                              {"judged", inv.judged}});
  }
  j["investigations"] = investigations;
  j["coverage"] = Number(report.coverage);
  Json series = Json::array();
  for (const auto& [t_s, fraction] : report.coverage_over_time) {
    series.push_back(Json::array({Number(t_s), Number(fraction)}));
  }
  j["coverage_over_time"] = series;
  Json collisions = Json::array();
  for (const Collision& c : report.collisions) {
    collisions.push_back({{"t_s", c.t_s},
                          {"vehicle_a", c.vehicle_a},
                          {"vehicle_b", c.vehicle_b},
                          {"lat", c.position.lat_deg},
                          {"lon", c.position.lon_deg}});
  }
  j["collisions"] = collisions;
  j["min_separation_m"] = Optional(report.min_separation_m);
  const SeparationOutcome& separation = report.separation;
  j["separation"] = {{"rule", separation.rule},
                     {"separation_m", Number(separation.separation_m)},
                     {"conflicts", separation.conflicts},
                     {"orders", separation.orders},
                     {"resolved", separation.resolved},
                     {"lost_separation", separation.lost_separation},
                     {"takeoffs_held", separation.takeoffs_held},
                     {"releases", separation.releases},
                     {"not_taken", separation.not_taken},
                     {"closest", nullptr},
                     {"lost", Json::array()}};
  for (const SeparationOutcome::Lost& lost : separation.lost) {
    j["separation"]["lost"].push_back({{"detected_s", Number(lost.detected_s)},
                                       {"vehicle_a", lost.vehicle_a},
                                       {"vehicle_b", lost.vehicle_b},
                                       {"reported_min_m", Number(lost.reported_min_m)},
                                       {"predicted_m", Number(lost.predicted_m)},
                                       {"time_to_closest_s", Number(lost.time_to_closest_s)},
                                       {"resolution", lost.resolution},
                                       {"mover", lost.mover}});
  }
  if (const std::optional<ClosestApproach>& c = separation.closest) {
    j["separation"]["closest"] = {{"t_s", Number(c->t_s)},
                                  {"vehicle_a", c->vehicle_a},
                                  {"vehicle_b", c->vehicle_b},
                                  {"distance_m", Number(c->distance_m)},
                                  {"altitude_a_m", Number(c->altitude_a_m)},
                                  {"altitude_b_m", Number(c->altitude_b_m)}};
  }
  j["radio"] = RadioJson(report.radio);
  Json vehicles = Json::object();
  for (const auto& [id, vehicle] : report.vehicles) {
    vehicles[std::to_string(id)] = {{"distance_m", Number(vehicle.distance_m)},
                                    {"airborne_s", Number(vehicle.airborne_s)},
                                    {"battery_used", Number(vehicle.battery_used)},
                                    {"final_state", vehicle.final_state},
                                    {"sorties",
                                     {{"planned", vehicle.sorties_planned},
                                      {"flown", vehicle.sorties_flown},
                                      {"current", vehicle.sortie}}},
                                    {"battery_swaps", vehicle.battery_swaps}};
  }
  j["vehicles"] = vehicles;
  j["sim_seconds"] = Number(report.sim_seconds);
  j["wall_seconds"] = Number(report.wall_seconds);
  j["real_time_factor"] = Number(report.real_time_factor);
  Json expect = Json::array();
  for (const ExpectOutcome& e : report.expect) {
    expect.push_back({{"name", e.name},
                      {"value", Number(e.value)},
                      {"limit", Number(e.limit)},
                      {"verdict", e.passed ? "pass" : "fail"}});
  }
  j["expect"] = expect;
  return j;
}

}  // namespace fireswarm::run
