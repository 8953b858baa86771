// The shared half-duplex channel (seed 5.3.1.1, scaled to a fleet). Transmissions
// are checked for overlaps when they are submitted and resolved when the channel's
// time passes their end. Because a start is never before the channel's time, every
// transmission that can overlap one still on the air is already known by its end.
#include "fireswarm/radio/channel.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

namespace fireswarm::radio {
namespace {

constexpr int kDataBitsPerByte = 8;

template <typename Value>
[[noreturn]] void ThrowInvalid(const char* field, const char* requirement, Value value) {
  std::ostringstream message;
  message << "ChannelConfig." << field << " must be " << requirement << ", got " << value;
  throw std::invalid_argument(message.str());
}

// `!(a <= x && x <= b)` rather than `x < a || x > b` so that NaN fails too.
void RequireProbability(const char* field, double value) {
  if (!(value >= 0.0 && value <= 1.0)) ThrowInvalid(field, "in [0, 1]", value);
}

void RequireFinite(const RadioPosition& position) {
  if (!std::isfinite(position.east_m) || !std::isfinite(position.north_m) ||
      !std::isfinite(position.up_m)) {
    throw std::invalid_argument("RadioPosition must have finite east_m, north_m and up_m");
  }
}

// Uniform in [0, 1) from the top 53 bits; written out (not std::uniform_real_distribution)
// so the draws do not depend on the standard library's implementation.
double UniformUnit(std::mt19937_64& rng) {
  constexpr double kTwoToMinus53 = 0x1.0p-53;
  return static_cast<double>(rng() >> 11U) * kTwoToMinus53;
}

// Number of unflipped bits before the next flipped one, geometric with success
// probability `p` in (0, 1], by inversion. A double, because for tiny `p` it can
// exceed every integer type; callers compare it with the bits left.
double GeometricGap(std::mt19937_64& rng, double p) {
  if (p >= 1.0) return 0.0;
  return std::floor(std::log1p(-UniformUnit(rng)) / std::log1p(-p));
}

}  // namespace

void ChannelConfig::Validate() const {
  if (baud <= 0) ThrowInvalid("baud", "> 0", baud);
  if (bits_per_byte < kDataBitsPerByte) ThrowInvalid("bits_per_byte", ">= 8", bits_per_byte);
  if (turnaround < Nanos::zero()) ThrowInvalid("turnaround", ">= 0 ns", turnaround.count());
  RequireProbability("loss", loss);
  RequireProbability("bit_error_rate", bit_error_rate);
  RequireProbability("range.bit_error_rate_at_max_range", range.bit_error_rate_at_max_range);
  if (!(range.clean_range_m >= 0.0))
    ThrowInvalid("range.clean_range_m", ">= 0 m", range.clean_range_m);
  if (!(range.max_range_m >= range.clean_range_m)) {
    ThrowInvalid("range.max_range_m", ">= range.clean_range_m", range.max_range_m);
  }
  for (const LossBurst& burst : loss_bursts) {
    RequireProbability("loss_bursts.loss", burst.loss);
    if (burst.until < burst.from) {
      ThrowInvalid("loss_bursts.until", ">= from", burst.until.count());
    }
  }
}

SharedChannel::SharedChannel(const ChannelConfig& config, std::uint64_t seed)
    : config_(config), rng_(seed) {
  config_.Validate();
}

RadioId SharedChannel::AddRadio(RadioPosition position) {
  RequireFinite(position);
  radios_.push_back(Radio{position, Nanos{0}, {}});
  return static_cast<RadioId>(radios_.size() - 1);
}

void SharedChannel::SetPosition(RadioId radio, RadioPosition position) {
  RequireFinite(position);
  RadioAt(radio).position = position;
}

SharedChannel::Radio& SharedChannel::RadioAt(RadioId radio) {
  if (radio >= radios_.size()) {
    throw std::out_of_range("SharedChannel: unknown radio " + std::to_string(radio) + " (" +
                            std::to_string(radios_.size()) + " radios)");
  }
  return radios_[radio];
}

Nanos SharedChannel::Transmit(RadioId radio, Nanos now, Nanos start,
                              std::span<const std::uint8_t> bytes) {
  Radio& sender = RadioAt(radio);
  // Built only on the error paths: Transmit runs once per burst on the air.
  const auto who = [radio] { return "SharedChannel: radio " + std::to_string(radio); };
  if (now < now_) {
    throw std::logic_error(who() + " decides at " + std::to_string(now.count()) +
                           " ns, before the channel time " + std::to_string(now_.count()) + " ns");
  }
  // Half duplex: only a radio still in transmit mode skips the receive-to-transmit turnaround.
  if (now < sender.transmitting_until) {
    if (start < sender.transmitting_until) {
      throw std::logic_error(who() + " starts at " + std::to_string(start.count()) +
                             " ns, inside its own transmission ending at " +
                             std::to_string(sender.transmitting_until.count()) + " ns");
    }
  } else if (start < now + config_.turnaround) {
    throw std::logic_error(who() + " starts at " + std::to_string(start.count()) +
                           " ns, before the turnaround ends at " +
                           std::to_string((now + config_.turnaround).count()) + " ns");
  }
  if (bytes.empty()) return start;

  Transmission sent{.transmitter = radio,
                    .start = start,
                    .end = start + AirtimeOf(bytes.size()),
                    .sequence = next_sequence_++,
                    .bytes = {bytes.begin(), bytes.end()}};
  for (Transmission& other : in_flight_) {
    if (other.start < sent.end && sent.start < other.end) {
      other.collided = true;
      sent.collided = true;
      other.overlapping_transmitters.push_back(sent.transmitter);
      sent.overlapping_transmitters.push_back(other.transmitter);
    }
  }
  sender.transmitting_until = sent.end;
  in_flight_.push_back(std::move(sent));
  return in_flight_.back().end;
}

void SharedChannel::AdvanceTo(Nanos t) {
  if (t < now_) {
    throw std::logic_error("SharedChannel: AdvanceTo(" + std::to_string(t.count()) +
                           " ns) lies before the channel time " + std::to_string(now_.count()) +
                           " ns");
  }
  AddBusyTime(now_, t);
  now_ = t;

  const auto ended = std::partition(in_flight_.begin(), in_flight_.end(),
                                    [t](const Transmission& x) { return x.end > t; });
  if (ended == in_flight_.end()) return;
  // Taken out of in_flight_ first so the observer may Transmit() while they resolve.
  std::vector<Transmission> resolving(std::make_move_iterator(ended),
                                      std::make_move_iterator(in_flight_.end()));
  in_flight_.erase(ended, in_flight_.end());
  std::sort(resolving.begin(), resolving.end(), [](const Transmission& a, const Transmission& b) {
    return std::pair(a.end, a.sequence) < std::pair(b.end, b.sequence);
  });
  for (const Transmission& transmission : resolving) Resolve(transmission);
}

// Every transmission that can overlap [from, to) is in in_flight_: resolved ones
// ended by `from`, and later ones cannot start before `to`.
void SharedChannel::AddBusyTime(Nanos from, Nanos to) {
  if (to <= from || in_flight_.empty()) return;
  std::vector<std::pair<Nanos, Nanos>> spans;
  for (const Transmission& x : in_flight_) {
    const Nanos start = std::max(x.start, from);
    const Nanos end = std::min(x.end, to);
    if (start < end) spans.emplace_back(start, end);
  }
  std::sort(spans.begin(), spans.end());
  Nanos covered_until = from;
  for (const auto& [start, end] : spans) {
    if (end <= covered_until) continue;
    stats_.busy += end - std::max(start, covered_until);
    covered_until = end;
  }
}

void SharedChannel::Resolve(const Transmission& transmission) {
  ++stats_.transmissions;
  stats_.bytes_sent += transmission.bytes.size();
  if (transmission.collided) {
    // Counted once per transmission; its bytes reach nobody.
    ++stats_.collisions;
  } else {
    for (RadioId receiver = 0; receiver < radios_.size(); ++receiver) {
      if (receiver != transmission.transmitter) Deliver(transmission, receiver);
    }
  }
  if (observer_) {
    observer_(AirRecord{transmission.transmitter, transmission.start, transmission.end,
                        transmission.collided, transmission.bytes});
  }
}

void SharedChannel::Deliver(const Transmission& transmission, RadioId receiver) {
  // A radio transmitting during any part of the transmission cannot hear it (half
  // duplex). Such overlaps also collide, so this only states the rule explicitly.
  const auto& overlapping = transmission.overlapping_transmitters;
  if (std::find(overlapping.begin(), overlapping.end(), receiver) != overlapping.end()) return;

  Radio& to = radios_[receiver];
  const double range_factor = RangeFactor(radios_[transmission.transmitter], to);
  double loss = config_.loss + (1.0 - config_.loss) * range_factor;
  // Outside a burst the loss is left exactly as it was (no rounding through the
  // combination), so a scenario without bursts draws as before.
  if (const double burst = BurstLossAt(transmission.end); burst > 0.0) {
    loss = 1.0 - (1.0 - loss) * (1.0 - burst);
  }
  // No draw when the outcome is certain, so a lossless channel uses no randomness.
  if (loss >= 1.0 || (loss > 0.0 && UniformUnit(rng_) < loss)) {
    ++stats_.receptions_lost;
    return;
  }
  ++stats_.receptions;
  const std::size_t first = to.inbox.size();
  to.inbox.insert(to.inbox.end(), transmission.bytes.begin(), transmission.bytes.end());

  const double bit_error_rate =
      config_.bit_error_rate +
      (1.0 - config_.bit_error_rate) * range_factor * config_.range.bit_error_rate_at_max_range;
  if (bit_error_rate <= 0.0) return;
  // Jump from flip to flip with geometric gaps: the cost follows the number of
  // flipped bits, not the number of bytes. Bit k of a byte is its k-th bit on the
  // air (serial sends the least significant bit first).
  const std::uint64_t total_bits = std::uint64_t{transmission.bytes.size()} * kDataBitsPerByte;
  std::uint64_t bit = 0;
  while (true) {
    const double gap = GeometricGap(rng_, bit_error_rate);
    if (gap >= static_cast<double>(total_bits - bit)) break;
    bit += static_cast<std::uint64_t>(gap);
    to.inbox[first + bit / kDataBitsPerByte] ^=
        static_cast<std::uint8_t>(1U << (bit % kDataBitsPerByte));
    ++stats_.bits_flipped;
    if (++bit >= total_bits) break;
  }
}

double SharedChannel::BurstLossAt(Nanos t) const {
  double loss = 0.0;
  for (const LossBurst& burst : config_.loss_bursts) {
    if (burst.from <= t && t < burst.until) loss = std::max(loss, burst.loss);
  }
  return loss;
}

double SharedChannel::RangeFactor(const Radio& from, const Radio& to) const {
  const RangeModel& range = config_.range;
  const double distance_m = std::hypot(from.position.east_m - to.position.east_m,
                                       from.position.north_m - to.position.north_m,
                                       from.position.up_m - to.position.up_m);
  if (!(distance_m > range.clean_range_m)) return 0.0;
  if (distance_m >= range.max_range_m) return 1.0;
  const double fraction =
      (distance_m - range.clean_range_m) / (range.max_range_m - range.clean_range_m);
  return fraction * fraction;
}

std::optional<Nanos> SharedChannel::NextEventTime() const {
  if (in_flight_.empty()) return std::nullopt;
  return std::min_element(
             in_flight_.begin(), in_flight_.end(),
             [](const Transmission& a, const Transmission& b) { return a.end < b.end; })
      ->end;
}

void SharedChannel::Drain(RadioId radio, std::vector<std::uint8_t>& out) {
  std::vector<std::uint8_t>& inbox = RadioAt(radio).inbox;
  out.insert(out.end(), inbox.begin(), inbox.end());
  inbox.clear();
}

void SharedChannel::SetAirObserver(std::function<void(const AirRecord&)> observer) {
  observer_ = std::move(observer);
}

}  // namespace fireswarm::radio
