// The radio bench's simulated vehicles and its bookkeeping: what each vehicle
// generates, what the server received, and the figures computed from both.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "fireswarm/bench/radio_bench.hpp"
#include "fireswarm/common/time.hpp"
#include "fireswarm/radio/channel.hpp"
#include "fireswarm/radio/channel_router.hpp"
#include "fireswarm/radio/master_scheduler.hpp"
#include "fireswarm/radio/vehicle_endpoint.hpp"

namespace fireswarm::bench::internal {

/// Accepts every command and mission chunk, as a vehicle with a free mission store.
class BenchHandler final : public radio::VehicleRequestHandler {
 public:
  radio::CommandResult OnCommand(const radio::Command& command) override;
  radio::MissionAckStatus OnMissionChunk(const radio::MissionChunk& chunk) override;
  radio::ParamValue OnParamRead(const radio::ParamRead& read) override;
  radio::ParamValue OnParamWrite(const radio::ParamWrite& write) override;

 private:
  std::vector<bool> chunks_stored_;
};

struct BenchVehicle {
  explicit BenchVehicle(const radio::VehicleEndpointConfig& config) : endpoint(config, handler) {}
  BenchHandler handler;  // before endpoint, which keeps a reference to it
  radio::VehicleEndpoint endpoint;
  common::Nanos next_report = common::Nanos::max();  // next generation time
  std::vector<common::Nanos> report_generated;       // by report_id
  std::uint64_t telemetry_received = 0;  // telemetry turns due in the generation window, served
  std::optional<common::Nanos>
      latest_sample;           // sampling time of its latest telemetry at the server
  std::vector<double> ages_s;  // telemetry age at the server, every age sample
  int chunks_left = 0;         // mission chunks not yet acknowledged
};

using Fleet = std::vector<std::unique_ptr<BenchVehicle>>;

struct Metrics {
  std::uint64_t reports_sent = 0;
  std::uint64_t reports_received = 0;
  std::vector<double> report_latencies_s;
  int missions_pending = 0;  // vehicles whose upload is still running
  bool mission_failed = false;
  common::Nanos mission_done{0};  // when the last upload completed
};

/// Channel figures at the end of the generation window.
struct Snapshot {
  std::vector<common::Nanos> busy;  ///< per channel
  std::uint64_t payload_bytes = 0;
};

/// State of vehicle `id` at `now` (a fixed position; only the frame's size matters).
radio::Telemetry SampleTelemetry(std::uint8_t id, common::Nanos now);
/// A fire report detected by vehicle `id` at `now`.
radio::FireReport SampleReport(std::uint8_t id, common::Nanos now);
/// Queues a `waypoints`-waypoint mission (1..kMaxMissionWaypoints) for `vehicle` in
/// chunks; sets chunks_left.
void QueueMission(radio::ChannelRouter& server, BenchVehicle& vehicle, int waypoints);
/// Applies one scheduler event to the bookkeeping.
void Record(const radio::SchedulerEvent& event, common::Nanos generation_end, Fleet& fleet,
            Metrics& metrics);
/// The figures of a finished run that ended at `end`.
RadioBenchResult Figures(const RadioBenchConfig& config, const Snapshot& snapshot,
                         const Metrics& metrics, const radio::ChannelRouter& server,
                         std::span<const radio::SharedChannel* const> channels, const Fleet& fleet,
                         common::Nanos end);

}  // namespace fireswarm::bench::internal
