// The radio bench: the channel loop runs the server and the vehicle endpoints from
// event to event (a server wakeup, the end of a transmission, a fire report, an age
// sample); between events the bench generates fire reports and samples ages.
#include "fireswarm/bench/radio_bench.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <random>
#include <span>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "bench_fleet.hpp"
#include "fireswarm/common/time.hpp"
#include "fireswarm/radio/channel.hpp"
#include "fireswarm/radio/channel_loop.hpp"
#include "fireswarm/radio/channel_router.hpp"
#include "fireswarm/radio/master_scheduler.hpp"
#include "fireswarm/radio/mission_chunks.hpp"
#include "fireswarm/radio/simulation_keys.hpp"

namespace fireswarm::bench {

using common::Nanos;

namespace {

using internal::BenchVehicle;

constexpr Nanos kAgeSamplePeriod = std::chrono::milliseconds(100);
constexpr double kSecondsPerMinute = 60.0;
// Report arrivals draw from their own generator, decorrelated from the channel's.
constexpr std::uint64_t kReportSeedSalt = 0x9E37'79B9'7F4A'7C15ULL;
constexpr int kMaxVehicles = 254;
constexpr double kMaxBenchSeconds = 86'400.0;  // one simulated day
constexpr int kMaxBenchBaud = 10'000'000;
constexpr double kMaxReportsPerMinute = 600.0;
constexpr double kMaxTelemetryHz = 50.0;

template <typename Value>
[[noreturn]] void ThrowConfig(const std::string& field, const std::string& requirement,
                              Value value) {
  std::ostringstream message;
  message << "RadioBenchConfig." << field << " must be " << requirement << ", got " << value;
  throw std::invalid_argument(message.str());
}

class Bench {
 public:
  explicit Bench(const RadioBenchConfig& config)
      : config_(config),
        generation_end_(common::FromSeconds(config.seconds)),
        hard_end_(generation_end_ + common::FromSeconds(config.drain_seconds)),
        telemetry_period_(common::FromSeconds(1.0 / config.telemetry_hz)),
        server_(std::vector<radio::SchedulerConfig>(static_cast<std::size_t>(config.channels),
                                                    SchedulerConfigFor(config))),
        report_rng_(config.seed ^ kReportSeedSalt),
        step_s_(static_cast<std::size_t>(config.channels), 0.0) {
    for (std::size_t k = 0; k < server_.channel_count(); ++k) {
      // Separate frequencies: each channel its own generator (channel 0's as before).
      loops_.push_back(std::make_unique<radio::ChannelLoop>(
          ChannelConfigFor(config), config.seed + k,
          radio::LoopMaster{[this, k] { return server_.NextWakeup(k); },
                            [this, k](Nanos now, std::span<const std::uint8_t> received) {
                              return StepServer(k, now, received);
                            }}));
    }
    for (int i = 0; i < config.vehicles; ++i) {
      const auto id = static_cast<std::uint8_t>(i + 1);
      fleet_.push_back(std::make_unique<BenchVehicle>(EndpointConfigFor(config, id)));
      // Staggered first turns spread the telemetry load over the period.
      const std::size_t channel =
          server_.AddVehicle(id, config.telemetry_hz, telemetry_period_ * i / config.vehicles);
      loops_[channel]->AddVehicle(
          [&v = *fleet_.back()](Nanos now, std::span<const std::uint8_t> received) {
            return StepVehicle(v, now, received);
          });
      fleet_.back()->next_report =
          generation_end_ > Nanos{0} ? NextArrival(Nanos{0}) : Nanos::max();
    }
    if (config.mission_waypoints > 0) {
      for (auto& v : fleet_) {
        internal::QueueMission(server_, *v, config.mission_waypoints);
        ++metrics_.missions_pending;
      }
    }
  }

  void ObserveAir(const AirObserver& observer) {
    for (auto& loop : loops_) loop->channel().SetAirObserver(observer);
  }

  RadioBenchResult Run() {
    Nanos t{0};
    while (!Finished(t)) {
      t = NextEventTime();
      for (auto& loop : loops_) loop->StepAt(t);
      GenerateReports(t);
      if (t == next_sample_) SampleAges(t);
    }
    if (!snapshot_) SnapshotGenerationEnd();
    std::vector<const radio::SharedChannel*> channels;
    for (const auto& loop : loops_) channels.push_back(&loop->channel());
    RadioBenchResult result =
        internal::Figures(config_, *snapshot_, metrics_, server_, channels, fleet_, t);
    for (std::size_t k = 0; k < result.per_channel.size(); ++k) {
      result.per_channel[k].server_step_s = step_s_[k];
    }
    return result;
  }

 private:
  static radio::ChannelConfig ChannelConfigFor(const RadioBenchConfig& config) {
    radio::ChannelConfig c;
    c.baud = config.baud;
    c.turnaround = config.turnaround;
    c.loss = config.loss;
    c.bit_error_rate = config.bit_error_rate;
    return c;
  }

  static radio::SchedulerConfig SchedulerConfigFor(const RadioBenchConfig& config) {
    radio::SchedulerConfig s;
    s.mode = config.mode;
    s.checksum = config.checksum;
    s.timing = radio::LinkTiming{config.baud, radio::kBitsPerByte8N1, config.turnaround};
    s.default_telemetry_hz = config.telemetry_hz;
    if (config.checksum == radio::ChecksumMode::kSecure) {
      std::vector<std::uint8_t> ids;
      for (int i = 1; i <= config.vehicles; ++i) ids.push_back(static_cast<std::uint8_t>(i));
      s.security = radio::SimulationServerSecurity(config.seed, ids);
    }
    return s;
  }

  static radio::VehicleEndpointConfig EndpointConfigFor(const RadioBenchConfig& config,
                                                        std::uint8_t id) {
    radio::VehicleEndpointConfig e;
    e.id = id;
    e.mode = config.mode;
    e.checksum = config.checksum;
    e.timing = radio::LinkTiming{config.baud, radio::kBitsPerByte8N1, config.turnaround};
    if (config.checksum == radio::ChecksumMode::kSecure) {
      e.security = radio::SimulationVehicleSecurity(config.seed, id);
    }
    return e;
  }

  // Poisson arrivals: exponential gaps, by inversion of a uniform draw written out
  // so the sequence does not depend on the standard library's distributions.
  Nanos NextArrival(Nanos after) {
    constexpr double kTwoToMinus53 = 0x1.0p-53;
    const double uniform = static_cast<double>(report_rng_() >> 11U) * kTwoToMinus53;
    const double rate_hz = config_.reports_per_minute / kSecondsPerMinute;
    if (rate_hz <= 0.0) return Nanos::max();
    return after + common::FromSeconds(-std::log1p(-uniform) / rate_hz);
  }

  bool Finished(Nanos t) const {
    if (t >= hard_end_) return true;
    // One period more: the window's last telemetry turns may need resends.
    if (t < generation_end_ + telemetry_period_) return false;
    return metrics_.reports_received == metrics_.reports_sent && metrics_.missions_pending == 0;
  }

  Nanos NextEventTime() const {
    Nanos next = Nanos::max();
    for (const auto& loop : loops_) next = std::min(next, loop->NextEventTime());
    for (const auto& v : fleet_) next = std::min(next, v->next_report);
    if (!snapshot_) next = std::min(next, generation_end_);
    if (next_sample_ <= generation_end_) next = std::min(next, next_sample_);
    return std::min(next, hard_end_);
  }

  // The loop's master step, the first thing at every event time once the channel
  // has advanced: the generation-end snapshot is taken here, before anyone hears
  // what ended at that instant.
  std::vector<radio::Burst> StepServer(std::size_t channel, Nanos t,
                                       std::span<const std::uint8_t> received) {
    if (t == generation_end_) SnapshotGenerationEnd();
    if (received.empty() && t < server_.NextWakeup(channel)) return {};
    const auto started = std::chrono::steady_clock::now();
    std::vector<radio::Burst> bursts = server_.Step(t, channel, received);
    step_s_[channel] += std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    for (const radio::SchedulerEvent& event : server_.TakeEvents()) {
      internal::Record(event, generation_end_, fleet_, metrics_);
    }
    return bursts;
  }

  static std::vector<radio::Burst> StepVehicle(BenchVehicle& v, Nanos t,
                                               std::span<const std::uint8_t> received) {
    // The vehicle samples its state when it hears the channel: the telemetry it
    // sends in a turn is as fresh as the burst that gave the turn.
    v.endpoint.SetTelemetry(internal::SampleTelemetry(v.endpoint.config().id, t));
    return v.endpoint.OnReceive(t, received);
  }

  void GenerateReports(Nanos t) {
    for (auto& v : fleet_) {
      while (v->next_report <= t) {
        v->report_generated.push_back(v->next_report);
        v->endpoint.QueueFireReport(internal::SampleReport(v->endpoint.config().id, t));
        ++metrics_.reports_sent;
        const Nanos next = NextArrival(v->next_report);
        v->next_report = next < generation_end_ ? next : Nanos::max();
      }
    }
  }

  void SampleAges(Nanos t) {
    for (const auto& v : fleet_) {
      if (v->latest_sample) v->ages_s.push_back(common::ToSeconds(t - *v->latest_sample));
    }
    next_sample_ += kAgeSamplePeriod;
  }

  void SnapshotGenerationEnd() {
    internal::Snapshot s;
    for (const auto& loop : loops_) s.busy.push_back(loop->channel().stats().busy);
    s.payload_bytes = server_.stats().payload_bytes;
    for (const auto& v : fleet_) s.payload_bytes += v->endpoint.stats().payload_bytes_for_me;
    snapshot_ = s;
  }

  RadioBenchConfig config_;
  Nanos generation_end_;
  Nanos hard_end_;
  Nanos telemetry_period_;
  radio::ChannelRouter server_;
  std::vector<std::unique_ptr<radio::ChannelLoop>> loops_;  // their master steps use server_
  std::mt19937_64 report_rng_;
  std::vector<double> step_s_;  // per channel: wall time in server_.Step, s
  std::vector<std::unique_ptr<BenchVehicle>> fleet_;
  internal::Metrics metrics_;
  std::optional<internal::Snapshot> snapshot_;
  Nanos next_sample_{0};
};

}  // namespace

void RadioBenchConfig::Validate() const {
  if (vehicles < 1 || vehicles > kMaxVehicles) ThrowConfig("vehicles", "in 1..254", vehicles);
  if (channels < 1 || std::cmp_greater(channels, radio::kMaxChannels)) {
    ThrowConfig("channels", "in 1.." + std::to_string(radio::kMaxChannels), channels);
  }
  // Upper limits bound the simulated work (docs/limits.md).
  if (!(seconds > 0.0 && seconds <= kMaxBenchSeconds)) {
    ThrowConfig("seconds", "in (0, 86400]", seconds);
  }
  if (!(drain_seconds >= 0.0 && drain_seconds <= kMaxBenchSeconds)) {
    ThrowConfig("drain_seconds", "in [0, 86400]", drain_seconds);
  }
  if (baud <= 0 || baud > kMaxBenchBaud) ThrowConfig("baud", "in 1..10000000", baud);
  if (turnaround < Nanos::zero()) ThrowConfig("turnaround", ">= 0 ns", turnaround.count());
  if (!(loss >= 0.0 && loss < 1.0)) ThrowConfig("loss", "in [0, 1)", loss);
  if (!(bit_error_rate >= 0.0 && bit_error_rate < 1.0)) {
    ThrowConfig("bit_error_rate", "in [0, 1)", bit_error_rate);
  }
  if (!(reports_per_minute >= 0.0 && reports_per_minute <= kMaxReportsPerMinute)) {
    ThrowConfig("reports_per_minute", "in [0, 600]", reports_per_minute);
  }
  if (!(telemetry_hz > 0.0 && telemetry_hz <= kMaxTelemetryHz)) {
    ThrowConfig("telemetry_hz", "in (0, 50]", telemetry_hz);
  }
  if (mission_waypoints < 0 || std::cmp_greater(mission_waypoints, radio::kMaxMissionWaypoints)) {
    ThrowConfig("mission_waypoints", "in 0.." + std::to_string(radio::kMaxMissionWaypoints),
                mission_waypoints);
  }
}

RadioBenchResult RunRadioBench(const RadioBenchConfig& config, const AirObserver& observer) {
  config.Validate();
  Bench bench(config);
  if (observer) bench.ObserveAir(observer);
  return bench.Run();
}

}  // namespace fireswarm::bench
