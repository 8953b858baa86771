// `fireswarm vehicle`: one simulated APOne vehicle (the sim2d plant flown by an
// agents::Vehicle through the HIL bridge) behind a real link, serial or UDP, paced
// by the wall clock. Run one per vehicle to spread a fleet over several machines.
//
// Time. The radio side (link calls, when a burst leaves) uses the steady clock
// since the run started, as the real links expect. The Vehicle needs one
// monotonic clock for Step() and OnRadio(); it is the simulated time, because the
// lockstep fleet steps the vehicle on it and the control loops integrate on it.
// The simulation is paced so that simulated time = speed * wall time (since the
// pacing origin), so at --speed 1 the vehicle's clock is the wall clock. OnRadio()
// gets the wall clock mapped onto simulated time, clamped between the last step
// and the next one so it never runs ahead of the next Step(). The endpoint's delays
// (turnaround, slot offsets) are real airtimes: a burst's start minus the `now` it
// was computed at is applied unscaled on the wall clock. At --speed K > 1 the
// vehicle's timers (link-lost, loiter time) run K times faster than the server's;
// K < 1 is refused: the vehicle's clock would lag the airtimes it must keep.
//
// Half duplex over UDP. A datagram takes no airtime, so the server can answer
// before our reply would have left a real modem; the endpoint, half duplex like
// the radio, would refuse that turn as overlapping its own transmission. Bytes
// arriving while our latest burst is still on the (modelled) air are handed over
// as soon as the endpoint may answer them: one turnaround before that burst ends.
// Through a serial modem nothing arrives in that window, so nothing is held.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <deque>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "cli.hpp"
#include "commands.hpp"
#include "fireswarm/agents/vehicle.hpp"
#include "fireswarm/common/camera_model.hpp"
#include "fireswarm/common/local_frame.hpp"
#include "fireswarm/hil/sim_bridge.hpp"
#include "fireswarm/radio/link.hpp"
#include "fireswarm/radio/udp_link.hpp"
#include "fireswarm/sim2d/simulation.hpp"
#include "message_json.hpp"

namespace fireswarm::app {
namespace {

namespace po = boost::program_options;
using radio::Nanos;
using Clock = std::chrono::steady_clock;

constexpr const char* kName = "vehicle";
constexpr int kMinId = 1;
constexpr int kMaxId = 254;
constexpr double kMinSpeed = 1.0;
constexpr double kMaxSpeed = 1000.0;
// The fire area: a square of this half-width around the launch point.
constexpr double kFireHalfWidthM = 1000.0;
// A loop more than this late (wall clock) moves its pacing origin instead of
// stepping back to back to catch up: the simulation then runs slower than asked.
constexpr Nanos kMaxLag = std::chrono::milliseconds(200);

struct Flags {
  int id = 1;
  std::vector<std::string> udp;  // LOCAL REMOTE
  std::string serial;            // device, empty = none
  unsigned baud = 57'600;
  std::string mode = "slots";
  std::string checksum = "crc16";
  std::optional<double> lat_deg;
  std::optional<double> lon_deg;
  std::optional<double> fire_east_m;
  std::optional<double> fire_north_m;
  std::string camera = "seed";
  std::string param_file;
  std::uint64_t seed = 1;
  std::optional<double> duration_s;
  double speed = 1.0;
  bool print_bound_port = false;
};

[[noreturn]] void BadFlag(const std::string& flag, const std::string& requirement,
                          const std::string& got) {
  throw UsageError("fireswarm vehicle: --" + flag + " must be " + requirement + ", got '" + got +
                   "'");
}

std::string Text(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

// What a flag needs before it can become configuration; the ranges of the
// configurations themselves are checked by their Validate().
void CheckFlags(const Flags& f, const po::variables_map& values) {
  const bool udp = values.count("udp") != 0U;
  const bool serial = values.count("serial") != 0U;
  if (udp == serial) {
    throw UsageError(
        "fireswarm vehicle: give exactly one link, --udp LOCAL REMOTE or --serial "
        "DEVICE (see 'fireswarm vehicle --help')");
  }
  if (udp && f.udp.size() != 2) {
    BadFlag("udp", "two endpoints, LOCAL REMOTE (host:port each)",
            std::to_string(f.udp.size()) + " values");
  }
  if (!serial && !values["baud"].defaulted()) {
    throw UsageError("fireswarm vehicle: --baud goes with --serial");
  }
  if (f.print_bound_port && !udp) {
    throw UsageError("fireswarm vehicle: --print-bound-port goes with --udp");
  }
  if (f.id < kMinId || f.id > kMaxId) BadFlag("id", "in 1..254", std::to_string(f.id));
  if (!radio::ParseLinkMode(f.mode)) BadFlag("mode", "poll or slots", f.mode);
  if (!radio::ParseChecksumMode(f.checksum)) BadFlag("checksum", "xor or crc16", f.checksum);
  if (common::FindCameraModel(f.camera) == nullptr) {
    BadFlag("camera", common::CameraModelNames(), f.camera);
  }
  if (f.lat_deg && !common::IsValidLatLon({*f.lat_deg, 0.0})) {
    BadFlag("lat", "in [-90, 90]", Text(*f.lat_deg));
  }
  if (f.lon_deg && !common::IsValidLatLon({0.0, *f.lon_deg})) {
    BadFlag("lon", "in [-180, 180]", Text(*f.lon_deg));
  }
  for (const auto& [flag, value] :
       {std::pair{"fire-east-m", f.fire_east_m}, std::pair{"fire-north-m", f.fire_north_m}}) {
    if (value && !(std::abs(*value) < kFireHalfWidthM)) {
      BadFlag(flag, "within (-1000, 1000) m of the launch point", Text(*value));
    }
  }
  if (f.duration_s && !(*f.duration_s > 0.0)) {
    BadFlag("duration-s", "> 0", Text(*f.duration_s));
  }
  if (!(f.speed >= kMinSpeed && f.speed <= kMaxSpeed)) {
    BadFlag("speed", "in [1, 1000]", Text(f.speed));
  }
}

// A 2 km square forest centred on the launch site (the world's origin) with the
// vehicle at its centre carrying its camera, and the optional ignition at t = 0.
sim2d::SimulationConfig WorldFor(const Flags& f) {
  sim2d::SimulationConfig config;
  config.world.seed = f.seed;
  if (f.lat_deg) config.world.origin.lat_deg = *f.lat_deg;
  if (f.lon_deg) config.world.origin.lon_deg = *f.lon_deg;
  sim2d::VehicleConfig vehicle;
  vehicle.id = f.id;
  config.world.vehicles.push_back(vehicle);
  config.fire.origin_m = sim2d::Vec2(-kFireHalfWidthM, -kFireHalfWidthM);
  config.fire.width_m = 2.0 * kFireHalfWidthM;
  config.fire.height_m = 2.0 * kFireHalfWidthM;
  if (f.fire_east_m || f.fire_north_m) {
    sim2d::Ignition ignition;
    ignition.position_m = sim2d::Vec2(f.fire_east_m.value_or(0.0), f.fire_north_m.value_or(0.0));
    config.ignitions.push_back(ignition);
  }
  sim2d::VehicleCamera camera;
  camera.vehicle_id = f.id;
  camera.model = f.camera;
  config.cameras.push_back(camera);
  return config;
}

agents::VehicleConfig VehicleFor(const Flags& f) {
  agents::VehicleConfig config;
  config.id = static_cast<std::uint8_t>(f.id);
  config.radio.id = config.id;
  config.radio.mode = *radio::ParseLinkMode(f.mode);
  config.radio.checksum = *radio::ParseChecksumMode(f.checksum);
  config.radio.timing.baud = static_cast<int>(f.baud);
  config.param_file = f.param_file;
  config.camera = common::CameraModelByName(f.camera);
  return config;
}

// SIGINT and SIGTERM end the run cleanly; the previous handlers come back after it.
volatile std::sig_atomic_t stop_requested = 0;

void RequestStop(int /*signal*/) {
  stop_requested = 1;
}

class StopOnSignals {
 public:
  StopOnSignals() {
    stop_requested = 0;
    interrupt_ = std::signal(SIGINT, RequestStop);
    terminate_ = std::signal(SIGTERM, RequestStop);
  }
  ~StopOnSignals() {
    std::signal(SIGINT, interrupt_);
    std::signal(SIGTERM, terminate_);
  }
  StopOnSignals(const StopOnSignals&) = delete;
  StopOnSignals& operator=(const StopOnSignals&) = delete;

 private:
  void (*interrupt_)(int) = SIG_DFL;
  void (*terminate_)(int) = SIG_DFL;
};

// A reply held until it may leave: the modem adds the turnaround itself, so a
// burst is written `turnaround` before its start (at once for a Poll's answer,
// just before its slot in slots mode).
struct HeldBurst {
  Nanos send_at{0};  // wall clock
  Nanos start{0};    // wall clock
  std::vector<std::uint8_t> bytes;
};

// The run loop: the simulation stepped at its wall-clock due times, the radio
// answered as soon as bytes arrive.
class VehicleRunner {
 public:
  VehicleRunner(const Flags& f, radio::IoLink& link)
      : link_(link),
        speed_(f.speed),
        simulation_(WorldFor(f)),
        fleet_(simulation_),
        vehicle_(VehicleFor(f)),
        timing_(vehicle_.endpoint().config().timing),
        step_(radio::FromSeconds(simulation_.world().step_s())),
        end_(f.duration_s ? std::optional<Nanos>(radio::FromSeconds(*f.duration_s)) : std::nullopt),
        start_(Clock::now()) {
    fleet_.Add(vehicle_);
  }

  void Run() {
    while (stop_requested == 0) {
      const Nanos sim_now = fleet_.now();
      if (end_ && sim_now >= *end_) break;
      Nanos wall = Wall();
      if (wall >= DueAt(sim_now + step_)) {
        if (wall - DueAt(sim_now + step_) > kMaxLag) origin_ += wall - DueAt(sim_now + step_);
        fleet_.Step();
        wall = Wall();
      }
      Listen(wall);
      SendDue(Wall());
      Nanos next = std::min(DueAt(fleet_.now() + step_), NextSend());
      if (!received_.empty()) next = std::min(next, DueAt(deaf_until_));
      link_.WaitReadable(std::max(Nanos{0}, next - Wall()));
    }
  }

  nlohmann::ordered_json Summary() const {
    const radio::VehicleEndpointStats& radio = vehicle_.endpoint().stats();
    radio::Telemetry telemetry;
    telemetry.mode = vehicle_.mode();
    nlohmann::ordered_json j;
    j["id"] = vehicle_.id();
    j["sim_seconds"] = simulation_.time_s();
    j["mode"] = MessageToJson(telemetry)["mode"];  // named as radio-decode names it
    j["frames_heard"] = radio.frames_for_me + radio.broadcast_frames;
    j["replies_sent"] = radio.replies_sent;
    j["fire_reports_queued"] = radio.reports_queued;
    j["final_altitude_m"] = simulation_.world().Truth(vehicle_.id()).altitude_m;
    // Cross-track error on search lanes, to the vehicle's own position estimate.
    if (const agents::Navigator* navigator = vehicle_.navigator()) {
      const agents::CrossTrackStats cross_track = navigator->cross_track().Stats();
      j["cross_track"] = {{"samples", cross_track.samples},
                          {"mean_m", cross_track.mean_m},
                          {"p95_m", cross_track.p95_m},
                          {"max_m", cross_track.max_m}};
    }
    return j;
  }

 private:
  Nanos Wall() const { return Clock::now() - start_; }
  // When simulated time `sim` is due on the wall clock.
  Nanos DueAt(Nanos sim) const { return origin_ + std::chrono::round<Nanos>(sim / speed_); }
  // The vehicle's clock (simulated time) at wall time `wall`, kept within the
  // current step so that it never decreases nor passes the next Step().
  Nanos VehicleNow(Nanos wall) const {
    const Nanos sim_now = fleet_.now();
    const Nanos mapped = std::chrono::round<Nanos>((wall - origin_) * speed_);
    return std::clamp(mapped, sim_now, sim_now + step_ - Nanos{1});
  }

  // Hands what arrived to the vehicle (unless it is still deaf) and queues its replies.
  void Listen(Nanos wall) {
    link_.Receive(wall, received_);
    const Nanos now = VehicleNow(wall);
    if (received_.empty() || now < deaf_until_) return;
    std::vector<radio::Burst> replies = vehicle_.OnRadio(now, received_);
    received_.clear();
    for (radio::Burst& burst : replies) {
      const Nanos end = burst.start + timing_.AirtimeOf(burst.bytes.size());
      deaf_until_ = std::max(deaf_until_, end - timing_.turnaround);
      const Nanos start = wall + (burst.start - now);
      held_.push_back(
          HeldBurst{std::max(wall, start - timing_.turnaround), start, std::move(burst.bytes)});
    }
  }

  void SendDue(Nanos wall) {
    while (!held_.empty() && held_.front().send_at <= wall) {
      link_.Transmit(wall, held_.front().start, held_.front().bytes);
      held_.pop_front();
    }
  }

  Nanos NextSend() const { return held_.empty() ? Nanos::max() : held_.front().send_at; }

  radio::IoLink& link_;
  double speed_;
  sim2d::Simulation simulation_;
  hil::LockstepFleet fleet_;
  agents::Vehicle vehicle_;
  radio::LinkTiming timing_;
  Nanos step_;
  std::optional<Nanos> end_;
  Clock::time_point start_;
  Nanos origin_{0};                     // wall time at which simulated time 0 was due
  std::vector<std::uint8_t> received_;  // heard, not yet handed to the vehicle
  Nanos deaf_until_{0};                 // vehicle clock: see "Half duplex over UDP"
  std::deque<HeldBurst> held_;          // in start order, as the endpoint hands them out
};

}  // namespace

int RunVehicle(const std::vector<std::string>& args) {
  Flags f;
  po::options_description options("vehicle options");
  auto add = options.add_options();
  add("id", po::value(&f.id)->default_value(f.id), "receiver ID, 1..254");
  add("udp", po::value(&f.udp)->multitoken()->value_name("LOCAL REMOTE"),
      "UDP link: bind LOCAL (host:port, port 0 = any) and send to REMOTE (host:port)");
  add("serial", po::value(&f.serial)->value_name("DEVICE"), "serial link: the modem's device");
  add("baud", po::value(&f.baud)->default_value(f.baud),
      "serial speed, 8N1 (with --serial); turn timing assumes it, as the server must");
  add("mode", po::value(&f.mode)->default_value(f.mode), "poll or slots, as the server");
  add("checksum", po::value(&f.checksum)->default_value(f.checksum), "xor or crc16, as the server");
  add("lat", po::value<double>()->notifier([&f](double v) { f.lat_deg = v; }),
      "launch site latitude, deg (default: the simulator's origin)");
  add("lon", po::value<double>()->notifier([&f](double v) { f.lon_deg = v; }),
      "launch site longitude, deg (default: the simulator's origin)");
  add("fire-east-m", po::value<double>()->notifier([&f](double v) { f.fire_east_m = v; }),
      "ignite a fire at t = 0 this far east of the launch point, m");
  add("fire-north-m", po::value<double>()->notifier([&f](double v) { f.fire_north_m = v; }),
      "ignite a fire at t = 0 this far north of the launch point, m");
  const std::string camera_help = "thermal camera: " + common::CameraModelNames();
  add("camera", po::value(&f.camera)->default_value(f.camera), camera_help.c_str());
  add("param-file", po::value(&f.param_file)->value_name("PATH"),
      "the vehicle's parameter file (its EEPROM); default: parameters in memory only");
  add("seed", po::value(&f.seed)->default_value(f.seed), "simulation seed");
  add("duration-s", po::value<double>()->notifier([&f](double v) { f.duration_s = v; }),
      "stop after this much simulated time, s (default: run until SIGINT or SIGTERM)");
  add("speed", po::value(&f.speed)->default_value(f.speed),
      "run the simulation this many times faster than the wall clock, 1..1000");
  add("print-bound-port", po::bool_switch(&f.print_bound_port),
      "print 'bound_port=<port>' on stdout once the UDP link is bound");
  po::variables_map values;
  if (!ParseCommandLine(kName, "(--udp LOCAL REMOTE | --serial DEVICE) [options]", options, {},
                        args, values)) {
    return kExitOk;
  }
  CheckFlags(f, values);

  // Handled from here on, so a signal right after the port is printed ends cleanly.
  const StopOnSignals stop_on_signals;
  radio::UdpLink* udp = nullptr;
  std::unique_ptr<radio::IoLink> link;
  if (f.serial.empty()) {
    auto udp_link = std::make_unique<radio::UdpLink>(f.udp[0], f.udp[1]);
    udp = udp_link.get();
    link = std::move(udp_link);
  } else {
    link = radio::OpenSerialLink(f.serial, f.baud);
  }
  VehicleRunner runner(f, *link);
  // Printed once the vehicle is built, so whoever reads it is answered at once.
  if (f.print_bound_port) std::cout << "bound_port=" << udp->local_port() << std::endl;
  runner.Run();
  std::cout << runner.Summary().dump() << std::endl;
  return kExitOk;
}

}  // namespace fireswarm::app
