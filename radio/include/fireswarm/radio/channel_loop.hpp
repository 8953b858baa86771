// The event loop of a simulated radio link: one master (the server core, a
// MasterScheduler) and N vehicle-side endpoints on one SharedChannel, stepped in
// simulated time from event to event. At each event time, in this order: the
// channel advances and resolves what ended; the master hears its bytes and steps
// (with or without bytes); then each vehicle, in the order added, hears its bytes
// and, when it heard any, steps; every burst goes on the air as it is returned.
// The next event time is the earlier of the master's wake-up and the channel's
// next transmission end. No clock, socket or LCM: the whole-mission runner, the
// closed-loop tests and the radio bench all run their link through this one loop.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <vector>

#include "fireswarm/radio/channel.hpp"
#include "fireswarm/radio/discipline.hpp"
#include "fireswarm/radio/time.hpp"

namespace fireswarm::radio {

/// One radio's core as the loop sees it: the bytes it heard up to `now` in, the
/// bursts to put on the air out (each starting no earlier than now + turnaround).
using RadioStep =
    std::function<std::vector<Burst>(Nanos now, std::span<const std::uint8_t> received)>;

/// The master end of a ChannelLoop.
struct LoopMaster {
  /// When the master must next step without new bytes; Nanos::max() for never.
  std::function<Nanos()> next_wakeup;
  /// Called at every event time, first, whether or not it heard bytes.
  RadioStep step;
};

/// A LoopMaster over any core with `Nanos NextWakeup() const` and
/// `std::vector<Burst> Step(Nanos, std::span<const std::uint8_t>)` (server::Server,
/// MasterScheduler). `core` must outlive every use of the result.
template <typename Core>
LoopMaster MasterOf(Core& core) {
  return LoopMaster{[&core] { return core.NextWakeup(); },
                    [&core](Nanos now, std::span<const std::uint8_t> received) {
                      return core.Step(now, received);
                    }};
}

/// Owns a SharedChannel and steps it between one master (radio 0) and the vehicle
/// endpoints added after it (radios 1, 2, ...). Deterministic: the same calls and
/// the same cores give the same bytes at the same times. Not thread-safe.
class ChannelLoop {
 public:
  /// Many turns at one instant are normal (a burst, its replies); more than this
  /// many in a row mean a wake-up stuck in the past.
  static constexpr int kMaxStepsAtOneInstant = 100'000;

  /// A channel with `config` and `seed` (see SharedChannel) and `master` on its
  /// radio 0. Throws std::invalid_argument when the configuration is invalid.
  ChannelLoop(const ChannelConfig& config, std::uint64_t seed, LoopMaster master);
  // Its steps usually point at cores kept beside it (often capturing their owner's
  // `this`): a copy or a move would step them from two places, or from a stale one.
  ChannelLoop(const ChannelLoop&) = delete;
  ChannelLoop& operator=(const ChannelLoop&) = delete;

  /// Adds a vehicle's radio, stepped with `step` at each event time at which it
  /// heard bytes. Returns its radio ID (1 for the first vehicle, and so on).
  RadioId AddVehicle(RadioStep step);

  /// The next event time: the earlier of the master's wake-up and the channel's next
  /// transmission end, never before the channel's time (a request queued between
  /// calls makes the master due at once, which may be before the channel's time).
  /// Nanos::max() when neither has one.
  Nanos NextEventTime() const;

  /// Runs the loop at event time `t` (>= channel().now()): advances the channel to
  /// `t`, then steps the master and the vehicles and transmits their bursts.
  /// Throws std::logic_error when `t` lies before the channel's time, when a core
  /// returns a burst that starts too early, or after kMaxStepsAtOneInstant steps in
  /// a row at the same instant.
  void StepAt(Nanos t);

  /// Runs every event time up to and including `end`, then advances the channel to
  /// `end` (or leaves it where it is when it is already later). Throws as StepAt().
  void RunUntil(Nanos end);

  SharedChannel& channel() { return channel_; }
  /// The master's (the server's) radio on channel().
  RadioId master_radio() const { return master_radio_; }
  const SharedChannel& channel() const { return channel_; }

 private:
  struct Vehicle {
    RadioId radio;
    RadioStep step;
  };

  void Transmit(RadioId radio, Nanos now, const std::vector<Burst>& bursts);

  SharedChannel channel_;
  RadioId master_radio_;
  LoopMaster master_;
  std::vector<Vehicle> vehicles_;
  std::vector<std::uint8_t> received_;  // reused between steps
  Nanos last_step_{-1};
  int steps_at_last_instant_ = 0;
};

/// Several loops on separate frequencies (ChannelRouter's channels) whose masters
/// share one core: runs every loop's event times up to and including `end` in
/// time order (the earliest first, the lower index on ties), so the shared core
/// never sees time go back, then advances every channel to `end`. Throws as
/// ChannelLoop::StepAt().
void RunLoopsUntil(std::span<ChannelLoop* const> loops, Nanos end);

}  // namespace fireswarm::radio
