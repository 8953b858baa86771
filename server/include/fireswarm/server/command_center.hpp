// The command center's model: what the page shows, built only from the LCM
// messages the server publishes (docs/command_center.md "The state"). Pure: no
// clock, socket, LCM instance or thread; the web adapter feeds it and serves its
// JSON. Live, the server hands it its messages; in replay they come from a log
// (replay.hpp), so a replay shows what the live page showed.
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <utility>

#include "fireswarm/command_status_t.hpp"
#include "fireswarm/conflict_t.hpp"
#include "fireswarm/common/local_frame.hpp"
#include "fireswarm/fire_track_list_t.hpp"
#include "fireswarm/mission_status_t.hpp"
#include "fireswarm/plan_t.hpp"
#include "fireswarm/radio_stats_t.hpp"
#include "fireswarm/vehicle_state_t.hpp"

namespace fireswarm::server {

namespace internal {
class AlertLog;
class ConflictWatch;
class CoverageRaster;
class SeparationWatch;
}  // namespace internal

/// How the model is set up.
struct CommandCenterConfig {
  std::string source = "live";      ///< "live" | "simulated" | "replay", copied into the state
  bool read_only = false;           ///< copied into the state (replay: commands refused)
  std::size_t trail_points = 120;   ///< positions kept per vehicle trail, >= 1
  std::size_t alerts_kept = 200;    ///< newest alerts kept in the state, >= 1
  std::size_t commands_kept = 100;  ///< newest commands kept in the state, >= 1
  double separation_m = 15.0;  ///< 3-D distance under which two airborne drones raise an alert, > 0
  /// Throws std::invalid_argument naming the first bad field and its value.
  void Validate() const;
};

/// The command center's state, fed with the LCM messages (docs/lcm.md), read as
/// the JSON of docs/command_center.md. Every On* method takes a message as it
/// came (never throws on its content: a malformed plan is kept as an error in
/// the state). Times in the JSON are seconds of the publisher's clock (utime / 1e6).
class CommandCenter {
 public:
  /// Throws std::invalid_argument from CommandCenterConfig::Validate.
  explicit CommandCenter(CommandCenterConfig config);
  ~CommandCenter();
  CommandCenter(CommandCenter&&) noexcept;
  CommandCenter& operator=(CommandCenter&&) noexcept;
  CommandCenter(const CommandCenter&) = delete;
  CommandCenter& operator=(const CommandCenter&) = delete;

  /// A plan_t (re-published every few seconds: an unchanged one changes nothing).
  void OnPlan(const plan_t& message);
  void OnVehicleState(const vehicle_state_t& message);
  void OnFireTracks(const fire_track_list_t& message);
  void OnMissionStatus(const mission_status_t& message);
  void OnRadioStats(const radio_stats_t& message);
  /// A command's status; a refused one's (command_id 0, `refusal` given) counts
  /// as NoteRefused.
  void OnCommandStatus(const command_status_t& message);
  /// A conflict of the server's tactical watch: an alert when it is predicted,
  /// when a drone is ordered out of it, and when it is over (critical when the
  /// pair came closer than the limit); the state's "conflicts" counts them.
  void OnConflict(const conflict_t& message);
  /// Counts a command the web adapter refused (the state's `refused`).
  void NoteRefused();

  /// The whole state (GET /api/state, the WebSocket "snapshot"'s "state").
  nlohmann::json State() const;
  /// The WebSocket "delta" message ({"type": "delta", ...}) with what changed since
  /// the last call (or since construction); nullopt when nothing did.
  std::optional<nlohmann::json> TakeDelta();
  /// GET /api/plan: the latest plan_t's GeoJSON FeatureCollection, an empty
  /// FeatureCollection before the first (or when every plan so far was malformed).
  const nlohmann::json& Plan() const { return plan_; }
  /// GET /api/coverage: {"cell_m", "rows", "cols", "corners", "seen"} over the
  /// plan's area (docs/command_center.md); rows = cols = 0 before a plan with an area.
  nlohmann::json Coverage() const;
  /// Changes whenever Coverage() does (a new raster, a cell seen): the web
  /// adapter serialises the raster again only then.
  std::uint64_t coverage_version() const { return coverage_version_; }

 private:
  struct Vehicle {
    vehicle_state_t last;                          // the latest message
    std::optional<vehicle_state_t> sent;           // the one the last delta's row said
    std::optional<common::EastNorth> local;        // last's position in frame_
    std::deque<nlohmann::json> trail;              // [lat, lon], oldest first
    std::optional<common::EastNorth> trail_end_m;  // the newest trail point, local
    std::size_t trail_unsent = 0;                  // newest trail points not in a delta yet
  };
  struct Track {
    int status = 0;
    nlohmann::json row;
  };
  void UpdateTime(std::int64_t utime);
  // `local`: the message's position in frame_, nullopt without one.
  void ExtendTrail(Vehicle& vehicle, const vehicle_state_t& message,
                   const std::optional<common::EastNorth>& local);
  void WatchSeparation(const vehicle_state_t& message,
                       const std::optional<common::EastNorth>& local);
  // The vehicle's row with its whole trail (the state), or for a delta only what
  // changed since the last delta's row, with the trail points since: nullopt when
  // nothing did.
  static nlohmann::json WholeRow(const Vehicle& vehicle);
  static std::optional<nlohmann::json> RowChanges(const Vehicle& vehicle);

  CommandCenterConfig config_;
  double time_s_ = 0.0;
  bool time_known_ = false;
  bool time_changed_ = false;

  nlohmann::json plan_;
  std::string plan_text_;
  nlohmann::json plan_info_;  // the state's "plan"
  bool plan_changed_ = false;
  std::uint32_t plan_version_ = 0;

  std::map<int, Vehicle> vehicles_;          // by receiver ID
  std::optional<common::LocalFrame> frame_;  // trails and separation; origin: the first position
  std::map<int, Track> tracks_;              // by track ID
  std::set<int> changed_tracks_;
  std::set<int> removed_tracks_;
  nlohmann::json mission_;  // null before the first message
  bool mission_changed_ = false;
  nlohmann::json radio_;
  bool radio_changed_ = false;
  std::map<int, nlohmann::json> commands_;  // by command ID, the newest commands_kept
  std::set<int> changed_commands_;
  std::uint64_t refused_ = 0;
  bool refused_changed_ = false;

  std::unique_ptr<internal::AlertLog> alerts_;
  std::unique_ptr<internal::SeparationWatch> separation_;
  std::unique_ptr<internal::ConflictWatch> conflicts_;
  bool conflicts_changed_ = false;
  std::unique_ptr<internal::CoverageRaster> coverage_;
  std::uint64_t coverage_version_ = 0;
};

}  // namespace fireswarm::server
