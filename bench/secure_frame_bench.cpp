// CPU cost per frame of secure mode against crc16: build (seal) and check (open)
// one Telemetry frame, the fleet's most common frame. `fireswarm radio-bench
// --checksum secure` gives the airtime side (docs/protocol.md, README figures).
#include <benchmark/benchmark.h>

#include <cstdint>
#include <vector>

#include "fireswarm/radio/frame_security.hpp"
#include "fireswarm/radio/parser.hpp"
#include "fireswarm/radio/simulation_keys.hpp"

namespace {

using fireswarm::radio::ChecksumMode;
namespace radio = fireswarm::radio;

constexpr std::uint8_t kVehicle = 7;
constexpr std::uint64_t kSeed = 1;

radio::Message SampleTelemetry() {
  radio::Telemetry telemetry;
  telemetry.header = {kVehicle, 1};
  telemetry.lat_deg = 46.5;
  telemetry.lon_deg = 7.5;
  telemetry.altitude_m = 60.0;
  return telemetry;
}

// Builds one telemetry frame per iteration; frame size reported as a counter.
void BM_BuildFrame(benchmark::State& state, ChecksumMode mode) {
  auto security = radio::SimulationVehicleSecurity(kSeed, kVehicle);
  const radio::Message telemetry = SampleTelemetry();
  std::vector<std::uint8_t> out;
  out.reserve(radio::kMaxFrameSize);
  for (auto _ : state) {
    out.clear();
    radio::AppendFrameFor(out, radio::kServerId, telemetry, mode, security.get());
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["frame_bytes"] = static_cast<double>(out.size());
}

// Parses and checks (secure: authenticates and decrypts) one telemetry frame per
// iteration, as the server does; fresh counters so none is a replay.
void BM_ReadFrame(benchmark::State& state, ChecksumMode mode) {
  auto vehicle = radio::SimulationVehicleSecurity(kSeed, kVehicle);
  const std::vector<std::uint8_t> ids{kVehicle};
  auto server = radio::SimulationServerSecurity(kSeed, ids);
  constexpr std::size_t kFrames = 1 << 16;
  std::vector<std::vector<std::uint8_t>> frames(kFrames);
  for (auto& frame : frames) {
    radio::AppendFrameFor(frame, radio::kServerId, SampleTelemetry(), mode, vehicle.get());
  }
  radio::FrameParser parser(mode);
  std::vector<std::uint8_t> scratch;
  std::size_t next = 0;
  std::size_t opened = 0;
  for (auto _ : state) {
    if (next == kFrames) {
      // Every counter was taken: a fresh server window for the next round.
      state.PauseTiming();
      server = radio::SimulationServerSecurity(kSeed, ids);
      next = 0;
      state.ResumeTiming();
    }
    parser.Feed(frames[next++], [&](const radio::FrameView& frame) {
      const radio::OpenedData data = radio::OpenFrameData(frame, mode, server.get(), scratch);
      opened += data.status == radio::OpenStatus::kOk ? 1 : 0;
    });
  }
  benchmark::DoNotOptimize(opened);
  if (opened != static_cast<std::size_t>(state.iterations())) state.SkipWithError("frame refused");
}

BENCHMARK_CAPTURE(BM_BuildFrame, crc16, ChecksumMode::kCrc16);
BENCHMARK_CAPTURE(BM_BuildFrame, secure, ChecksumMode::kSecure);
BENCHMARK_CAPTURE(BM_ReadFrame, crc16, ChecksumMode::kCrc16);
BENCHMARK_CAPTURE(BM_ReadFrame, secure, ChecksumMode::kSecure);

}  // namespace

BENCHMARK_MAIN();
