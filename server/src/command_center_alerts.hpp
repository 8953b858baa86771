// The command center's alerts: raised by transitions between consecutive LCM
// messages, kept newest-last in a bounded log (docs/command_center.md).
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <string>
#include <string_view>
#include <utility>

#include "fireswarm/conflict_t.hpp"
#include "fireswarm/fire_track_t.hpp"
#include "fireswarm/radio_stats_t.hpp"
#include "fireswarm/vehicle_state_t.hpp"

namespace fireswarm::server::internal {

enum class AlertLevel { kInfo, kWarning, kCritical };

/// The newest `kept` alerts, IDs from 1 in the order raised.
class AlertLog {
 public:
  explicit AlertLog(std::size_t kept) : kept_(kept) {}
  /// Raises one alert. `vehicle` and `track` are 0 when the alert is about none.
  void Add(double time_s, AlertLevel level, std::string_view kind, int vehicle, int track,
           std::string text);
  /// Every kept alert, oldest first: [{id, time_s, level, kind, vehicle, track, text}].
  nlohmann::json All() const;
  /// The kept alerts raised since the last call, oldest first.
  nlohmann::json TakeNew();
  bool has_new() const { return unsent_ > 0; }

 private:
  std::size_t kept_;
  std::deque<nlohmann::json> alerts_;
  std::uint64_t next_id_ = 1;
  std::size_t unsent_ = 0;  // the newest alerts not yet taken, at most alerts_.size()
};

/// The battery is low: FLAG_LOW_BATTERY, or returning to launch (the vehicle's
/// own low-battery reaction) with at most kLowBatteryPercent left.
inline constexpr double kLowBatteryPercent = 20.0;
bool BatteryLow(const vehicle_state_t& message);

/// Alerts from one vehicle's state against its previous one (nullptr: its first
/// message, compared with a vehicle never heard, flags clear and task idle):
/// link_degraded (link turned degraded from ok or never heard), link_lost (turned
/// lost), battery_low (BatteryLow turned true), vehicle_given_up (task turned
/// TASK_GIVEN_UP).
void RaiseVehicleAlerts(const vehicle_state_t* previous, const vehicle_state_t& now, AlertLog& log);

/// Alerts from one fire track against its previous status (nullopt: a track ID not
/// seen before): new_fire (a new ID, unless it is already rejected), fire_confirmed
/// (status turned confirmed).
void RaiseTrackAlerts(std::optional<int> previous_status, const fire_track_t& track, double time_s,
                      AlertLog& log);

/// Alerts from the radio channels against the radio panel's previous JSON
/// (RadioJson; null before the first message): channel_silent (a channel turned
/// silent: every vehicle on it stopped answering, its modem or link is likely
/// dead) and channel_heard (a silent channel answers again).
void RaiseChannelAlerts(const nlohmann::json& previous_radio, const radio_stats_t& now,
                        double time_s, AlertLog& log);

/// Below this a drone is on the ground or taking off, metres above the launch ground.
inline constexpr double kAirborneMinAltitudeM = 2.0;
/// Flying with a known position: has a fix, has telemetry, is neither idle nor
/// landed, and is above kAirborneMinAltitudeM.
bool IsAirborne(const vehicle_state_t& message);

/// Pairs of airborne drones closer than the separation, 3-D: one `separation`
/// alert per pair until they part by more than kSeparationClearFactor times it
/// (or one of them is no longer airborne).
class SeparationWatch {
 public:
  static constexpr double kSeparationClearFactor = 1.5;
  explicit SeparationWatch(double separation_m) : separation_m_(separation_m) {}
  /// The vehicle's position in one local frame (east, north, up; metres), or
  /// nullopt when it is not airborne; checked against every other airborne drone.
  void Update(int vehicle, const std::optional<Eigen::Vector3d>& position_enu_m, double time_s,
              AlertLog& log);

 private:
  double separation_m_;
  std::map<int, Eigen::Vector3d> airborne_;
  std::set<std::pair<int, int>> close_;  // (lower ID, higher ID) alerted, not yet parted
};

/// The server's predicted conflicts (conflict_t), one alert per step of each:
/// "conflict" (warning) when predicted, "conflict_resolution" (info) when a drone
/// is ordered out of it, "conflict_resolved" (info) or "separation_lost"
/// (critical) when it is over. Counts them for the state's "conflicts".
class ConflictWatch {
 public:
  void Update(const conflict_t& message, AlertLog& log);
  /// {"predicted", "ordered", "resolved", "lost_separation", "open"}.
  nlohmann::json Counts() const;

 private:
  struct Seen {
    std::int8_t resolution = conflict_t::RESOLUTION_NONE;
    std::int8_t outcome = conflict_t::OUTCOME_OPEN;
  };
  std::map<int, Seen> seen_;  // by conflict ID
  std::uint64_t predicted_ = 0;
  std::uint64_t ordered_ = 0;
  std::uint64_t resolved_ = 0;
  std::uint64_t lost_separation_ = 0;
};

}  // namespace fireswarm::server::internal
