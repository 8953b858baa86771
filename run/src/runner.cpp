#include "fireswarm/run/runner.hpp"

#include <algorithm>
#include <chrono>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "fireswarm/agents/non_volatile_store.hpp"
#include "fireswarm/agents/params.hpp"
#include "fireswarm/agents/vehicle.hpp"
#include "fireswarm/common/secret_key.hpp"
#include "fireswarm/common/time.hpp"
#include "fireswarm/hil/sim_bridge.hpp"
#include "fireswarm/planner/plan.hpp"
#include "fireswarm/radio/channel.hpp"
#include "fireswarm/radio/channel_loop.hpp"
#include "fireswarm/radio/simulation_keys.hpp"
#include "fireswarm/server/journal.hpp"
#include "fireswarm/server/journal_format.hpp"
#include "fireswarm/server/mission_manager.hpp"
#include "fireswarm/server/server.hpp"
#include "fireswarm/sim2d/simulation.hpp"
#include "scoring.hpp"
#include "world_setup.hpp"

namespace fireswarm::run {
namespace {

using common::Nanos;

constexpr std::uint16_t kMissionId = 1;
/// Mixed into the scenario seed for the radio channel's own generator, so the
/// channel's losses do not repeat sim2d's draws.
constexpr std::uint64_t kChannelSeedSalt = 0x9e3779b97f4a7c15ULL;
/// Every vehicle down this long (several telemetry periods) ends the run, s.
constexpr double kSettleS = 5.0;

// A time window in which a vehicle's radio is dead: radio_silent faults, and a
// total loss from its time on (the vehicle is gone).
struct SilentWindow {
  double from_s = 0.0;
  double until_s = 0.0;
};

bool SilentAt(const std::vector<SilentWindow>& silent, double t_s) {
  return std::ranges::any_of(
      silent, [&](const SilentWindow& w) { return w.from_s <= t_s && t_s < w.until_s; });
}

// The runner's own operator: it signs the mission's start with a key made for
// this run only (kept in memory), through the same check as an operator's.
constexpr const char* kRunnerOperator = "runner";
constexpr std::int64_t kStartNonce = 1;

radio::LinkTiming TimingOf(const RadioConfig& radio) {
  radio::LinkTiming timing;
  timing.baud = radio.baud;
  timing.turnaround = std::chrono::duration_cast<Nanos>(
      std::chrono::duration<double, std::milli>(radio.turnaround_ms));
  return timing;
}

server::ServerConfig MakeServerConfig(const Scenario& scenario, const RunOptions& options,
                                      const common::SecretKey& runner_key) {
  server::ServerConfig config;
  config.operators = options.operators;
  config.operators[kRunnerOperator] = runner_key;
  config.radio.mode = scenario.radio.mode;
  config.radio.checksum = scenario.radio.checksum;
  if (scenario.radio.checksum == radio::ChecksumMode::kSecure) {
    std::vector<std::uint8_t> ids;
    for (const int id : scenario.fleet.ReceiverIds()) ids.push_back(static_cast<std::uint8_t>(id));
    config.radio.security = radio::SimulationServerSecurity(scenario.seed, ids);
  }
  config.radio.timing = TimingOf(scenario.radio);
  // Several channels: each its own baud and turnaround, vehicles fixed or balanced.
  for (int k = 0; k < scenario.radio.channels; ++k) {
    config.channels.push_back(TimingOf(scenario.radio.ChannelAt(k)));
  }
  for (const RadioConfig::ChannelOverride& o : scenario.radio.channel_overrides) {
    for (const int id : o.vehicles)
      config.vehicle_channels[id] = static_cast<std::size_t>(o.channel);
  }
  // The zones the plan kept out of, in the same local frame as the server's.
  config.no_fly = scenario.area.no_fly;
  config.no_fly_seed = static_cast<unsigned>(scenario.seed);
  // The server's coverage from telemetry, on the grid and camera the scorer uses
  // with the truth; the launch site for the published plan.
  config.area = scenario.area.area;
  config.camera = *scenario.fleet.camera;
  config.camera_pitch_deg = scenario.fleet.camera_pitch_deg;
  config.launch_en_m = scenario.area.frame.ToLocal(scenario.fleet.launch);
  config.separation = scenario.separation;
  return config;
}

radio::ChannelConfig MakeChannelConfig(const Scenario& scenario, std::size_t channel,
                                       const radio::LinkTiming& timing) {
  radio::ChannelConfig config;
  config.baud = timing.baud;
  config.bits_per_byte = timing.bits_per_byte;
  config.turnaround = timing.turnaround;
  config.loss = scenario.radio.ChannelAt(static_cast<int>(channel)).loss;
  // radio_burst faults: interference on every channel for their window.
  for (const FaultSpec& fault : scenario.faults) {
    if (fault.kind != FaultKind::kRadioBurst) continue;
    config.loss_bursts.push_back({common::FromSeconds(fault.at_s),
                                  common::FromSeconds(fault.at_s + fault.duration_s), fault.loss});
  }
  return config;
}

std::vector<SilentWindow> SilentWindowsOf(const Scenario& scenario, int id) {
  std::vector<SilentWindow> out;
  for (const FaultSpec& fault : scenario.faults) {
    if (fault.vehicle != id) continue;
    // A rebooting vehicle's radio is down with its software.
    if (fault.kind == FaultKind::kRadioSilent || fault.kind == FaultKind::kVehicleReboot)
      out.push_back({fault.at_s, fault.at_s + fault.duration_s});
    if (fault.kind == FaultKind::kTotalLoss) {
      out.push_back({fault.at_s, std::numeric_limits<double>::infinity()});
    }
  }
  return out;
}

// The plan as the runner needs it: the missions the vehicles fly, each drone's
// launch site and its sorties.
struct PlannedMissions {
  std::vector<server::DroneMission> missions;
  std::map<std::uint8_t, common::EastNorth> sites;
  std::map<int, int> sorties;  // receiver ID -> sorties planned
  server::AirspacePlan airspace;
};

// Plans and turns the plan into the missions the vehicles fly. Planner refusals
// are bad input: they name the scenario file.
PlannedMissions PlanMissions(const Scenario& scenario) {
  try {
    const planner::Plan plan =
        planner::PlanSearch(scenario.area, MakeFleetSpec(scenario), scenario.fleet.planner,
                            static_cast<unsigned>(scenario.seed));
    PlannedMissions out;
    out.sites = server::LaunchSitesOf(plan);
    for (const planner::DronePlan& drone : plan.drones)
      out.sorties[drone.receiver_id] = drone.sorties;
    out.missions = server::WithoutLaunchSite(
        server::ToDroneMissions(plan, kMissionId, scenario.fleet.altitude_m,
                                scenario.fleet.speed_mps),
        scenario.area.frame, out.sites);
    out.airspace = server::AssignAirspace(out.missions, scenario.area.frame, out.sites,
                                          scenario.fleet.altitude_m, scenario.separation);
    return out;
  } catch (const std::invalid_argument& e) {
    throw ScenarioError(scenario.source + ": fleet: the planner refused it: " + e.what());
  } catch (const std::runtime_error& e) {
    throw ScenarioError(scenario.source + ": fleet: the planner refused it: " + e.what());
  }
}

// Everything of one run, stepped together.
class Lockstep {
 public:
  Lockstep(const Scenario& scenario, const std::vector<FireSpec>& fires,
           const PlannedMissions& planned, const RunOptions& options)
      : runner_key_(common::GenerateSecretKey()),
        simulation_(internal::MakeSimulationConfig(
            scenario, fires, internal::StandPositions(scenario, planned.missions, planned.sites))),
        sorties_planned_(planned.sorties),
        fleet_(simulation_),
        server_config_(MakeServerConfig(scenario, options, runner_key_)),
        frame_(scenario.area.frame),
        server_(std::make_unique<server::Server>(server_config_, frame_)),
        seed_(scenario.seed) {
    const std::vector<radio::SchedulerConfig> channels = server_config_.ChannelConfigs();
    for (std::size_t k = 0; k < channels.size(); ++k) {
      // Through server_, which a restart replaces. Separate frequencies: each
      // channel its own generator (channel 0's as the single channel's).
      radios_.push_back(std::make_unique<radio::ChannelLoop>(
          MakeChannelConfig(scenario, k, channels[k].timing),
          (scenario.seed ^ kChannelSeedSalt) + k,
          radio::LoopMaster{
              [this, k] { return server_down_ ? Nanos::max() : server_->NextWakeup(k); },
              [this, k](Nanos now, std::span<const std::uint8_t> received) {
                // A dead server's modem hears nothing and says nothing.
                if (server_down_) return std::vector<radio::Burst>{};
                return server_->Step(now, k, received);
              }}));
      loops_.push_back(radios_.back().get());
    }
    for (const int id : scenario.fleet.ReceiverIds()) {
      agents::VehicleConfig config;
      config.id = static_cast<std::uint8_t>(id);
      config.radio.id = config.id;
      config.radio.mode = server_config_.radio.mode;
      config.radio.checksum = server_config_.radio.checksum;
      // Its flash: what a reboot keeps (vehicle_reboot faults).
      config.storage = std::make_shared<agents::NonVolatileStore>();
      server_->AddVehicle(id);
      const std::size_t channel = server_->scheduler().ChannelOf(config.id);
      config.radio.timing = channels[channel].timing;
      config.camera = *scenario.fleet.camera;
      vehicle_configs_.push_back(config);
      config.radio.security = SecurityOf(config);
      auto vehicle = std::make_unique<agents::Vehicle>(config);
      // The mount pitch is a parameter (the seed's EEPROM), set before the flight.
      radio::ParamWrite pitch;
      pitch.param_id = static_cast<std::uint16_t>(agents::ParamId::kCameraPitchDeg);
      pitch.value = static_cast<float>(scenario.fleet.camera_pitch_deg);
      vehicle->OnParamWrite(pitch);
      fleet_.Add(*vehicle);
      radios_[channel]->AddVehicle(RadioSideOf(vehicles_.size(), SilentWindowsOf(scenario, id)));
      vehicles_.push_back(std::move(vehicle));
      down_.push_back(false);
      reports_queued_before_.push_back(0);
    }
    server_->LoadMission(planned.missions, 0.0, planned.airspace);
    Start(0.0);
  }

  /// Loads the plan again as the server's next mission (a patrol's next round),
  /// under the next free mission IDs, and starts it at `t_s`. The server must be
  /// over the one before (Server::MissionOver).
  void StartNextMission(const PlannedMissions& planned, double t_s) {
    for (const std::uint8_t id : server_->mission()->vehicles()) {
      sorties_flown_before_[id] += static_cast<int>(server_->mission()->progress(id).sorties_flown);
    }
    std::vector<server::DroneMission> missions = planned.missions;
    const std::uint16_t first_id = server_->NextMissionId();
    for (server::DroneMission& mission : missions) mission.mission_id = first_id;
    server_->LoadMission(std::move(missions), t_s, planned.airspace);
    // What only the rounds before needed goes: the journal stays one round long.
    KeepJournal();
    journal_ = server::CompactJournal(std::move(journal_), server_->config().fusion);
    Start(t_s);
  }
  /// Missions started so far (1 + a patrol's rounds).
  int missions_started() const { return missions_started_; }

  /// The operator's start of the loaded mission at `t_s`, signed as from outside
  /// (each start its own nonce).
  void Start(double t_s) {
    // utime: simulated microseconds since the start (docs/lcm.md).
    const auto utime = static_cast<std::int64_t>(std::llround(t_s * 1e6));
    const server::SignedCommand start =
        server::SignCommand(server::OperatorCommand{}, kRunnerOperator, runner_key_, utime,
                            kStartNonce + missions_started_);
    std::string why;
    if (!server_->HandleSigned(start, common::FromSeconds(t_s), utime, &why)) {
      throw std::logic_error("runner: the server refused to start the mission: " + why);
    }
    ++missions_started_;
  }

  /// One lockstep step: sim2d and the vehicles, then the radio and the server up
  /// to the step's end; then what the server journaled is kept, as `fireswarm
  /// serve` writes it to its file.
  void Step() {
    fleet_.Step();
    radio::RunLoopsUntil(loops_, fleet_.now());
    KeepJournal();
  }
  /// The journal a restart would read now.
  std::size_t journal_entries() const { return journal_.size(); }

  double time_s() const { return simulation_.time_s(); }
  const sim2d::World& world() const { return simulation_.world(); }
  const sim2d::Simulation& simulation() const { return simulation_; }
  const server::Server& server() const { return *server_; }
  server::Server& server() { return *server_; }

  /// Vehicle `k` (in fleet order) goes down for a reboot: no more steps (the
  /// simulator holds its last commands) and no radio until RebootVehicle().
  void ShutDownVehicle(std::size_t k) {
    fleet_.Remove(vehicles_[k]->id());
    down_[k] = true;
  }
  bool VehicleDown(std::size_t k) const { return down_[k]; }
  /// Vehicle `k` comes back: a new Vehicle, made from its configuration and its
  /// non-volatile storage, takes the old one's place on the radio and in the fleet.
  void RebootVehicle(std::size_t k) {
    reports_queued_before_[k] += vehicles_[k]->endpoint().stats().reports_queued;
    agents::VehicleConfig config = vehicle_configs_[k];
    config.radio.security = SecurityOf(config);
    vehicles_[k] = std::make_unique<agents::Vehicle>(config);
    fleet_.Add(*vehicles_[k]);
    down_[k] = false;
  }
  /// The index of vehicle `id` in fleet order.
  std::size_t IndexOf(int id) const {
    const auto found =
        std::ranges::find_if(vehicles_, [id](const auto& v) { return v->id() == id; });
    return static_cast<std::size_t>(found - vehicles_.begin());
  }

  /// The server dies (a restart with down time): its radio goes silent and it
  /// processes nothing until RestartServer().
  void StopServer() {
    KeepJournal();
    server_down_ = true;
  }
  bool server_down() const { return server_down_; }

  /// Keeps what the server journaled since the last call (for a restart).
  void KeepJournal() {
    for (server::JournalEntry& entry : server_->TakeJournalEntries()) {
      journal_.push_back(std::move(entry));
    }
  }

  /// Replaces the server by one restored from its journal, every entry through
  /// the journal file's record format (as `fireswarm serve --journal` after a
  /// crash): what the next server reads is what the file would hold.
  void RestartServer() {
    KeepJournal();
    std::vector<server::JournalEntry> entries;
    std::uint64_t seq = 0;
    for (const server::JournalEntry& entry : journal_) {
      const server::JournalRecord record{++seq, entry.t_s, server::JournalKindOf(entry),
                                         server::JournalDataOf(entry)};
      entries.push_back(server::JournalEntryOf(record));
    }
    server_ =
        std::make_unique<server::Server>(server::Server::Restore(server_config_, frame_, entries));
    server_down_ = false;
  }
  /// Whether the server's radio is off the air on every channel: a server can
  /// only be replaced between its transmissions (a dying server's modem still
  /// sends what it was given; the new one's first burst comes after it).
  bool ServerRadioQuiet() const {
    return std::ranges::all_of(radios_, [](const auto& loop) {
      return loop->channel().TransmittingUntil(loop->master_radio()) <= loop->channel().now();
    });
  }
  /// The busiest channel's airtime (one channel: its airtime).
  Nanos BusiestAirtime() const {
    Nanos busiest{0};
    for (const auto& loop : radios_) busiest = std::max(busiest, loop->channel().stats().busy);
    return busiest;
  }
  const std::vector<std::unique_ptr<agents::Vehicle>>& vehicles() const { return vehicles_; }

  /// Fire reports the vehicles queued, over every reboot.
  std::uint64_t ReportsQueued() const {
    std::uint64_t queued = 0;
    for (std::size_t k = 0; k < vehicles_.size(); ++k) {
      queued += reports_queued_before_[k] + vehicles_[k]->endpoint().stats().reports_queued;
    }
    return queued;
  }

  std::size_t PendingReports() const {
    std::size_t pending = 0;
    for (const auto& v : vehicles_) pending += v->endpoint().pending_reports();
    return pending;
  }

  /// What the scorer needs at the end besides the world and the server.
  internal::FinalState Final() const {
    internal::FinalState out;
    out.sim_seconds = time_s();
    out.radio_busy_s = common::ToSeconds(BusiestAirtime());
    for (const auto& v : vehicles_) {
      // A vehicle the simulator lost or crashed is that, whatever its software says.
      const sim2d::FlightPhase phase = world().Truth(v->id()).phase;
      std::string state(radio::ToString(v->mode()));
      if (phase == sim2d::FlightPhase::kLost) state = "lost";
      if (phase == sim2d::FlightPhase::kCrashed) state = "crashed";
      out.modes[v->id()] = state;
    }
    out.reports_queued = ReportsQueued();
    // A patrol plans its sorties once and flies them every round.
    out.sorties_planned = sorties_planned_;
    for (auto& [id, sorties] : out.sorties_planned) sorties *= missions_started_;
    out.sorties_flown_before = sorties_flown_before_;
    return out;
  }

  /// Every vehicle landed after flying, crashed or lost, and none waits on the
  /// ground for its next sortie (the server's mission says).
  bool AllDown() const {
    // The vehicles first: while one flies (most steps) this ends at it.
    const bool vehicles_down = std::ranges::all_of(vehicles_, [&](const auto& v) {
      const sim2d::FlightPhase phase = world().Truth(v->id()).phase;
      return phase == sim2d::FlightPhase::kCrashed || phase == sim2d::FlightPhase::kLost ||
             (phase == sim2d::FlightPhase::kOnGround && v->mode() == radio::FlightMode::kLanded);
    });
    if (!vehicles_down) return false;
    const server::MissionManager* mission = server_->mission();
    if (mission == nullptr) return true;
    return std::ranges::none_of(mission->vehicles(), [&](std::uint8_t id) {
      const server::DroneProgress& progress = mission->progress(id);
      return progress.phase == server::DronePhase::kSwapping ||
             (progress.sorties_flown > 0 && (progress.phase == server::DronePhase::kUploading ||
                                             progress.phase == server::DronePhase::kStarting));
    });
  }

 private:
  // A vehicle on the radio; a silent or rebooting one is cut off both ways (it
  // hears nothing and says nothing). Through vehicles_[k], which a reboot replaces.
  radio::RadioStep RadioSideOf(std::size_t k, std::vector<SilentWindow> silent) {
    return
        [this, k, silent = std::move(silent)](Nanos now, std::span<const std::uint8_t> received) {
          if (down_[k] || SilentAt(silent, common::ToSeconds(now)))
            return std::vector<radio::Burst>{};
          return vehicles_[k]->OnRadio(now, received);
        };
  }
  // Secure mode: the vehicle's frame security, restored from and persisted to its
  // storage (a reboot neither reuses a nonce nor takes a replayed frame).
  std::shared_ptr<radio::FrameSecurity> SecurityOf(const agents::VehicleConfig& config) const {
    if (config.radio.checksum != radio::ChecksumMode::kSecure) return nullptr;
    const std::shared_ptr<agents::NonVolatileStore> storage = config.storage;
    return radio::SimulationVehicleSecurity(
        seed_, config.id, storage->security(),
        [storage](const radio::SecurityState& state) { return storage->WriteSecurity(state); });
  }

  common::SecretKey runner_key_;  // signs the start; first: the server's config holds it
  sim2d::Simulation simulation_;
  std::map<int, int> sorties_planned_;
  hil::LockstepFleet fleet_;
  server::ServerConfig server_config_;
  common::LocalFrame frame_;
  std::unique_ptr<server::Server> server_;
  std::vector<server::JournalEntry> journal_;  // what a restart reads
  // One loop per channel, each stepping *server_ (its master) and its vehicles.
  std::vector<std::unique_ptr<radio::ChannelLoop>> radios_;
  std::vector<radio::ChannelLoop*> loops_;
  std::vector<std::unique_ptr<agents::Vehicle>> vehicles_;
  int missions_started_ = 0;
  std::map<int, int> sorties_flown_before_;  // a patrol's earlier rounds, by receiver ID
  std::vector<agents::VehicleConfig> vehicle_configs_;  // a rebooted vehicle's, by fleet order
  std::vector<bool> down_;                              // rebooting, by fleet order
  std::vector<std::uint64_t> reports_queued_before_;    // by the vehicle's earlier lives
  std::uint64_t seed_ = 0;
  bool server_down_ = false;
};

// When to end a run before its duration: the mission is complete (or aborted) and
// no report waits on a vehicle, or every vehicle is down for a few telemetry turns
// (the server then sees the landings); either way at most drain_s later.
class StopRule {
 public:
  explicit StopRule(const RunOptions& options) : drain_s_(options.drain_s) {}

  std::optional<StopReason> Check(double t_s, const Lockstep& run) {
    const server::MissionState state = run.server().state();
    if (state == server::MissionState::kComplete || state == server::MissionState::kAborted) {
      if (!complete_at_s_) complete_at_s_ = t_s;
      if (run.PendingReports() == 0 || t_s - *complete_at_s_ >= drain_s_) {
        return StopReason::kMissionComplete;
      }
      return std::nullopt;
    }
    if (!run.AllDown()) {
      down_at_s_.reset();
      return std::nullopt;
    }
    if (!down_at_s_) down_at_s_ = t_s;
    const double down_s = t_s - *down_at_s_;
    if ((down_s >= kSettleS && run.PendingReports() == 0) || down_s >= drain_s_) {
      return StopReason::kAllDown;
    }
    return std::nullopt;
  }

 private:
  double drain_s_;
  std::optional<double> complete_at_s_;
  std::optional<double> down_at_s_;
};

// One vehicle_reboot fault as the run goes: down from at_s, back at until_s.
struct Reboot {
  std::size_t vehicle = 0;  // index in fleet order
  double at_s = 0.0;
  double until_s = 0.0;
  bool down = false;
  bool done = false;
};

// Shuts down and brings back the vehicles whose reboot is due at `t_s` (a vehicle
// already down for another reboot stays down until the later one ends). Returns
// the reboots finished.
int StepReboots(double t_s, std::vector<Reboot>& reboots, Lockstep& run) {
  constexpr double kEps = 1e-9;
  int finished = 0;
  for (Reboot& reboot : reboots) {
    if (reboot.done) continue;
    if (!reboot.down && t_s + kEps >= reboot.at_s) {
      if (!run.VehicleDown(reboot.vehicle)) run.ShutDownVehicle(reboot.vehicle);
      reboot.down = true;
    }
    if (reboot.down && t_s + kEps >= reboot.until_s) {
      const bool overlapped = std::ranges::any_of(reboots, [&](const Reboot& other) {
        return &other != &reboot && other.vehicle == reboot.vehicle && other.down && !other.done &&
               other.until_s > reboot.until_s;
      });
      if (!overlapped) run.RebootVehicle(reboot.vehicle);
      reboot.done = true;
      ++finished;
    }
  }
  return finished;
}

}  // namespace

const char* ToString(StopReason reason) {
  switch (reason) {
    case StopReason::kDuration:
      return "duration";
    case StopReason::kMissionComplete:
      return "mission_complete";
    case StopReason::kAllDown:
      return "all_down";
  }
  return "unknown";
}

RunResult RunScenario(const Scenario& scenario, const RunOptions& options) {
  const auto wall_start = std::chrono::steady_clock::now();
  const std::vector<FireSpec> fires = internal::ExpandFires(scenario);
  const PlannedMissions planned = PlanMissions(scenario);
  Lockstep run(scenario, fires, planned, options);

  internal::Scorer scorer(scenario, fires);

  RunResult result;
  StopRule stop(options);
  double next_progress_s = 0.0;
  const auto report_progress = [&] {
    if (!options.progress) return;
    RunProgress progress;
    progress.sim_s = run.time_s();
    progress.duration_s = scenario.duration_s;
    progress.coverage = scorer.coverage();
    progress.fires_confirmed = scorer.confirmed_tracks();
    progress.fires_total = fires.size();
    progress.missions = run.missions_started();
    progress.journal_entries = run.journal_entries();
    options.progress(progress);
  };
  constexpr double kEps = 1e-9;
  // The scenario's server restarts (faults of kind server_restart), in time order.
  std::vector<const FaultSpec*> restarts;
  std::vector<Reboot> reboots;
  for (const FaultSpec& fault : scenario.faults) {
    if (fault.kind == FaultKind::kServerRestart) restarts.push_back(&fault);
    if (fault.kind == FaultKind::kVehicleReboot) {
      reboots.push_back({run.IndexOf(fault.vehicle), fault.at_s, fault.at_s + fault.duration_s});
    }
  }
  std::ranges::stable_sort(restarts, {}, &FaultSpec::at_s);
  std::size_t restarts_done = 0;
  std::optional<double> server_back_at_s;  // a restart's down time ends
  bool drilled = false;                    // RunOptions::restart_server_when's one restart
  double next_patrol_s = scenario.patrol ? scenario.patrol->every_s : 0.0;
  while (run.time_s() < scenario.duration_s - kEps) {
    run.Step();
    const double t_s = run.time_s();
    // At its time, or just after: once the server's radio is off the air. With a
    // down time the server dies then and its successor takes over that much later.
    for (; restarts_done < restarts.size() && t_s + kEps >= restarts[restarts_done]->at_s &&
           !run.server_down() && run.ServerRadioQuiet();
         ++restarts_done) {
      if (restarts[restarts_done]->duration_s > 0.0) {
        run.StopServer();
        server_back_at_s = t_s + restarts[restarts_done]->duration_s;
      } else {
        run.RestartServer();
        ++result.server_restarts;
      }
    }
    if (server_back_at_s && t_s + kEps >= *server_back_at_s) {
      run.RestartServer();
      ++result.server_restarts;
      server_back_at_s.reset();
    }
    result.vehicle_reboots += StepReboots(t_s, reboots, run);
    if (options.on_step) options.on_step(t_s, run.server());
    // The drill too replaces the server only between its transmissions.
    if (options.restart_server_when && !drilled && !run.server_down() && run.ServerRadioQuiet()) {
      run.KeepJournal();
      if (options.restart_server_when(t_s, run.server())) {
        run.RestartServer();
        ++result.server_restarts;
        drilled = true;
      }
    }
    scorer.Observe(t_s, run.simulation(), run.server());
    if (t_s + kEps >= next_progress_s) {
      report_progress();
      next_progress_s += options.progress_interval_s;
    }
    // A patrol flies the search again every_s after the last start, once the
    // server (up) is over that one and the crews have swapped the packs (as the
    // operator would wait); it stops at the duration only.
    if (scenario.patrol) {
      if (t_s + kEps >= next_patrol_s && !run.server_down() && run.server().MissionOver() &&
          run.server().FleetReady(t_s)) {
        run.StartNextMission(planned, t_s);
        next_patrol_s = t_s + scenario.patrol->every_s;
      }
      continue;
    }
    if (const std::optional<StopReason> reason = stop.Check(t_s, run)) {
      result.stop = *reason;
      break;
    }
  }
  report_progress();

  const internal::FinalState final_state = run.Final();
  result.report = scorer.Finish(run.world(), run.server(), final_state);
  const server::TrafficControl& traffic = run.server().traffic();
  SeparationOutcome& separation = result.report.separation;
  separation.rule = planned.airspace.rule;
  separation.separation_m = traffic.config().separation_m;
  separation.conflicts = traffic.counts().conflicts;
  separation.orders = traffic.counts().orders;
  separation.resolved = traffic.counts().resolved;
  separation.lost_separation = traffic.counts().lost_separation;
  separation.takeoffs_held = traffic.counts().takeoffs_held;
  separation.releases = traffic.counts().releases;
  separation.not_taken = traffic.counts().not_taken;
  for (const server::Conflict& c : traffic.lost()) {
    separation.lost.push_back({c.detected_s, c.vehicle_a, c.vehicle_b, c.observed_min_separation_m,
                               c.predicted_separation_m, c.time_to_closest_s,
                               server::ToString(c.resolution), c.mover});
  }
  result.state_hash = run.simulation().StateHash();
  result.missions = run.missions_started();
  result.mission_state = server::ToString(run.server().state());
  const double wall_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  result.report.wall_seconds = wall_s;
  result.report.real_time_factor = wall_s > 0.0 ? result.report.sim_seconds / wall_s : 0.0;
  return result;
}

}  // namespace fireswarm::run
