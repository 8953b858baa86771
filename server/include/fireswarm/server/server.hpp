// The command server's core: the fleet (registry), the radio master (scheduler),
// the mission (uploads, starts, progress), fire fusion and re-tasking, in one
// pure class. `Step(now, received bytes) -> bursts`; no clock, socket, file or
// LCM. What must survive a restart comes out as journal entries for an adapter
// to append (journal_format.hpp), and Server::Restore rebuilds the core from them.
//
// Re-tasking: when a report opens a new tentative track, a vehicle is sent to
// loiter around it (seed 7.4) for investigate_s (after its transit there) and
// then resumes its lanes by itself; its verdict may reject the track.
// investigations.hpp says which vehicle is chosen, how the no-fly zones limit
// it and when a track is rejected; when no vehicle can go, none is sent and the
// reason is journaled.
//
// A lost drone: when a flying drone has not been heard for the registry's lost
// time, its remaining lanes go to the drones still searching (server_handover.cpp).
//
// Operator commands to drones (hold, resume, return, land; one drone or the
// fleet) go to the vehicles as radio commands; the vehicle decides (agents/: a
// drone on the ground refuses a hold, resume goes back to what the hold
// interrupted). The mission's state does not change with them: a holding drone
// is still on its mission (it neither searches nor heads home, so the mission
// stays running), and a drone told to return or land counts as heading home as
// any other. An investigation the command interrupts ends without a verdict.
//
// Command status (command_status.hpp): every accepted command gets an ID and a
// record of its targets. Targets: the vehicle named or chosen (per-drone orders,
// investigations), every registered vehicle (fleet orders), the mission's
// vehicles (start). A start's target is queued until the first frame of the
// drone's upload goes out (sent), acknowledged once the drone accepted its start
// (DronePhase kFlying or kDone) and failed when the drone failed (upload refused
// or unanswered; `failure` is the detail); refused starts are asked again, so
// they stay sent. Other targets follow the radio request carrying the command.
// Restored servers keep counting IDs after the journal's last one.
//
// Authenticated commands (command_auth.hpp): commands from outside the process
// (LCM, the page) come in through HandleSigned, which checks the operator's MAC,
// the window and the nonce before Handle; a refusal is journaled
// (CommandRefused), counted per verdict and kept for the adapters to answer. A
// restored server remembers the nonces its journal's signed commands used.
// Handle itself is for the process's own orders (`serve --start`).
//
// No-fly zones (ServerConfig::no_fly): the legs the server makes up keep out of
// them as the planner's do. A taker's joins to the lanes it is handed go around
// them (planner::TransitPlanner), and investigations keep out of them too.
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "fireswarm/common/camera_model.hpp"
#include "fireswarm/common/local_frame.hpp"
#include "fireswarm/common/time.hpp"
#include "fireswarm/planner/coverage_grid.hpp"
#include "fireswarm/planner/geometry.hpp"
#include "fireswarm/planner/transit.hpp"
#include "fireswarm/radio/channel_router.hpp"
#include "fireswarm/radio/master_scheduler.hpp"
#include "fireswarm/server/airspace.hpp"
#include "fireswarm/server/command_auth.hpp"
#include "fireswarm/server/command_status.hpp"
#include "fireswarm/server/fire_fusion.hpp"
#include "fireswarm/server/handover.hpp"
#include "fireswarm/server/investigations.hpp"
#include "fireswarm/server/journal_entry.hpp"
#include "fireswarm/server/mission_manager.hpp"
#include "fireswarm/server/mission_state.hpp"
#include "fireswarm/server/operator_command.hpp"
#include "fireswarm/server/traffic.hpp"
#include "fireswarm/server/vehicle_registry.hpp"

namespace fireswarm::server {

struct ServerConfig {
  /// The radio master's configuration; with several channels, every channel's but
  /// for its timing (below).
  radio::SchedulerConfig radio;
  /// Several radio channels (issue 21): one LinkTiming per channel (its modem's
  /// baud and turnaround), channel k is channels[k]. Empty: one channel with
  /// radio.timing.
  std::vector<radio::LinkTiming> channels;
  /// Receiver ID -> channel for vehicles whose channel is fixed; the others are
  /// spread over the channels in balanced groups, in the order they are added.
  std::map<int, std::size_t> vehicle_channels;
  /// One scheduler configuration per channel (radio with each channel's timing).
  std::vector<radio::SchedulerConfig> ChannelConfigs() const;
  double telemetry_hz = 1.0;  ///< per vehicle
  LinkThresholds link;
  FireFusionConfig fusion;
  MissionManagerConfig mission;
  bool auto_investigate = true;  ///< send a vehicle to each new tentative track
  double investigate_s = 60.0;   ///< loiter time of an investigation, s (1..65535)
  /// Speed assumed for the transit to an investigation's circle, m/s: the order's
  /// duration is that transit plus investigate_s (the vehicle counts it from the
  /// order), so a far investigator still gets its time on the circle.
  double investigate_transit_mps = 8.0;
  /// An investigation judges its track only when the vehicle came this close to
  /// the point, m (its loiter radius is 20 m by default; the camera sees ~45 m
  /// to either side at 60 m).
  double investigate_near_m = 60.0;
  double investigate_radius_m = 0.0;  ///< 0: the vehicle's own loiter radius parameter
  /// A flying drone the registry marks lost is given up, and the lanes it had
  /// still to fly go to the drones still searching as new missions (handover.hpp).
  bool hand_over_lost_lanes = true;
  /// A drone done with its sorties, on the ground with a fresh pack, takes the last
  /// sortie not yet started of the drone with the most still to start, at the
  /// same site (server_rebalance.cpp): investigations and sorties cut short by a
  /// low battery leave some drones behind, and the fleet should finish together.
  bool rebalance_sorties = true;
  /// Two drones whose stands (where they were last seen on the ground) are at most
  /// this far apart share a launch site, m.
  double same_site_m = 200.0;
  /// A tentative track is rejected this long after its investigation ended when
  /// the investigator did not report it again, s (reports still in the air).
  double reject_grace_s = 10.0;
  /// No-fly zones in the server's local frame (x metres east, y north of its
  /// origin, as planner::SearchArea::no_fly): the joins of handed-over lanes go
  /// around them and no investigation's approach or circle may enter them. Empty:
  /// none.
  planner::MultiPolygon no_fly;
  /// Seed of the transit planning around `no_fly` (same seed, same routes).
  unsigned no_fly_seed = 1;
  /// The search area in the same local frame (planner::SearchArea::area: no-fly
  /// zones cut out, holes kept). Given, the server marks a planner::CoverageGrid
  /// (area minus `no_fly`) from every telemetry with a GPS fix at the reported
  /// position, heading and altitude, through `camera` at `camera_pitch_deg`: the
  /// coverage a run's report gives from the simulator's truth. Empty: no coverage
  /// grid (coverage() is null; mission_status_t falls back to the share of
  /// waypoints passed). It and the camera are also the published plan (plan_t).
  planner::MultiPolygon area;
  /// The fleet's camera; needed when `area` is given.
  std::optional<common::CameraModel> camera;
  /// The camera's mount pitch from the horizon, degrees, -90 straight down, [-90, 0).
  double camera_pitch_deg = -90.0;
  /// Where the fleet launches, local metres, for the published plan only.
  std::optional<common::EastNorth> launch_en_m;
  /// Operator ID -> key: whose signed commands HandleSigned takes (loaded from a
  /// key store by operator_keys.hpp). Empty: every signed command is refused.
  std::map<std::string, common::SecretKey> operators;
  /// HandleSigned's window around the server's LCM clock, microseconds (> 0).
  std::int64_t command_window_us = kDefaultCommandWindowUs;
  /// Separation: the altitude layers LoadMission gives the missions and the
  /// tactical watch over the fleet (traffic.hpp).
  SeparationConfig separation;
  /// Throws std::invalid_argument naming the field (`camera` missing with an
  /// `area`, a camera field or camera_pitch_deg out of range).
  void Validate() const;
};

class Server {
 public:
  /// `frame`: the local frame fire positions are fused in (the mission area's).
  /// Throws std::invalid_argument as ServerConfig::Validate (and for a window <= 0).
  Server(const ServerConfig& config, const common::LocalFrame& frame);

  /// Registers a vehicle with the registry and the scheduler. Throws
  /// std::invalid_argument naming the ID when it is out of range or a duplicate.
  void AddVehicle(int receiver_id, double now_s = 0.0);
  /// The mission to fly (one per registered vehicle at most). A server flies
  /// mission after mission (a patrol): the next can be loaded once the one before
  /// is over (MissionOver), with IDs from NextMissionId() on; it starts idle, with
  /// a new coverage grid, and the fire tracks and counters stay. Throws
  /// std::invalid_argument when a drone's vehicle is not registered, a mission is
  /// loaded and not over, or an ID is below NextMissionId().
  /// `airspace`: the layers AssignAirspace gave the missions, journaled with
  /// them and used for the legs the server makes up later (investigations).
  void LoadMission(std::vector<DroneMission> missions, double now_s = 0.0,
                   std::optional<AirspacePlan> airspace = std::nullopt);
  /// No mission, or the loaded one is complete, or aborted with every drone of it
  /// on the ground or given up as lost: the next one may be loaded.
  bool MissionOver() const;
  /// Every registered drone in touch (link not lost) reports itself on the ground
  /// (landed or idle) with a fresh pack (mission_manager.hpp's kFreshPackPercent, no low-battery
  /// flag): the fleet could fly a next mission now.
  bool FleetReady(double now_s) const;
  /// The lowest mission ID the next mission may use: every sortie and handed-over
  /// mission of the one before has a lower one (1 without a mission). Throws
  /// std::invalid_argument when the 16-bit IDs are used up.
  std::uint16_t NextMissionId() const;
  /// The layers of the loaded mission, if it was given them.
  const std::optional<AirspacePlan>& airspace() const { return airspace_; }

  /// Carries out an operator's command at `now`. Returns false (and journals
  /// nothing) when it cannot be done now, with the reason in `why` if given:
  /// start without a mission or twice, a missing or unknown vehicle, an invalid
  /// point, a fleet order without vehicles. When accepted, `command_id` (if given)
  /// receives the ID of its record in commands().
  bool Handle(const OperatorCommand& command, common::Nanos now, std::string* why = nullptr,
              std::int32_t* command_id = nullptr);
  /// A command from outside the process: verified first (CommandVerifier with
  /// ServerConfig::operators and command_window_us, at `now_utime`, the server's
  /// LCM clock in microseconds), then carried out as Handle. When the verdict
  /// (stored in `verdict` if given) is not kAccepted, the command is refused:
  /// journaled and counted (CommandRefused), `why` says why, and false.
  bool HandleSigned(const SignedCommand& command, common::Nanos now, std::int64_t now_utime,
                    std::string* why = nullptr, std::int32_t* command_id = nullptr,
                    CommandVerdict* verdict = nullptr);
  /// Journals and counts a command an adapter could not read (its verdict, e.g.
  /// kMalformed, and why are in `refusal`), as HandleSigned does its refusals.
  void Refuse(CommandRefused refusal, common::Nanos now);

  /// Feeds the bytes radio channel `channel` received up to `now` and returns
  /// what to transmit on it (ServerConfig::channels; 0..channel_count()-1).
  std::vector<radio::Burst> Step(common::Nanos now, std::size_t channel,
                                 std::span<const std::uint8_t> received);
  /// Step on channel 0: the single-channel server's (and ChannelLoop's) call.
  std::vector<radio::Burst> Step(common::Nanos now, std::span<const std::uint8_t> received);
  /// When Step() must next be called without new bytes, on any channel.
  common::Nanos NextWakeup() const;
  /// When Step() must next be called on `channel` without new bytes.
  common::Nanos NextWakeup(std::size_t channel) const;

  /// Journal entries produced since the last call, in order.
  std::vector<JournalEntry> TakeJournalEntries();
  /// Rebuilds the server from the journal entries a previous instance produced:
  /// the vehicles, the mission and each drone's phase (no second upload), every
  /// fire report (tracks come back with their IDs) and rejection. The radio's
  /// sequence numbers restart half their range away from the last journaled one
  /// (every entry records it), so no vehicle mistakes a new request for a resend
  /// of the last one it answered. Throws std::runtime_error naming the entry (its
  /// index and kind) when one does not fit the ones before (a phase before any
  /// mission, an unknown vehicle).
  static Server Restore(const ServerConfig& config, const common::LocalFrame& frame,
                        const std::vector<JournalEntry>& entries);

  MissionState state() const { return state_; }
  const VehicleRegistry& registry() const { return registry_; }
  const FireFusion& fusion() const { return fusion_; }
  const MissionManager* mission() const { return mission_ ? &*mission_ : nullptr; }
  /// The radio master: one scheduler per channel, requests routed by vehicle.
  const radio::ChannelRouter& scheduler() const { return *scheduler_; }
  const std::vector<Investigation>& investigations() const { return investigations_.all(); }
  const common::LocalFrame& frame() const { return frame_; }
  const ServerConfig& config() const { return config_; }
  /// The ground the cameras have seen by telemetry (ServerConfig::area); null
  /// without an area. Not journaled: a restored server counts from zero again.
  const planner::CoverageGrid* coverage() const { return coverage_ ? &*coverage_ : nullptr; }
  /// The fire reports fused and their latencies (journaled: a restored server
  /// has the counts of its whole life).
  const ReportStats& report_stats() const { return report_stats_; }
  double mission_started_s() const { return mission_started_s_; }
  /// Every command accepted since this server started, in order (IDs ascending).
  const std::vector<CommandRecord>& commands() const { return commands_.records(); }
  /// Rises whenever a record in commands() is added or changes; a record's
  /// `version` is this value when it last changed.
  std::uint64_t commands_version() const { return commands_.version(); }
  /// The ID the next accepted command gets.
  std::int32_t next_command_id() const { return commands_.next_id(); }
  /// Drones given up as lost whose lanes went to others -> true once heard again
  /// (and ordered home).
  const std::map<std::uint8_t, bool>& handed_over() const { return handed_over_; }
  /// The tactical watch: predicted conflicts, their resolutions and outcomes.
  const TrafficControl& traffic() const { return traffic_; }
  /// Commands refused unread or unauthenticated since this server started, per
  /// CommandVerdict (index kAccepted stays 0).
  const std::array<std::uint64_t, 6>& command_refusals() const { return command_refusals_; }
  /// The latest refusals (at most kKeptRefusals), oldest first, and how many
  /// there have been in all: an adapter that remembers how many it answered
  /// answers the newer ones.
  const std::deque<CommandRefused>& recent_refusals() const { return recent_refusals_; }
  std::uint64_t refusal_count() const { return refusal_count_; }
  static constexpr std::size_t kKeptRefusals = 64;
  /// Bytes the server has transmitted (all bursts) and received, since it started.
  std::uint64_t bytes_sent() const { return bytes_sent_; }
  std::uint64_t bytes_received() const { return bytes_received_; }

 private:
  bool Carry(const OperatorCommand& command, common::Nanos now, std::string* why,
             std::int32_t* command_id, const CommandCredentials* signer);
  void Attribute(std::int32_t command_id, const CommandCredentials& signer);
  void OnEvent(const radio::SchedulerEvent& event, double now_s);
  void MarkCoverage(const radio::Telemetry& telemetry, const Eigen::Vector2d& where_en_m);
  void WatchTraffic(std::uint8_t vehicle, const radio::Telemetry& telemetry,
                    const Eigen::Vector2d& where_en_m, double now_s);
  void ResolveConflicts(double now_s);
  // The mission's start gate: whether the drone's take-off from its stand is
  // clear of the traffic (TrafficControl::ClearToDepart); no while its drone has
  // not been heard (or heard on the ground without its position); yes when
  // take-offs are not sequenced, its sortie is not known or it is in the air.
  bool ClearToTakeOff(std::uint8_t vehicle, double now_s);
  // ClearToTakeOff as the mission's start gate, for one call into the mission
  // (never kept: a Server may be moved, Restore returns one).
  StartGate TakeOffGate();
  // The sortie's waypoints from index `from` on (at most kRouteAheadWaypoints),
  // in local metres (east, north, up).
  std::vector<Eigen::Vector3d> RouteAhead(std::span<const radio::Waypoint> sortie,
                                          std::size_t from) const;
  // Where `vehicle` in `mode` climbs or descends to by itself (TrafficSample).
  std::optional<double> IntentAltitudeM(std::uint8_t vehicle, radio::FlightMode mode) const;
  void OnFireReport(const radio::FireReportReceived& received, double now_s);
  void AfterFusion(const FireObservation& observation, const FireReportResult& result,
                   double now_s);
  radio::RequestId Investigate(std::uint8_t vehicle, common::LatLon point, double radius_m,
                               std::int32_t track_id, double now_s);
  void SendToAll(radio::CommandType type, std::int32_t command_id);
  std::optional<std::string> HandleDroneOrder(const OperatorCommand& command, double now_s,
                                              std::int32_t* command_id);
  std::optional<std::string> HandleInvestigation(const OperatorCommand& command, double now_s,
                                                 std::int32_t* command_id);
  void CallOff(const CommandAccepted& command, double now_s);
  void UpdateStartCommand(const radio::SchedulerEvent& event);
  void HandOverLostDrones(double now_s);
  void HandOver(std::uint8_t lost, double now_s);
  void RecallHandedOverDrones(double now_s);
  void RebalanceSorties(double now_s);
  bool ReadyForASortie(std::uint8_t vehicle, double now_s) const;
  std::optional<std::uint8_t> SortieDonorFor(std::uint8_t taker) const;
  std::vector<Taker> TakersFor(std::uint8_t lost, double now_s) const;
  void CheckInvestigations(common::Nanos now);
  void UpdateState(double now_s);
  void Record(double t_s, JournalEvent event);
  void Replay(const JournalEntry& entry);

  ServerConfig config_;
  common::LocalFrame frame_;
  std::unique_ptr<const planner::TransitPlanner> transit_;  // null without no-fly zones
  std::unique_ptr<radio::ChannelRouter> scheduler_;
  VehicleRegistry registry_;
  FireFusion fusion_;
  Investigations investigations_;  // holds transit_.get(): declared after it
  std::optional<MissionManager> mission_;
  std::optional<planner::CoverageGrid> coverage_;  // with ServerConfig::area only
  TrafficControl traffic_;
  // Avoid orders on the radio, by request: what became of each goes to traffic_.
  std::map<radio::RequestId, AvoidOrder> avoid_requests_;
  std::optional<AirspacePlan> airspace_;
  MissionState state_ = MissionState::kIdle;
  double mission_started_s_ = 0.0;
  // Drones given up as lost whose lanes went to others -> ordered home since
  // they were heard again (server_handover.cpp).
  std::map<std::uint8_t, bool> handed_over_;
  ReportStats report_stats_;
  std::map<std::uint8_t, double> clock_offset_s_;  // mission time - vehicle clock, per vehicle
  struct JournaledPhase {
    DronePhase phase = DronePhase::kUploading;
    std::vector<std::size_t> sortie_starts;
  };
  // By receiver ID: every radio event compares every drone's (OnEvent).
  std::array<std::optional<JournaledPhase>, 256> journaled_phases_;
  // Where each drone was last seen on the ground with a fix, local metres: its
  // stand, which tells its launch site (RebalanceSorties).
  std::map<std::uint8_t, Eigen::Vector2d> stand_en_m_;
  CommandLog commands_;
  std::int32_t start_command_id_ = 0;  // the start's record, 0: none this life
  std::vector<JournalEntry> journal_;
  CommandVerifier verifier_;
  std::array<std::uint64_t, 6> command_refusals_{};
  std::deque<CommandRefused> recent_refusals_;
  std::uint64_t refusal_count_ = 0;
  bool restoring_ = false;
  double last_step_s_ = 0.0;  // the latest Step's time, s
  std::uint64_t bytes_sent_ = 0;
  std::uint64_t bytes_received_ = 0;
};

}  // namespace fireswarm::server
