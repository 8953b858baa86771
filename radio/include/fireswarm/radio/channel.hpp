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

/// Loss and bit errors rise with transmitter-receiver distance d (metres, 3-D).
/// Range factor f(d): 0 up to `clean_range_m`, ((d - clean) / (max - clean))^2
/// between the two, 1 at and beyond `max_range_m` (every reception lost there).
/// Loss probability: loss + (1 - loss) * f.
/// Bit-error rate: ber + (1 - ber) * f * bit_error_rate_at_max_range.
/// The defaults (infinite ranges) switch the range model off.
struct RangeModel {
  double clean_range_m = std::numeric_limits<double>::infinity();
  double max_range_m = std::numeric_limits<double>::infinity();
  /// Extra bit-error rate as the range factor reaches 1, in [0, 1].
  double bit_error_rate_at_max_range = 1e-3;
};

/// A window of extra loss on the channel: a burst of interference (or a jammer)
/// that every receiver suffers. A transmission that ends in [from, until) is lost
/// for each receiver with probability `loss` besides the channel's own loss, drawn
/// from the channel's generator: 1 - (1 - own) * (1 - loss) in all.
struct LossBurst {
  Nanos from{0};
  Nanos until{0};
  double loss = 1.0;  ///< in [0, 1]; 1 is a dead channel for the window
};

struct ChannelConfig {
  int baud = 57'600;
  int bits_per_byte = kBitsPerByte8N1;
  /// Receive-to-transmit switch time of a radio: a transmission decided at time t
  /// starts no earlier than t + turnaround.
  Nanos turnaround = std::chrono::milliseconds(5);
  double loss = 0.0;            ///< probability a transmission is lost for one receiver
  double bit_error_rate = 0.0;  ///< probability each received data bit is flipped
  RangeModel range;
  /// Windows of extra loss (LossBurst), in any order; they may overlap (the
  /// highest loss applies).
  std::vector<LossBurst> loss_bursts;
  /// Throws std::invalid_argument naming the field when a value is out of range
  /// (baud <= 0, bits_per_byte < 8, negative turnaround, a probability outside
  /// [0, 1], a negative or NaN range, max_range_m < clean_range_m, a loss burst
  /// that ends before it starts).
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

/// Counters over resolved transmissions, except `busy`, which runs up to now().
struct ChannelStats {
  std::uint64_t transmissions = 0;
  std::uint64_t bytes_sent = 0;
  std::uint64_t collisions = 0;       ///< transmissions lost to an overlap
  std::uint64_t receptions = 0;       ///< (transmission, receiver) pairs delivered
  std::uint64_t receptions_lost = 0;  ///< (transmission, receiver) pairs dropped by loss
  std::uint64_t bits_flipped = 0;
  Nanos busy{0};  ///< time at least one radio was transmitting (overlaps counted once)
  friend bool operator==(const ChannelStats&, const ChannelStats&) = default;
};

/// Not thread-safe: one simulation loop owns the channel.
class SharedChannel {
 public:
  /// `seed` seeds the channel's own random generator (loss and bit errors): the
  /// same seed and the same calls give the same bytes, stats and air records.
  /// Throws std::invalid_argument when the configuration is invalid.
  SharedChannel(const ChannelConfig& config, std::uint64_t seed);

  /// Adds a radio; every radio hears every transmission except its own (radios
  /// added while a transmission is on the air hear it too). IDs count from 0.
  /// Throws std::invalid_argument when a coordinate is not finite.
  RadioId AddRadio(RadioPosition position = {});
  /// Moves a radio; the range model uses positions at the end of each transmission.
  /// Throws std::out_of_range for an unknown radio, std::invalid_argument for a
  /// coordinate that is not finite.
  void SetPosition(RadioId radio, RadioPosition position);

  /// Starts a transmission of `bytes` from `radio` at `start`, decided at `now`.
  /// A radio that is receiving needs start >= now + turnaround; a radio still
  /// transmitting at `now` may append back to back (start >= end of its last
  /// transmission). Returns the end time, start + AirtimeOf(bytes.size()); an
  /// empty burst puts nothing on the air and returns `start`.
  /// Throws std::logic_error when the start is too early or `now` lies before
  /// now(); std::out_of_range (a logic_error) for an unknown radio.
  Nanos Transmit(RadioId radio, Nanos now, Nanos start, std::span<const std::uint8_t> bytes);

  /// Moves the channel's time to `t` and resolves, in order of end time, every
  /// transmission that ended at or before `t`: collided ones are lost to everyone;
  /// the others reach each other radio (with loss and bit errors).
  /// Throws std::logic_error when `t` lies before now(). The air observer must not
  /// call AdvanceTo().
  void AdvanceTo(Nanos t);

  /// Earliest end of a transmission not yet resolved; nullopt when the air is quiet.
  std::optional<Nanos> NextEventTime() const;

  /// Appends the bytes `radio` received so far (in order of transmission end) to
  /// `out` and empties its inbox. Throws std::out_of_range for an unknown radio.
  void Drain(RadioId radio, std::vector<std::uint8_t>& out);

  /// Called once per transmission when it is resolved, in resolution order.
  void SetAirObserver(std::function<void(const AirRecord&)> observer);

  /// The end of `radio`'s latest transmission (0 before its first): it is on the
  /// air until then. Throws std::out_of_range for an unknown radio.
  Nanos TransmittingUntil(RadioId radio) const { return radios_.at(radio).transmitting_until; }

  Nanos now() const { return now_; }
  const ChannelConfig& config() const { return config_; }
  const ChannelStats& stats() const { return stats_; }
  std::size_t radio_count() const { return radios_.size(); }
  /// Time `bytes` bytes occupy on the air at the configured baud and framing.
  Nanos AirtimeOf(std::size_t bytes) const {
    return Airtime(bytes, config_.baud, config_.bits_per_byte);
  }

 private:
  struct Transmission {
    RadioId transmitter;
    Nanos start;
    Nanos end;
    std::uint64_t sequence;  // submission order, breaks ties between equal ends
    std::vector<std::uint8_t> bytes;
    bool collided = false;
    // Radios whose own transmissions overlap this one: they cannot hear it.
    std::vector<RadioId> overlapping_transmitters{};
  };
  struct Radio {
    RadioPosition position;
    Nanos transmitting_until{0};  // end of its latest transmission
    std::vector<std::uint8_t> inbox;
  };

  Radio& RadioAt(RadioId radio);
  void AddBusyTime(Nanos from, Nanos to);
  void Resolve(const Transmission& transmission);
  void Deliver(const Transmission& transmission, RadioId receiver);
  double RangeFactor(const Radio& from, const Radio& to) const;
  /// The highest loss of the loss bursts active at `t` (0 outside them).
  double BurstLossAt(Nanos t) const;

  ChannelConfig config_;
  std::mt19937_64 rng_;
  std::vector<Radio> radios_;
  std::vector<Transmission> in_flight_;  // not yet resolved, any order
  std::uint64_t next_sequence_ = 0;
  Nanos now_{0};
  ChannelStats stats_;
  std::function<void(const AirRecord&)> observer_;
};

}  // namespace fireswarm::radio
