// The LCM side of the server: what it publishes (vehicle_state_t, fire tracks,
// mission_status_t, radio_stats_t, plan_t, each at its own rate; command_status_t
// when a command is accepted or one of its targets changes state), what it accepts
// (operator_command_t), the LCM log it writes for the stock `lcm-logplayer`, and
// the per-message CSV files (not plan_t: one GeoJSON string; the seed's ground station logged its
// telemetry to CSV at fixed rates, 3.6).
//
// Times: LCM `utime` fields are microseconds of the clock the caller passes:
// `fireswarm serve` passes the Unix-epoch wall clock; `fireswarm run` passes
// simulated time from the scenario's start (so a run's log is reproducible).
//
// The conversions are pure (lcm_messages.cpp); LcmBridge is the adapter that owns
// the lcm::LCM instance and the files (lcm_bridge.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include "fireswarm/command_status_t.hpp"
#include "fireswarm/conflict_t.hpp"
#include "fireswarm/fire_track_list_t.hpp"
#include "fireswarm/mission_status_t.hpp"
#include "fireswarm/operator_command_t.hpp"
#include "fireswarm/plan_t.hpp"
#include "fireswarm/radio_stats_t.hpp"
#include "fireswarm/server/server.hpp"
#include "fireswarm/vehicle_state_t.hpp"

namespace lcm {
class LCM;
class LogFile;
struct ReceiveBuffer;
}  // namespace lcm

namespace fireswarm::server {

/// The LCM URL the examples and the docs give: host-local (ttl=0: multicast
/// never leaves this machine). Operator commands are signed either way.
inline constexpr const char* kDefaultLcmUrl = "udpm://239.255.76.67:7667?ttl=0";

/// Channel names.
inline constexpr const char* kVehicleStateChannel = "FIRESWARM_VEHICLE_STATE";
inline constexpr const char* kFireTracksChannel = "FIRESWARM_FIRE_TRACKS";
inline constexpr const char* kMissionStatusChannel = "FIRESWARM_MISSION_STATUS";
inline constexpr const char* kRadioStatsChannel = "FIRESWARM_RADIO_STATS";
inline constexpr const char* kOperatorCommandChannel = "FIRESWARM_OPERATOR_COMMAND";
inline constexpr const char* kCommandStatusChannel = "FIRESWARM_COMMAND_STATUS";
inline constexpr const char* kPlanChannel = "FIRESWARM_PLAN";
inline constexpr const char* kConflictChannel = "FIRESWARM_CONFLICTS";

/// Publication rates, Hz (0 = not published).
struct LcmRates {
  double vehicle_state_hz = 2.0;  ///< every vehicle, each period
  double fire_tracks_hz = 1.0;
  double mission_status_hz = 1.0;
  double radio_stats_hz = 0.5;
  /// plan_t: at once when a mission is loaded, then at this rate.
  double plan_hz = 0.2;
  /// Throws std::invalid_argument naming the rate that is negative or not finite.
  void Validate() const;
};

// ---- Pure conversions (lcm_messages.cpp) -------------------------------------

/// One registered vehicle at `now_s` (mission seconds), stamped `utime`.
vehicle_state_t ToVehicleState(const Server& server, std::uint8_t vehicle, double now_s,
                               std::int64_t utime);
/// Every track, ascending by ID, positions in WGS84 through the server's frame;
/// track times converted with utime = `utime_at_zero` + seconds * 1e6.
fire_track_list_t ToFireTrackList(const Server& server, std::int64_t utime,
                                  std::int64_t utime_at_zero);
/// The mission's state and figures. coverage_fraction is Server::coverage()'s
/// fraction (the cameras' coverage from telemetry, as a run's report counts it);
/// without ServerConfig::area it falls back to MissionManager::WaypointFraction
/// (0 without a mission).
mission_status_t ToMissionStatus(const Server& server, double now_s, std::int64_t utime);
/// The mission's plan (plan_geojson.hpp's PlanGeoJson, compact) with the
/// mission ID mission_status_t gives.
plan_t ToPlan(const Server& server, std::int64_t utime);
/// The counters a radio_stats_t window is the difference of.
struct RadioCounters {
  std::vector<radio::SchedulerStats> stats;  ///< per channel
  std::vector<radio::ChannelBytes> bytes;    ///< per channel
};
/// Counters since the start; busy fraction (airtime of the bytes the server sent
/// and received: a lower bound, turnarounds not counted) and payload rate over the
/// last `window_s`, from the difference with `previous`, which is then updated.
/// The fleet's fields add every channel up (busy_fraction: the busiest channel's);
/// the channel_* arrays are each channel's.
radio_stats_t ToRadioStats(const Server& server, double now_s, std::int64_t utime, double window_s,
                           RadioCounters& previous);
/// One command's record (Server::commands()) stamped `utime`; its issue time
/// converted with utime = `utime_at_zero` + seconds * 1e6.
command_status_t ToCommandStatus(const CommandRecord& record, std::int64_t utime,
                                 std::int64_t utime_at_zero);
/// A refused command's status: command_id 0, no targets, `refusal` = its why.
command_status_t ToCommandStatus(const CommandRefused& refusal, std::int64_t utime);
/// One conflict of the tactical watch (traffic.hpp); its times converted with
/// utime = `utime_at_zero` + seconds * 1e6.
conflict_t ToConflict(const Conflict& conflict, std::int64_t utime, std::int64_t utime_at_zero);
/// An operator's command as the server takes it; nullopt (with the reason in
/// `why`) when the command constant is unknown or a field is out of range.
/// Lossless for the commands it takes (MAC input: command_auth.hpp).
std::optional<OperatorCommand> FromLcm(const operator_command_t& message, std::string* why);
/// operator_command_t bytes as they arrive on kOperatorCommandChannel, decoded;
/// nullopt when they are not one. Never throws, and never hands a bad string
/// length to the generated decode (LcmStringsFit).
std::optional<operator_command_t> DecodeOperatorCommand(std::span<const std::uint8_t> bytes);

/// Where the strings of an encoded message begin (its 8-byte hash included):
/// operator_command_t's reason and operator_id follow its utime, command,
/// target_vehicle, lat_deg, lon_deg and radius_m; plan_t's geojson its utime and
/// mission_id. tests/server/lcm_bridge_test.cpp checks both against lcm-gen's encode.
inline constexpr std::size_t kOperatorCommandStringsAt = 8 + 8 + 1 + 2 + 3 * 8;
inline constexpr std::size_t kPlanStringsAt = 8 + 8 + 4;

/// True when the `count` strings one after the other from byte `at` of `bytes`
/// each have a length (a big-endian int32 counting its NUL) of 1 up to the bytes
/// left. LCM 1.3.1's generated decode trusts that length: 0 or less throws
/// std::length_error, and INT32_MIN overflows `length - 1` (undefined; in practice
/// a 2 GiB read past the buffer: one packet on the LCM group could crash the
/// server; found by fuzz/operator_command). Check outside bytes with it before
/// decoding a message with strings.
bool LcmStringsFit(std::span<const std::uint8_t> bytes, std::size_t at, int count);
/// The message's credentials: operator_id, utime, nonce, mac.
CommandCredentials CredentialsFromLcm(const operator_command_t& message);
/// A signed command as an operator's tool publishes it.
operator_command_t ToLcm(const SignedCommand& command);

/// What the bridge takes from LCM: a command to verify and carry out, or one it
/// could not read (a kMalformed refusal for Server::Refuse).
using IncomingCommand = std::variant<SignedCommand, CommandRefused>;

// ---- The adapter (lcm_bridge.cpp) --------------------------------------------

struct LcmBridgeConfig {
  /// LCM provider URL ("udpm://239.255.76.67:7667?ttl=0", "memq://"); empty: no
  /// network, only the log and CSV files.
  std::string url;
  LcmRates rates;
  std::optional<std::filesystem::path> log_path;  ///< LCM event log to write
  std::optional<std::filesystem::path> csv_dir;   ///< one CSV per message type
};

class LcmBridge {
 public:
  /// Throws std::runtime_error naming the URL or file when LCM cannot start or a
  /// file cannot be created; std::invalid_argument for a bad rate.
  explicit LcmBridge(const LcmBridgeConfig& config);
  ~LcmBridge();
  LcmBridge(const LcmBridge&) = delete;
  LcmBridge& operator=(const LcmBridge&) = delete;

  /// Publishes (and logs, and writes to CSV) every message type whose period has
  /// come round at `now_s` (mission seconds), a command_status_t for every
  /// command accepted or changed, and every refusal, and a conflict_t for every
  /// conflict detected, resolved or closed, since the last call; `utime` stamps them.
  void Publish(const Server& server, double now_s, std::int64_t utime, std::int64_t utime_at_zero);
  /// Operator commands received since the last call (handles pending LCM
  /// traffic without blocking), for Server::HandleSigned; malformed ones come as
  /// refusals (for Server::Refuse) and are counted in rejected_commands().
  std::vector<IncomingCommand> TakeCommands();
  /// When Publish next has something to publish, mission seconds.
  double NextPublishS() const;

  /// The bridge's LCM instance (null without a URL): in-process listeners
  /// subscribe here, as memq:// delivers only within the instance that publishes.
  lcm::LCM* lcm() { return lcm_.get(); }

  std::uint64_t published() const { return published_; }
  std::uint64_t rejected_commands() const { return rejected_commands_; }

 private:
  template <typename Message>
  void Emit(const char* channel, const Message& message, std::int64_t utime);
  void OnCommandMessage(const lcm::ReceiveBuffer* buffer, const std::string& channel);

  LcmBridgeConfig config_;
  std::unique_ptr<lcm::LCM> lcm_;
  std::unique_ptr<lcm::LogFile> log_;
  std::map<std::string, std::ofstream> csv_;
  std::map<std::string, double> next_s_;  // per channel
  RadioCounters previous_counters_;
  double previous_radio_stats_s_ = 0.0;
  std::vector<IncomingCommand> commands_;
  std::uint64_t commands_version_ = 0;    // Server::commands_version() last published
  std::uint64_t traffic_version_ = 0;     // TrafficControl::version() last published
  std::uint64_t refusals_published_ = 0;  // Server::refusal_count() last published
  std::uint64_t published_ = 0;
  std::uint64_t rejected_commands_ = 0;
};

}  // namespace fireswarm::server
