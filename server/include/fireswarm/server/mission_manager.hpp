// The mission manager: takes the planner's per-drone plans to the vehicles and
// follows them. Each drone's waypoints go up in chunks through the master
// scheduler (with its acks and retries), then the drone is told to start; a start
// the vehicle refuses (no GPS fix yet, battery low) is asked again every few
// seconds; telemetry then says how far along its lanes each drone is.
//
// Sorties: a drone's route may be several sorties (the planner's is_return
// waypoints end them). Only the sortie to fly goes up, as a radio mission of its
// own (mission_id + its index), and ends with the vehicle's return and landing at
// its stand. Landed with more to fly, the drone waits for its battery swap
// (kSwapping) until its telemetry says it is on the ground with a fresh pack
// (battery at least kFreshPackPercent, no low-battery flag): only then does the
// next sortie go up and start. The upload waits for the swap because a real pack
// change power-cycles the vehicle, and the server never launches a drone on a
// battery it has not seen full; a crew that is slow only delays that drone. A
// sortie cut short by a low-battery return is resumed after the swap: its rest,
// from the leg it was on, becomes a sortie of its own as soon as telemetry shows
// the return (so a drone standing ready may take it: Server::RebalanceSorties).
//
// A pure core: it queues requests on the scheduler it is given and reacts to the
// scheduler's events. No clock: times come with the events and with Step().
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "fireswarm/common/local_frame.hpp"
#include "fireswarm/common/time.hpp"
#include "fireswarm/planner/plan.hpp"
#include "fireswarm/radio/channel_router.hpp"
#include "fireswarm/radio/master_scheduler.hpp"
#include "fireswarm/radio/messages.hpp"

namespace fireswarm::server {

/// One drone's part of a mission as it goes over the radio.
struct DroneMission {
  std::uint8_t vehicle = 0;  ///< receiver ID, 1..254
  /// The first sortie's radio mission ID; sortie k goes up as mission_id + k.
  std::uint16_t mission_id = 0;
  /// The whole route, every sortie, in flying order.
  std::vector<radio::Waypoint> waypoints;
  /// Where each sortie after the first begins in `waypoints`: ascending, each in
  /// [1, waypoints.size()). Empty: one sortie.
  std::vector<std::size_t> sortie_starts;
};

/// A drone's telemetry battery level that counts as a fresh pack, percent.
inline constexpr int kFreshPackPercent = 95;

/// How many sorties `mission` has (1 at least).
std::size_t SortieCount(const DroneMission& mission);
/// Sortie `sortie`'s waypoints as [first, end) indices into mission.waypoints.
/// Throws std::out_of_range for a sortie it does not have.
std::pair<std::size_t, std::size_t> SortieRange(const DroneMission& mission, std::size_t sortie);
/// The radio mission ID sortie `sortie` goes up with.
std::uint16_t SortieMissionId(const DroneMission& mission, std::size_t sortie);
/// The sortie whose waypoints include index `waypoint` (the last one beyond the end).
std::size_t SortieOf(const DroneMission& mission, std::size_t waypoint);
/// The sorties' waypoints, one list per sortie.
std::vector<std::vector<radio::Waypoint>> SortiesOf(const DroneMission& mission);
/// Sets mission.waypoints and sortie_starts from one list per sortie (empty
/// lists are dropped).
void SetSorties(DroneMission& mission, const std::vector<std::vector<radio::Waypoint>>& sorties);

/// The plan's drones as radio missions, all with `mission_id`: every waypoint at
/// `altitude_m` above ground and `speed_mps`, lane starts flagged (bit 0), the
/// launch point at either end included, split into sorties after each is_return
/// waypoint. Throws std::invalid_argument when a receiver ID is outside 1..254 or
/// a sortie has more waypoints than a mission can hold (255 chunks).
std::vector<DroneMission> ToDroneMissions(const planner::Plan& plan, std::uint16_t mission_id,
                                          double altitude_m, double speed_mps);

/// The missions as the vehicles fly them from their own stands around their
/// launch sites: the waypoints within 1 m of the drone's site (`launch_of`, local
/// metres of `frame`; a drone not listed keeps its route) at either end of each
/// sortie are dropped, or every vehicle would fly to the same point at the same
/// altitude (each sortie ends with the vehicle's own return to its stand). A
/// sortie of only the launch site is dropped: a drone the plan gave nothing to
/// search gets a mission without waypoints, and stays on the ground
/// (MissionManager: done at once, ready for others' work).
std::vector<DroneMission> WithoutLaunchSite(
    std::vector<DroneMission> missions, const common::LocalFrame& frame,
    const std::map<std::uint8_t, common::EastNorth>& launch_of);
/// The same with one site for every drone.
std::vector<DroneMission> WithoutLaunchSite(std::vector<DroneMission> missions,
                                            const common::LocalFrame& frame,
                                            common::EastNorth launch);
/// Each drone's launch site in the plan (DronePlan::launch), by receiver ID.
std::map<std::uint8_t, common::EastNorth> LaunchSitesOf(const planner::Plan& plan);

/// Where one drone is in the mission.
enum class DronePhase : std::uint8_t {
  kUploading,  ///< chunks queued, not all acknowledged
  kStarting,   ///< mission stored on the vehicle, start asked (again after a refusal)
  kFlying,     ///< the vehicle accepted the start
  kDone,       ///< landed after flying the mission (its last sortie)
  kFailed,     ///< upload rejected or unanswered after every retry; `failure` says why
  kSwapping,   ///< landed after a sortie; the next waits for a fresh pack (journals: 5)
};

const char* ToString(DronePhase phase);

struct DroneProgress {
  DronePhase phase = DronePhase::kUploading;
  std::size_t chunk_count = 0;  ///< of the sortie going up or flown
  std::size_t chunks_acked = 0;
  std::size_t waypoint_count = 0;  ///< the whole route, every sortie
  /// From telemetry: the waypoint being flown to, an index into the whole route.
  std::size_t waypoint_index = 0;
  /// The sortie going up, flown or just flown, from 0, of the mission it has now.
  std::size_t sortie = 0;
  std::size_t sortie_count = 1;   ///< sorties in the mission it has now
  std::size_t sorties_flown = 0;  ///< sorties ended with a landing, every mission it had
  int start_refusals = 0;         ///< starts the vehicle refused so far
  int start_holds = 0;            ///< starts the gate held back so far
  std::string failure;            ///< why the drone failed (kFailed only)
};

struct MissionManagerConfig {
  /// A refused start is asked again after this long, seconds.
  double start_retry_s = 2.0;
  /// Rounds of resending a chunk whose request failed (each round is itself the
  /// scheduler's max_retries resends) before the drone is given up.
  int chunk_rounds = 3;
  /// A start the gate holds (StartGate, given to Step and OnEvent) is asked of it
  /// again after this long, seconds.
  double gate_retry_s = 1.0;
};

/// Asked before each start goes out: whether `vehicle` may take off at `now`.
using StartGate = std::function<bool(std::uint8_t vehicle, common::Nanos now)>;

class MissionManager {
 public:
  /// `scheduler` must outlive the manager and know every drone's vehicle.
  /// Throws std::invalid_argument for a vehicle listed twice.
  MissionManager(radio::ChannelRouter& scheduler, std::vector<DroneMission> missions,
                 const MissionManagerConfig& config = {});
  // by_id_ points into drones_'s nodes: a move takes the nodes along, a copy would not.
  MissionManager(MissionManager&&) = default;
  MissionManager(const MissionManager&) = delete;
  MissionManager& operator=(const MissionManager&) = delete;

  /// Queues every uploading drone's chunks; each drone's start follows its last
  /// chunk's ack.
  void Begin();

  /// Feeds one scheduler event (every event may be fed; others are ignored).
  /// Every start it sends here or in Step (each sortie's, a replaced mission's,
  /// a retry's) first asks `gate`: a start the gate holds waits, asked again every
  /// gate_retry_s; the drone stays kStarting meanwhile (DroneProgress::start_holds
  /// counts the holds). No gate: starts go out at once. The gate is given per
  /// call, not kept: what it asks (the server) may have moved since.
  void OnEvent(const radio::SchedulerEvent& event, const StartGate& gate = {});

  /// Asks refused starts again once start_retry_s has passed. Call at least as
  /// often as NextWakeup() says.
  void Step(common::Nanos now, const StartGate& gate = {});
  /// When Step() must next be called; Nanos::max() when nothing waits.
  common::Nanos NextWakeup() const;

  /// Puts a drone back in `phase` of sortie `sortie` (from 0), without sending
  /// anything (a restarted server whose journal says where the drone was):
  /// kFlying and later drones are not uploaded again; kStarting asks its start at
  /// the next Step; kSwapping waits for a fresh pack. `sortie_starts`, given,
  /// replaces the mission's (sorties cut short made their rests sorties of their
  /// own). Throws std::out_of_range for a vehicle without a mission or a sortie
  /// beyond its last, std::invalid_argument for sortie starts outside its route.
  void RestorePhase(std::uint8_t vehicle, DronePhase phase, std::size_t sortie = 0,
                    const std::optional<std::vector<std::size_t>>& sortie_starts = std::nullopt);
  /// Stops sending further sorties: drones landed between sorties are done (an
  /// aborted or recalled mission). Idempotent.
  void StopSorties();

  /// Gives a drone a new mission (another mission ID; the waypoints it flies
  /// from where it is): its chunks go up and it is told to start, as at the
  /// mission's start, and its progress counts the new mission; a drone on the
  /// ground between sorties (kSwapping) starts it once its pack is fresh. `send`
  /// false only records it (a restored server). Throws std::out_of_range for a vehicle
  /// without a mission and std::invalid_argument for the same mission ID.
  void Replace(DroneMission mission, bool send = true);
  /// Gives a drone up as lost: kFailed with `why`, its requests forgotten,
  /// nothing sent. Throws std::out_of_range for a vehicle without a mission.
  void MarkLost(std::uint8_t vehicle, std::string why);
  /// The waypoints a drone has still to fly by its telemetry, later sorties
  /// included: from the one it flies to, or with `from_leg_start` from the one
  /// before (the leg it is on; never before its sortie's first). A drone between
  /// sorties has the next ones still to fly. With `sortie_starts`, where the
  /// later sorties begin in the list returned. Throws std::out_of_range for a
  /// vehicle without a mission.
  std::vector<radio::Waypoint> Remaining(std::uint8_t vehicle, bool from_leg_start,
                                         std::vector<std::size_t>* sortie_starts = nullptr) const;
  /// True when `telemetry` (the drone's latest) shows its sortie cut short: sent
  /// home by a low battery before the sortie's last waypoint, with enough flown
  /// that its rest goes up as a sortie of its own after the swap (it is not done).
  /// Throws std::out_of_range for a vehicle without a mission.
  bool CutShort(std::uint8_t vehicle, const radio::Telemetry& telemetry) const;
  /// How many of a drone's sorties are still to start: those after the one it
  /// uploads, starts or flies, or from the next one when on the ground between
  /// sorties. 0 for a drone done or failed. Throws std::out_of_range for a
  /// vehicle without a mission.
  std::size_t UnstartedSorties(std::uint8_t vehicle) const;
  /// Takes a drone's last sortie away when it has not started (another drone flies
  /// it: Server::RebalanceSorties) and returns its waypoints; nothing sent, the
  /// sortie never went up. A drone on the ground whose next sortie it was is done.
  /// nullopt, and nothing changed, when it has none unstarted. Throws
  /// std::out_of_range for a vehicle without a mission.
  std::optional<std::vector<radio::Waypoint>> TakeLastSortie(std::uint8_t vehicle);
  /// The highest radio mission ID any drone's sorties use.
  std::uint16_t LastMissionId() const;
  /// The mission a drone flies now. Throws std::out_of_range as progress().
  const DroneMission& mission_of(std::uint8_t vehicle) const;
  /// Counts the missions replaced: while it stays the same, every mission_of()
  /// does (the plan's GeoJSON need not be built again).
  std::uint64_t missions_version() const { return missions_version_; }

  const DroneProgress& progress(std::uint8_t vehicle) const;
  const std::vector<std::uint8_t>& vehicles() const;  ///< ascending
  /// True when every drone is flying, done or failed (none still uploading/starting).
  bool AllStarted() const;
  /// Fraction of all drones' waypoints passed, [0, 1] (done drones count whole).
  double WaypointFraction() const;
  /// Fraction of one drone's waypoints passed (of the mission it flies now), [0, 1];
  /// 1 when done, 0 for a mission without waypoints. Throws std::out_of_range for
  /// a vehicle without a mission.
  double WaypointFraction(std::uint8_t vehicle) const;
  /// True while `request` is one of the manager's (a chunk or a start) that has
  /// not finished.
  bool Owns(radio::RequestId request) const { return pending_.contains(request); }

 private:
  struct Drone {
    DroneMission mission;
    std::vector<radio::MissionChunk> chunks;  // of progress.sortie
    std::vector<int> chunk_rounds;            // per chunk: sends so far
    DroneProgress progress;
    common::Nanos retry_start_at = common::Nanos::max();
    // kSwapping: the sortie that goes up on a fresh pack (a mission handed to a
    // drone on the ground starts at its first).
    std::size_t next_sortie = 0;
  };
  static Drone DroneFor(DroneMission mission);
  // Makes `sortie` the drone's current one: its chunks, nothing sent.
  static void LoadSortie(Drone& drone, std::size_t sortie);
  void OnLanded(Drone& drone, const radio::Telemetry& telemetry);
  // Makes the rest of the drone's sortie, from the leg before waypoint
  // `flying_to` (an index into its route), a sortie of its own.
  void CutSortie(Drone& drone, std::size_t flying_to);
  void StartNextSortie(Drone& drone);
  // The drone of `vehicle`; throws std::out_of_range naming it when it has no mission.
  const Drone& Find(std::uint8_t vehicle) const;
  Drone& Find(std::uint8_t vehicle);
  void SendChunk(Drone& drone, std::size_t index);
  // Asks the gate, then sends the start of the drone's sortie (or asks the gate
  // again later).
  void SendStart(Drone& drone, common::Nanos now, const StartGate& gate);
  void OnFinished(const radio::RequestFinished& finished, const StartGate& gate);
  void OnTelemetry(const radio::TelemetryReceived& telemetry);
  void Fail(Drone& drone, std::string why);
  // Every change of a drone's retry_start_at goes through here: it forgets the
  // earliest one, which NextWakeup() keeps (the radio loop asks before each step).
  void SetRetry(Drone& drone, common::Nanos at);

  radio::ChannelRouter& scheduler_;
  MissionManagerConfig config_;
  std::map<std::uint8_t, Drone> drones_;
  std::vector<std::uint8_t> vehicles_;  // drones_'s keys, ascending: fixed by the plan
  // drones_ by receiver ID, for Find in O(1): the server asks for every drone
  // on every radio event. Map nodes stay put, also when the manager moves.
  std::array<Drone*, 256> by_id_{};
  struct Pending {
    std::uint8_t vehicle = 0;
    int chunk = -1;  // -1: the start command
  };
  std::map<radio::RequestId, Pending> pending_;
  std::uint64_t missions_version_ = 0;
  mutable std::optional<common::Nanos> next_wakeup_;  // NextWakeup(), until a retry changes
  bool sorties_stopped_ = false;
};

}  // namespace fireswarm::server
