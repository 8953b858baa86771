// The report file of `fireswarm run` (JSON): a contract for tools; docs/scenario.md
// lists every key. Positions WGS84 degrees, times simulated seconds, fractions 0..1;
// a value that does not exist (a fire never confirmed, no latency measured) is null.
#pragma once

#include <nlohmann/json.hpp>

#include "fireswarm/run/report.hpp"

namespace fireswarm::run {

/// The report as JSON, keys in a fixed order:
/// fires [{true_lat, true_lon, fused_lat, fused_lon, error_m, first_report_s,
/// confirmed_s, vehicles, ignition_lat, ignition_lon, ignition_error_m, start_s}], false_tracks [{track_id,
/// lat, lon, confirmed_s, vehicles}], coverage, coverage_over_time [[t_s, fraction]], collisions
/// [{t_s, vehicle_a, vehicle_b, lat, lon}], min_separation_m, radio {busy_fraction, telemetry_age_s
/// {"<id>": {p50, p99}}, retries, report_latency_s {p50, p99}, reports_lost},
/// vehicles {"<id>": {distance_m, battery_used, final_state}}, sim_seconds,
/// wall_seconds, real_time_factor, expect [{name, value, limit, verdict}].
/// Non-finite numbers are written as null.
nlohmann::ordered_json ToJson(const Report& report);

}  // namespace fireswarm::run
