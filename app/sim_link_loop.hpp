// Simulated vehicles behind one real link, paced by the wall clock: the run loop
// shared by `fireswarm vehicle` (one vehicle) and `fireswarm sim` (N vehicles in
// one sim2d world behind one shared radio modem).
//
// Time. The radio side (link calls, when a burst leaves) uses the steady clock
// since the run started, as the real links expect. The vehicles need one
// monotonic clock for Step() and OnRadio(); it is the simulated time, because the
// lockstep fleet steps them on it and the control loops integrate on it. The
// simulation is paced so that simulated time = speed * wall time (since the
// pacing origin), so at speed 1 the vehicles' clock is the wall clock. OnRadio()
// gets the wall clock mapped onto simulated time, clamped between the last step
// and the next one so it never runs ahead of the next Step(). The endpoints'
// delays (turnaround, slot offsets) are real airtimes: a burst's start minus the
// `now` it was computed at is applied unscaled on the wall clock. At speed K > 1
// the vehicles' timers (link-lost, loiter time) run K times faster than the
// server's; K < 1 is refused by the commands: the vehicles' clock would lag the
// airtimes they must keep.
//
// A shared modem. Every vehicle hears every byte the link delivers (each endpoint
// keeps what is addressed to it or to all); their replies go out on the one link
// in the order of their start times, each `turnaround` before it starts (the
// modem adds the turnaround itself). The server's turns keep them from
// overlapping: in slots mode each vehicle answers in its own slot.
//
// Half duplex over UDP. A datagram takes no airtime, so the server can answer
// before a vehicle's reply would have left a real modem; the endpoint, half duplex
// like the radio, would refuse that turn as overlapping its own transmission.
// Bytes arriving while a vehicle's latest burst is still on the (modelled) air are
// handed to it as soon as its endpoint may answer them: one turnaround before that
// burst ends. Through a serial modem nothing arrives in that window, so nothing is
// held.
#pragma once

#include <chrono>
#include <cstdint>
#include <deque>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

#include "fireswarm/agents/vehicle.hpp"
#include "fireswarm/common/time.hpp"
#include "fireswarm/hil/sim_bridge.hpp"
#include "fireswarm/radio/link.hpp"
#include "fireswarm/sim2d/simulation.hpp"

namespace fireswarm::app {

/// One sim2d world and the agents::Vehicle flying each of its vehicles, stepped in
/// lockstep and paced by the wall clock, talking through one link.
class SimulatedFleet {
 public:
  /// `vehicles`: one configuration per vehicle of `world` (same IDs). Throws
  /// std::invalid_argument as sim2d::Simulation, agents::Vehicle and
  /// hil::LockstepFleet::Add do.
  SimulatedFleet(const sim2d::SimulationConfig& world,
                 const std::vector<agents::VehicleConfig>& vehicles);

  /// Runs until StopRequested() (stop_signals.hpp) or until the simulated time
  /// reaches `end`, simulated time running `speed` times faster than the wall
  /// clock (slower when the machine cannot keep up: see `lag_s` in Summary()).
  /// Precondition: speed >= 1. Throws as the link's Receive and Transmit.
  void Run(radio::IoLink& link, double speed, std::optional<common::Nanos> end);

  /// The vehicles, in the order of their configurations (e.g. to set a parameter
  /// before Run()).
  std::vector<std::unique_ptr<agents::Vehicle>>& vehicles() { return vehicles_; }
  const sim2d::Simulation& simulation() const { return simulation_; }
  /// Wall time Run() took, s.
  double wall_seconds() const { return wall_seconds_; }

  /// One vehicle's figures at the end: id, sim_seconds, mode, frames heard,
  /// replies sent, fire reports queued, final altitude, cross-track error.
  nlohmann::ordered_json VehicleSummary(const agents::Vehicle& vehicle) const;

 private:
  // What one vehicle heard and may not answer yet (see "Half duplex over UDP").
  struct Radio {
    agents::Vehicle* vehicle = nullptr;
    std::vector<std::uint8_t> received;
    common::Nanos deaf_until{0};  // vehicle clock
  };
  // A reply held until it may leave: written `turnaround` before its start.
  struct HeldBurst {
    common::Nanos send_at{0};  // wall clock
    common::Nanos start{0};    // wall clock
    std::vector<std::uint8_t> bytes;
  };
  using Clock = std::chrono::steady_clock;

  common::Nanos Wall() const { return Clock::now() - start_; }
  common::Nanos DueAt(common::Nanos sim) const;
  common::Nanos VehicleNow(common::Nanos wall) const;
  void Listen(radio::IoLink& link, common::Nanos wall);
  void Hold(radio::Burst burst, common::Nanos wall, common::Nanos now);
  void SendDue(radio::IoLink& link, common::Nanos wall);

  sim2d::Simulation simulation_;
  hil::LockstepFleet fleet_;
  std::vector<std::unique_ptr<agents::Vehicle>> vehicles_;
  std::vector<Radio> radios_;
  radio::LinkTiming timing_;
  common::Nanos step_;
  double speed_ = 1.0;
  Clock::time_point start_;
  common::Nanos origin_{0};     // wall time at which simulated time 0 was due
  std::deque<HeldBurst> held_;  // in start order
  double wall_seconds_ = 0.0;
};

}  // namespace fireswarm::app
