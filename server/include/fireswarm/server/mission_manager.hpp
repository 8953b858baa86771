// The mission manager: takes the planner's per-drone plans to the vehicles and
// follows them. Each drone's waypoints go up in chunks through the master
// scheduler (with its acks and retries), then the drone is told to start; a start
// the vehicle refuses (no GPS fix yet, battery low) is asked again every few
// seconds; telemetry then says how far along its lanes each drone is.
//
// A pure core: it queues requests on the scheduler it is given and reacts to the
// scheduler's events. No clock: times come with the events and with Step().
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "fireswarm/common/local_frame.hpp"
#include "fireswarm/common/time.hpp"
#include "fireswarm/planner/plan.hpp"
#include "fireswarm/radio/master_scheduler.hpp"
#include "fireswarm/radio/messages.hpp"

namespace fireswarm::server {

/// One drone's part of a mission as it goes over the radio.
struct DroneMission {
  std::uint8_t vehicle = 0;  ///< receiver ID, 1..254
  std::uint16_t mission_id = 0;
  std::vector<radio::Waypoint> waypoints;
};

/// The plan's drones as radio missions, all with `mission_id`: every waypoint at
/// `altitude_m` above ground and `speed_mps`, lane starts flagged (bit 0), the
/// launch point at either end included. Throws std::invalid_argument when a
/// receiver ID is outside 1..254 or a drone has more waypoints than a mission can
/// hold (255 chunks).
std::vector<DroneMission> ToDroneMissions(const planner::Plan& plan, std::uint16_t mission_id,
                                          double altitude_m, double speed_mps);

/// The missions as the vehicles fly them from their own stands around the launch
/// site: the waypoints within 1 m of `launch` (local metres of `frame`) at either
/// end of each route are dropped, or every vehicle would fly to the same point at
/// the same altitude. Returns to launch between sorties stay. A route of only the
/// launch site keeps one waypoint.
std::vector<DroneMission> WithoutLaunchSite(std::vector<DroneMission> missions,
                                            const common::LocalFrame& frame,
                                            common::EastNorth launch);

/// Where one drone is in the mission.
enum class DronePhase : std::uint8_t {
  kUploading,  ///< chunks queued, not all acknowledged
  kStarting,   ///< mission stored on the vehicle, start asked (again after a refusal)
  kFlying,     ///< the vehicle accepted the start
  kDone,       ///< landed after flying the mission
  kFailed,     ///< upload rejected or unanswered after every retry; `failure` says why
};

const char* ToString(DronePhase phase);

struct DroneProgress {
  DronePhase phase = DronePhase::kUploading;
  std::size_t chunk_count = 0;
  std::size_t chunks_acked = 0;
  std::size_t waypoint_count = 0;
  std::uint16_t waypoint_index = 0;  ///< from telemetry: the waypoint being flown to
  int start_refusals = 0;            ///< starts the vehicle refused so far
  std::string failure;               ///< why the drone failed (kFailed only)
};

struct MissionManagerConfig {
  /// A refused start is asked again after this long, seconds.
  double start_retry_s = 2.0;
  /// Rounds of resending a chunk whose request failed (each round is itself the
  /// scheduler's max_retries resends) before the drone is given up.
  int chunk_rounds = 3;
};

class MissionManager {
 public:
  /// `scheduler` must outlive the manager and know every drone's vehicle.
  /// Throws std::invalid_argument for a vehicle listed twice.
  MissionManager(radio::MasterScheduler& scheduler, std::vector<DroneMission> missions,
                 const MissionManagerConfig& config = {});

  /// Queues every uploading drone's chunks; each drone's start follows its last
  /// chunk's ack.
  void Begin();

  /// Feeds one scheduler event (every event may be fed; others are ignored).
  void OnEvent(const radio::SchedulerEvent& event);

  /// Asks refused starts again once start_retry_s has passed. Call at least as
  /// often as NextWakeup() says.
  void Step(common::Nanos now);
  /// When Step() must next be called; Nanos::max() when nothing waits.
  common::Nanos NextWakeup() const;

  /// Puts a drone back in `phase` without sending anything (a restarted server
  /// whose journal says where the drone was): kFlying and later drones are not
  /// uploaded again; kStarting asks its start at the next Step. Throws
  /// std::out_of_range for a vehicle without a mission.
  void RestorePhase(std::uint8_t vehicle, DronePhase phase);

  /// Gives a drone a new mission (another mission ID; the waypoints it flies
  /// from where it is): its chunks go up and it is told to start, as at the
  /// mission's start, and its progress counts the new mission. `send` false only
  /// records it (a restored server). Throws std::out_of_range for a vehicle
  /// without a mission and std::invalid_argument for the same mission ID.
  void Replace(DroneMission mission, bool send = true);
  /// Gives a drone up as lost: kFailed with `why`, its requests forgotten,
  /// nothing sent. Throws std::out_of_range for a vehicle without a mission.
  void MarkLost(std::uint8_t vehicle, std::string why);
  /// The waypoints a drone has still to fly by its telemetry: from the one it
  /// flies to, or with `from_leg_start` from the one before (the leg it is on).
  /// Throws std::out_of_range for a vehicle without a mission.
  std::vector<radio::Waypoint> Remaining(std::uint8_t vehicle, bool from_leg_start) const;
  /// The mission a drone flies now. Throws std::out_of_range as progress().
  const DroneMission& mission_of(std::uint8_t vehicle) const;
  /// Counts the missions replaced: while it stays the same, every mission_of()
  /// does (the plan's GeoJSON need not be built again).
  std::uint64_t missions_version() const { return missions_version_; }

  const DroneProgress& progress(std::uint8_t vehicle) const;
  std::vector<std::uint8_t> vehicles() const;  ///< ascending
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
    std::vector<radio::MissionChunk> chunks;
    std::vector<int> chunk_rounds;  // per chunk: sends so far
    DroneProgress progress;
    common::Nanos retry_start_at = common::Nanos::max();
  };
  static Drone DroneFor(DroneMission mission);
  // The drone of `vehicle`; throws std::out_of_range naming it when it has no mission.
  const Drone& Find(std::uint8_t vehicle) const;
  Drone& Find(std::uint8_t vehicle);
  void SendChunk(Drone& drone, std::size_t index);
  void SendStart(Drone& drone);
  void OnFinished(const radio::RequestFinished& finished);
  void OnTelemetry(const radio::TelemetryReceived& telemetry);
  void Fail(Drone& drone, std::string why);

  radio::MasterScheduler& scheduler_;
  MissionManagerConfig config_;
  std::map<std::uint8_t, Drone> drones_;
  struct Pending {
    std::uint8_t vehicle = 0;
    int chunk = -1;  // -1: the start command
  };
  std::map<radio::RequestId, Pending> pending_;
  std::uint64_t missions_version_ = 0;
};

}  // namespace fireswarm::server
