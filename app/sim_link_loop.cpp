#include "sim_link_loop.hpp"

#include <algorithm>
#include <utility>

#include "fireswarm/common/time.hpp"
#include "fireswarm/radio/messages.hpp"
#include "message_json.hpp"
#include "stop_signals.hpp"

namespace fireswarm::app {
namespace {

using common::Nanos;

// A loop more than this late (wall clock) moves its pacing origin instead of
// stepping back to back to catch up: the simulation then runs slower than asked.
constexpr Nanos kMaxLag = std::chrono::milliseconds(200);

}  // namespace

SimulatedFleet::SimulatedFleet(const sim2d::SimulationConfig& world,
                               const std::vector<agents::VehicleConfig>& vehicles)
    : simulation_(world),
      fleet_(simulation_),
      step_(common::FromSeconds(simulation_.world().step_s())),
      start_(Clock::now()) {
  for (const agents::VehicleConfig& config : vehicles) {
    vehicles_.push_back(std::make_unique<agents::Vehicle>(config));
    fleet_.Add(*vehicles_.back());
    radios_.push_back(Radio{vehicles_.back().get(), {}, Nanos{0}});
  }
  // One modem, one timing: every vehicle's endpoint is configured alike.
  if (!vehicles_.empty()) timing_ = vehicles_.front()->endpoint().config().timing;
}

Nanos SimulatedFleet::DueAt(Nanos sim) const {
  return origin_ + std::chrono::round<Nanos>(sim / speed_);
}

// The vehicles' clock (simulated time) at wall time `wall`, kept within the
// current step so that it never decreases nor passes the next Step().
Nanos SimulatedFleet::VehicleNow(Nanos wall) const {
  const Nanos sim_now = fleet_.now();
  const Nanos mapped = std::chrono::round<Nanos>((wall - origin_) * speed_);
  return std::clamp(mapped, sim_now, sim_now + step_ - Nanos{1});
}

void SimulatedFleet::Run(radio::IoLink& link, double speed, std::optional<Nanos> end) {
  speed_ = speed;
  start_ = Clock::now();
  // The simulated time reached so far is due now.
  origin_ = Nanos{0} - std::chrono::round<Nanos>(fleet_.now() / speed_);
  while (!StopRequested()) {
    const Nanos sim_now = fleet_.now();
    if (end && sim_now >= *end) break;
    Nanos wall = Wall();
    if (wall >= DueAt(sim_now + step_)) {
      if (wall - DueAt(sim_now + step_) > kMaxLag) origin_ += wall - DueAt(sim_now + step_);
      fleet_.Step();
      wall = Wall();
    }
    Listen(link, wall);
    SendDue(link, Wall());
    Nanos next = DueAt(fleet_.now() + step_);
    if (!held_.empty()) next = std::min(next, held_.front().send_at);
    for (const Radio& r : radios_) {
      if (!r.received.empty()) next = std::min(next, DueAt(r.deaf_until));
    }
    link.WaitReadable(std::max(Nanos{0}, next - Wall()));
  }
  wall_seconds_ = common::ToSeconds(Wall());
}

// Hands what arrived to every vehicle that is not deaf and queues their replies.
void SimulatedFleet::Listen(radio::IoLink& link, Nanos wall) {
  std::vector<std::uint8_t> arrived;
  link.Receive(wall, arrived);
  const Nanos now = VehicleNow(wall);
  for (Radio& r : radios_) {
    r.received.insert(r.received.end(), arrived.begin(), arrived.end());
    if (r.received.empty() || now < r.deaf_until) continue;
    std::vector<radio::Burst> replies = r.vehicle->OnRadio(now, r.received);
    r.received.clear();
    for (radio::Burst& burst : replies) {
      const Nanos burst_end = burst.start + timing_.AirtimeOf(burst.bytes.size());
      r.deaf_until = std::max(r.deaf_until, burst_end - timing_.turnaround);
      Hold(std::move(burst), wall, now);
    }
  }
}

void SimulatedFleet::Hold(radio::Burst burst, Nanos wall, Nanos now) {
  const Nanos start = wall + (burst.start - now);
  HeldBurst held{std::max(wall, start - timing_.turnaround), start, std::move(burst.bytes)};
  const auto later =
      std::upper_bound(held_.begin(), held_.end(), start,
                       [](Nanos value, const HeldBurst& element) { return value < element.start; });
  held_.insert(later, std::move(held));
}

void SimulatedFleet::SendDue(radio::IoLink& link, Nanos wall) {
  while (!held_.empty() && held_.front().send_at <= wall) {
    link.Transmit(wall, held_.front().start, held_.front().bytes);
    held_.pop_front();
  }
}

nlohmann::ordered_json SimulatedFleet::VehicleSummary(const agents::Vehicle& vehicle) const {
  const radio::VehicleEndpointStats& radio = vehicle.endpoint().stats();
  radio::Telemetry telemetry;
  telemetry.mode = vehicle.mode();
  nlohmann::ordered_json j;
  j["id"] = vehicle.id();
  j["sim_seconds"] = simulation_.time_s();
  j["mode"] = MessageToJson(telemetry)["mode"];  // named as radio-decode names it
  j["frames_heard"] = radio.frames_for_me + radio.broadcast_frames;
  j["replies_sent"] = radio.replies_sent;
  j["fire_reports_queued"] = radio.reports_queued;
  j["final_altitude_m"] = simulation_.world().Truth(vehicle.id()).altitude_m;
  // Cross-track error on search lanes, to the vehicle's own position estimate.
  if (const agents::Navigator* navigator = vehicle.navigator()) {
    const agents::CrossTrackStats cross_track = navigator->cross_track().Stats();
    j["cross_track"] = {{"samples", cross_track.samples},
                        {"mean_m", cross_track.mean_m},
                        {"p95_m", cross_track.p95_m},
                        {"max_m", cross_track.max_m}};
  }
  return j;
}

}  // namespace fireswarm::app
