#include "bench_fleet.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "fireswarm/common/time.hpp"
#include "fireswarm/radio/mission_chunks.hpp"

namespace fireswarm::bench::internal {

using common::Nanos;

namespace {

// Where the bench fleet flies: only the size of the frames matters to the link.
constexpr double kBaseLatDeg = 45.0;
constexpr double kBaseLonDeg = 7.0;
constexpr double kVehicleSpacingDeg = 1e-3;
constexpr double kAltitudeM = 120.0;
constexpr double kSpeedMps = 15.0;
constexpr double kBatteryV = 15.8;
constexpr std::uint8_t kBatteryPercent = 80;
constexpr double kReportSigmaM = 5.0;
constexpr double kPeakTemperatureC = 450.0;
constexpr double kConfidence = 0.9;
constexpr std::uint16_t kPixelCount = 12;
constexpr std::uint16_t kMissionId = 1;
constexpr double kMedian = 0.5;
constexpr double kP99 = 0.99;

std::uint32_t Millis(Nanos t) {
  return static_cast<std::uint32_t>(
      std::chrono::duration_cast<std::chrono::milliseconds>(t).count());
}

double LatOf(std::uint8_t id) {
  return kBaseLatDeg + kVehicleSpacingDeg * id;
}

// Nearest-rank percentile of `values` (p in (0, 1]); 0 for none.
double Percentile(std::vector<double> values, double p) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const auto rank = static_cast<std::size_t>(std::ceil(p * static_cast<double>(values.size())));
  return values[std::clamp<std::size_t>(rank, 1, values.size()) - 1];
}

double Max(const std::vector<double>& values) {
  return values.empty() ? 0.0 : *std::max_element(values.begin(), values.end());
}

}  // namespace

radio::CommandResult BenchHandler::OnCommand(const radio::Command& /*command*/) {
  return radio::CommandResult::kAccepted;
}

radio::MissionAckStatus BenchHandler::OnMissionChunk(const radio::MissionChunk& chunk) {
  if (chunk.chunk_index >= chunk.chunk_count) return radio::MissionAckStatus::kRejected;
  chunks_stored_.resize(chunk.chunk_count, false);
  chunks_stored_[chunk.chunk_index] = true;
  const bool complete =
      std::all_of(chunks_stored_.begin(), chunks_stored_.end(), [](bool stored) { return stored; });
  return complete ? radio::MissionAckStatus::kComplete : radio::MissionAckStatus::kAccepted;
}

radio::ParamValue BenchHandler::OnParamRead(const radio::ParamRead& read) {
  return radio::ParamValue{{}, read.param_id, 0.0F, radio::ParamStatus::kUnknownParam};
}

radio::ParamValue BenchHandler::OnParamWrite(const radio::ParamWrite& write) {
  return radio::ParamValue{{}, write.param_id, write.value, radio::ParamStatus::kOk};
}

radio::Telemetry SampleTelemetry(std::uint8_t id, Nanos now) {
  radio::Telemetry t;
  t.time_ms = Millis(now);
  t.lat_deg = LatOf(id);
  t.lon_deg = kBaseLonDeg;
  t.altitude_m = kAltitudeM;
  t.velocity_north_mps = kSpeedMps;
  t.battery_v = kBatteryV;
  t.battery_percent = kBatteryPercent;
  t.mode = radio::FlightMode::kSearch;
  t.flags = radio::telemetry_flags::kGpsFix | radio::telemetry_flags::kMissionValid;
  return t;
}

radio::FireReport SampleReport(std::uint8_t id, Nanos now) {
  radio::FireReport r;
  r.time_ms = Millis(now);
  r.lat_deg = LatOf(id) + kVehicleSpacingDeg / 2;
  r.lon_deg = kBaseLonDeg;
  r.sigma_north_m = kReportSigmaM;
  r.sigma_east_m = kReportSigmaM;
  r.observer_lat_deg = LatOf(id);
  r.observer_lon_deg = kBaseLonDeg;
  r.observer_altitude_m = kAltitudeM;
  r.pixel_count = kPixelCount;
  r.peak_temperature_c = kPeakTemperatureC;
  r.confidence = kConfidence;
  return r;
}

void QueueMission(radio::ChannelRouter& server, BenchVehicle& vehicle, int waypoints) {
  const std::uint8_t id = vehicle.endpoint.config().id;
  std::vector<radio::Waypoint> mission(static_cast<std::size_t>(waypoints));
  for (std::size_t i = 0; i < mission.size(); ++i) {
    // Latitude steps restart in every chunk: only the frames' size matters here.
    const auto in_chunk = static_cast<double>(i % radio::kMaxWaypointsPerChunk);
    mission[i] = radio::Waypoint{LatOf(id) + kVehicleSpacingDeg * in_chunk, kBaseLonDeg, kAltitudeM,
                                 kSpeedMps, 0};
  }
  const std::vector<radio::MissionChunk> chunks = radio::SplitMission(kMissionId, mission);
  for (const radio::MissionChunk& chunk : chunks) server.SendMissionChunk(id, chunk);
  vehicle.chunks_left = static_cast<int>(chunks.size());
}

void Record(const radio::SchedulerEvent& event, Nanos generation_end, Fleet& fleet,
            Metrics& metrics) {
  if (const auto* telemetry = std::get_if<radio::TelemetryReceived>(&event)) {
    BenchVehicle& v = *fleet.at(telemetry->vehicle - 1U);
    // A turn due in the window counts wherever its frame arrived: the last turns'
    // resends after lost replies land after the window's end.
    if (telemetry->served_due && *telemetry->served_due < generation_end) ++v.telemetry_received;
    v.latest_sample = std::chrono::milliseconds(telemetry->telemetry.time_ms);
  } else if (const auto* report = std::get_if<radio::FireReportReceived>(&event)) {
    const BenchVehicle& v = *fleet.at(report->vehicle - 1U);
    ++metrics.reports_received;
    const Nanos generated = v.report_generated.at(report->report.report_id);
    metrics.report_latencies_s.push_back(common::ToSeconds(report->received - generated));
  } else if (const auto* finished = std::get_if<radio::RequestFinished>(&event)) {
    BenchVehicle& v = *fleet.at(finished->vehicle - 1U);
    if (v.chunks_left == 0) return;
    if (finished->status == radio::RequestStatus::kFailed) {
      metrics.mission_failed = true;
      v.chunks_left = 0;
    } else {
      --v.chunks_left;
    }
    if (v.chunks_left == 0) {
      --metrics.missions_pending;
      metrics.mission_done = std::max(metrics.mission_done, finished->finished);
    }
  }
}

RadioBenchResult Figures(const RadioBenchConfig& config, const Snapshot& snapshot,
                         const Metrics& metrics, const radio::ChannelRouter& server,
                         std::span<const radio::SharedChannel* const> channels, const Fleet& fleet,
                         Nanos end) {
  RadioBenchResult r;
  const double window_s = config.seconds;
  r.sim_seconds = common::ToSeconds(end);
  for (std::size_t k = 0; k < channels.size(); ++k) {
    ChannelFigures c;
    c.vehicles = static_cast<int>(server.VehiclesOn(k).size());
    c.busy_fraction = common::ToSeconds(snapshot.busy.at(k)) / window_s;
    r.busy_fraction = std::max(r.busy_fraction, c.busy_fraction);
    r.transmissions += channels[k]->stats().transmissions;
    r.collisions += channels[k]->stats().collisions;
    r.per_channel.push_back(c);
  }
  r.payload_bytes_per_s = static_cast<double>(snapshot.payload_bytes) / window_s;
  double rate_sum = 0.0;
  r.telemetry_hz_min = std::numeric_limits<double>::infinity();
  std::vector<double> fleet_ages_s;
  for (const auto& v : fleet) {
    const double rate = static_cast<double>(v->telemetry_received) / window_s;
    r.telemetry_hz_min = std::min(r.telemetry_hz_min, rate);
    rate_sum += rate;
    r.per_vehicle.push_back({.vehicle = v->endpoint.config().id,
                             .telemetry_hz = rate,
                             .telemetry_age_p50_s = Percentile(v->ages_s, kMedian),
                             .telemetry_age_p99_s = Percentile(v->ages_s, kP99),
                             .reports_sent = v->report_generated.size()});
    fleet_ages_s.insert(fleet_ages_s.end(), v->ages_s.begin(), v->ages_s.end());
  }
  r.telemetry_hz_mean = rate_sum / static_cast<double>(fleet.size());
  r.telemetry_age_p50_s = Percentile(fleet_ages_s, kMedian);
  r.telemetry_age_p99_s = Percentile(fleet_ages_s, kP99);
  r.telemetry_age_max_s = Max(fleet_ages_s);
  r.report_latency_p50_s = Percentile(metrics.report_latencies_s, kMedian);
  r.report_latency_p99_s = Percentile(metrics.report_latencies_s, kP99);
  r.report_latency_max_s = Max(metrics.report_latencies_s);
  r.reports_sent = metrics.reports_sent;
  r.reports_received = metrics.reports_received;
  r.reports_lost = metrics.reports_sent - metrics.reports_received;
  const radio::SchedulerStats s = server.stats();
  r.duplicate_reports = s.duplicate_reports;
  r.retries = s.retries;
  r.missed_replies = s.missed_replies;
  r.bursts = s.bursts;
  r.slots_granted = s.slots_granted;
  r.requests_completed = s.requests_completed;
  r.requests_failed = s.requests_failed;
  r.checksum_errors = server.parser_stats().checksum_errors;
  for (const auto& v : fleet) r.checksum_errors += v->endpoint.parser_stats().checksum_errors;
  if (config.mission_waypoints > 0 && !metrics.mission_failed && metrics.missions_pending == 0) {
    r.mission_upload_s = common::ToSeconds(metrics.mission_done);
  }
  return r;
}

}  // namespace fireswarm::bench::internal
