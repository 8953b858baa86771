// The radio bench's simulated vehicles and its bookkeeping: what each vehicle
// generates, what the server received, and the figures computed from both.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "fireswarm/radio/channel.hpp"
#include "fireswarm/radio/master_scheduler.hpp"
#include "fireswarm/radio/radio_bench.hpp"
#include "fireswarm/radio/vehicle_endpoint.hpp"

namespace fireswarm::radio::internal {

/// Accepts every command and mission chunk, as a vehicle with a free mission store.
class BenchHandler final : public VehicleRequestHandler {
 public:
  CommandResult OnCommand(const Command& command) override;
  MissionAckStatus OnMissionChunk(const MissionChunk& chunk) override;
  ParamValue OnParamRead(const ParamRead& read) override;
  ParamValue OnParamWrite(const ParamWrite& write) override;

 private:
  std::vector<bool> chunks_stored_;
};

struct BenchVehicle {
  explicit BenchVehicle(const VehicleEndpointConfig& config) : endpoint(config, handler) {}
  BenchHandler handler;  // before endpoint, which keeps a reference to it
  VehicleEndpoint endpoint;
  Nanos next_report = Nanos::max();      // next generation time
  std::vector<Nanos> report_generated;   // by report_id
  std::uint64_t telemetry_received = 0;  // by the server, during the generation window
  std::optional<Nanos> latest_sample;    // sampling time of its latest telemetry at the server
  std::vector<double> ages_s;            // telemetry age at the server, every age sample
  int chunks_left = 0;                   // mission chunks not yet acknowledged
};

using Fleet = std::vector<std::unique_ptr<BenchVehicle>>;

struct Metrics {
  std::uint64_t reports_sent = 0;
  std::uint64_t reports_received = 0;
  std::vector<double> report_latencies_s;
  int missions_pending = 0;  // vehicles whose upload is still running
  bool mission_failed = false;
  Nanos mission_done{0};  // when the last upload completed
};

/// Channel figures at the end of the generation window.
struct Snapshot {
  Nanos busy{0};
  std::uint64_t payload_bytes = 0;
};

/// State of vehicle `id` at `now` (a fixed position; only the frame's size matters).
Telemetry SampleTelemetry(std::uint8_t id, Nanos now);
/// A fire report detected by vehicle `id` at `now`.
FireReport SampleReport(std::uint8_t id, Nanos now);
/// Queues a `waypoints`-waypoint mission (1..kMaxMissionWaypoints) for `vehicle` in
/// chunks; sets chunks_left.
void QueueMission(MasterScheduler& server, BenchVehicle& vehicle, int waypoints);
/// Applies one scheduler event to the bookkeeping.
void Record(const SchedulerEvent& event, Nanos generation_end, Fleet& fleet, Metrics& metrics);
/// The figures of a finished run that ended at `end`.
RadioBenchResult Figures(const RadioBenchConfig& config, const Snapshot& snapshot,
                         const Metrics& metrics, const MasterScheduler& server,
                         const SharedChannel& channel, const Fleet& fleet, Nanos end);

}  // namespace fireswarm::radio::internal
