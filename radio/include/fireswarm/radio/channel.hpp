// A model of one shared half-duplex RF channel that every radio hears (seed
// 5.3.1.1, scaled to a fleet). Serial 8N1 timing (57,600 baud = 5,760 bytes/s),
// a radio turnaround before a transmission can start, loss and bit errors that can
// grow with distance, and collisions: transmissions overlapping in time are both
// lost, to every receiver. Time is simulated, in exact integer nanoseconds.
//
// Use: radios call Transmit(); the owner of the simulation loop calls AdvanceTo(t)
// at every event time (NextEventTime()); each radio then drains what it received.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <random>
#include <span>
#include <vector>

#include "fireswarm/radio/time.hpp"

namespace fireswarm::radio {

/// Loss and bit errors rise with transmitter-receiver distance: below
/// `clean_range_m` only the base rates apply; between clean_range_m and
/// max_range_m the extra loss rises as ((d - clean) / (max - clean))^2 to 1.
/// The bit-error rate scales by the same factor: ber(d) = ber0 + (1 - ber0) * f * 1e-3.
struct RangeModel {
  double clean_range_m = std::numeric_limits<double>::infinity();
  double max_range_m = std::numeric_limits<double>::infinity();
};

struct ChannelConfig {
  int baud = 57'600;
  int bits_per_byte = kBitsPerByte8N1;
  /// Receive-to-transmit switch time of a radio: a transmission decided at time t
  /// starts no earlier than t + turnaround.
  Nanos turnaround = std::chrono::milliseconds(5);
  double loss = 0.0;            ///< probability a transmission is lost for one receiver
  double bit_error_rate = 0.0;  ///< probability each received bit is flipped
  RangeModel range;
  /// Throws std::invalid_argument naming the field when a value is out of range.
  void Validate() const;
};

using RadioId = std::uint32_t;

/// Position of a radio in local ENU metres, for the range model.
struct RadioPosition {
  double east_m = 0.0;
  double north_m = 0.0;
  double up_m = 0.0;
};

/// One transmission as it was on the air, for captures and logs.
struct AirRecord {
  RadioId transmitter = 0;
  Nanos start{0};
  Nanos end{0};
  bool collided = false;
  std::span<const std::uint8_t> bytes;  ///< valid during the observer call only
};

struct ChannelStats {
  std::uint64_t transmissions = 0;
  std::uint64_t bytes_sent = 0;
  std::uint64_t collisions = 0;           ///< transmissions lost to an overlap
  std::uint64_t receptions_lost = 0;      ///< (transmission, receiver) pairs dropped by loss
  std::uint64_t bits_flipped = 0;
  Nanos busy{0};                          ///< time at least one radio was transmitting
};

class SharedChannel {
 public:
  /// `seed` seeds the channel's own random generator (loss and bit errors).
  /// Throws std::invalid_argument when the configuration is invalid.
  SharedChannel(const ChannelConfig& config, std::uint64_t seed);

  /// Adds a radio; every radio hears every transmission except its own.
  RadioId AddRadio(RadioPosition position = {});
  void SetPosition(RadioId radio, RadioPosition position);

  /// Starts a transmission of `bytes` from `radio` at `start`, decided at `now`.
  /// A radio that is receiving needs start >= now + turnaround; a radio still
  /// transmitting may append back to back (start >= end of its transmission).
  /// Returns the end time. Throws std::logic_error when the start is too early
  /// or `now` lies before the channel's current time.
  Nanos Transmit(RadioId radio, Nanos now, Nanos start, std::span<const std::uint8_t> bytes);

  /// Resolves every transmission that ended at or before `t`: collided ones are
  /// lost; the others are delivered to each receiver (with loss and bit errors).
  void AdvanceTo(Nanos t);

  /// Earliest end of a transmission not yet resolved; nullopt when the air is quiet.
  std::optional<Nanos> NextEventTime() const;

  /// Appends the bytes `radio` received so far (in order of transmission end) to `out`.
  void Drain(RadioId radio, std::vector<std::uint8_t>& out);

  /// Called once per transmission when it is resolved.
  void SetAirObserver(std::function<void(const AirRecord&)> observer);

  Nanos now() const { return now_; }
  const ChannelConfig& config() const { return config_; }
  const ChannelStats& stats() const { return stats_; }
  Nanos AirtimeOf(std::size_t bytes) const { return Airtime(bytes, config_.baud, config_.bits_per_byte); }

 private:
  struct Transmission {
    RadioId transmitter;
    Nanos start;
    Nanos end;
    std::vector<std::uint8_t> bytes;
    bool collided = false;
  };
  struct Radio {
    RadioPosition position;
    Nanos transmitting_until{0};
    std::vector<std::uint8_t> inbox;
  };

  void Resolve(Transmission& transmission);
  double LossProbability(const Radio& from, const Radio& to) const;
  double BitErrorRate(const Radio& from, const Radio& to) const;

  ChannelConfig config_;
  std::mt19937_64 rng_;
  std::vector<Radio> radios_;
  std::vector<Transmission> in_flight_;  // not yet resolved, any order
  Nanos now_{0};
  Nanos busy_until_{0};  // end of the latest transmission counted in stats_.busy
  ChannelStats stats_;
  std::function<void(const AirRecord&)> observer_;
};

}  // namespace fireswarm::radio
