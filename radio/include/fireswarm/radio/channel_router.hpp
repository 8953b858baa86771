// Several radio channels driven by one server (issue 21): one 57,600 baud
// half-duplex channel holds about 80 drones at 1 Hz, so a larger fleet flies on
// several frequencies, one modem each. ChannelRouter owns one MasterScheduler per
// channel and routes every request to the channel of its vehicle, so the server
// core calls SendCommand / SendMissionChunk / ReadParam / WriteParam as it would
// on a single scheduler. Channels are separate frequencies: each has its own
// bytes, its own exchanges, its own statistics.
//
// Request IDs are unique across channels (channel in the low bits). A channel
// whose every vehicle went silent (VehicleSilent and not heard since) is reported
// silent: a dead modem or link looks exactly like that, and the other channels
// fly on.
//
// A pure core like MasterScheduler: Step(now, channel, bytes) -> bursts for that
// channel. No clock, no socket.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "fireswarm/radio/master_scheduler.hpp"

namespace fireswarm::radio {

/// Most channels one server drives.
inline constexpr std::size_t kMaxChannels = 16;

/// Bytes a channel's master transmitted (every burst) and received.
struct ChannelBytes {
  std::uint64_t sent = 0;
  std::uint64_t received = 0;
};

/// A channel went silent (every vehicle on it silent) or was heard again.
struct ChannelHealth {
  bool silent = false;
  Nanos since{0};  ///< when it turned silent or was last heard again
};

class ChannelRouter {
 public:
  /// One SchedulerConfig per channel (1..kMaxChannels of them; channel k is
  /// configs[k]). Throws std::invalid_argument naming the channel when a
  /// configuration is invalid or the count is out of range.
  explicit ChannelRouter(const std::vector<SchedulerConfig>& configs);
  ~ChannelRouter();
  ChannelRouter(const ChannelRouter&) = delete;
  ChannelRouter& operator=(const ChannelRouter&) = delete;

  /// Registers a vehicle on `channel`, or (nullopt) on the channel with the fewest
  /// vehicles (the lowest index among equals): balanced groups. Returns the
  /// channel. Throws std::invalid_argument as MasterScheduler::AddVehicle, or for
  /// a channel out of range.
  std::size_t AddVehicle(std::uint8_t vehicle, double telemetry_hz = 0.0,
                         Nanos first_due = Nanos{0},
                         std::optional<std::size_t> channel = std::nullopt);
  /// The channel a vehicle is on. Throws std::invalid_argument for an unknown one.
  std::size_t ChannelOf(std::uint8_t vehicle) const;

  /// As MasterScheduler's, on the vehicle's channel; IDs unique across channels.
  void SetTelemetryRate(std::uint8_t vehicle, double telemetry_hz);
  double TelemetryRateHz(std::uint8_t vehicle) const;
  RequestId SendCommand(std::uint8_t vehicle, const Command& command, bool urgent = false);
  RequestId SendMissionChunk(std::uint8_t vehicle, const MissionChunk& chunk);
  RequestId ReadParam(std::uint8_t vehicle, std::uint16_t param_id);
  RequestId WriteParam(std::uint8_t vehicle, std::uint16_t param_id, float value);

  /// Steps channel `channel` with the bytes it received up to `now`; returns the
  /// bursts to transmit on that channel. `now` must not decrease per channel.
  /// Never throws (a channel out of range is an internal error: asserted).
  std::vector<Burst> Step(Nanos now, std::size_t channel, std::span<const std::uint8_t> received);
  /// When any channel must next be stepped without new bytes.
  Nanos NextWakeup() const;
  /// When `channel` must next be stepped without new bytes.
  Nanos NextWakeup(std::size_t channel) const;
  /// Events since the last call, every channel's, request IDs made global.
  std::vector<SchedulerEvent> TakeEvents();

  std::size_t channel_count() const { return channels_.size(); }
  /// Channel `channel`'s scheduler (its own stats, config, exchange).
  const MasterScheduler& channel(std::size_t channel) const;
  /// Vehicles on `channel`, ascending.
  std::vector<std::uint8_t> VehiclesOn(std::size_t channel) const;
  /// Whether `channel` is silent: it has vehicles and none answers.
  const ChannelHealth& health(std::size_t channel) const;

  /// Bytes transmitted and received on `channel` since the start.
  const ChannelBytes& bytes(std::size_t channel) const;

  /// Every channel's counters added up.
  SchedulerStats stats() const;
  ParserStats parser_stats() const;
  /// Channel 0's configuration (checksum and security are the same on all).
  const SchedulerConfig& config() const { return channel(0).config(); }
  /// Channel 0's next sequence number (the journal's restart point).
  std::uint16_t next_sequence() const { return channel(0).next_sequence(); }
  /// Channel 0's exchange in progress.
  std::optional<ExchangeTiming> exchange() const { return channel(0).exchange(); }

 private:
  void Track(std::size_t channel, const SchedulerEvent& event);

  std::vector<std::unique_ptr<MasterScheduler>> channels_;
  std::vector<ChannelHealth> health_;
  std::vector<ChannelBytes> bytes_;
  std::map<std::uint8_t, std::size_t> channel_of_;
  std::map<std::uint8_t, bool> silent_;  // vehicle -> silent and not heard since
  std::vector<SchedulerEvent> events_;
};

}  // namespace fireswarm::radio
