// Message payloads of the fleet protocol, carried as the data of APOne frames.
// Every payload begins with the sender's receiver ID (1 byte) and a sequence
// number (2 bytes, little-endian), so replies are attributable and retries can be
// de-duplicated. Multi-byte fields are little-endian; positions are fixed point
// (1e-7 degree). docs/protocol.md gives every payload byte by byte.
//
// The structs hold engineering units (degrees, metres, seconds); the codec rounds
// them to the wire's fixed point and clamps to each field's range.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <variant>
#include <vector>

#include "fireswarm/radio/frame.hpp"

namespace fireswarm::radio {

/// Frame message IDs. Server -> vehicle: 0x01-0x0F, 0x12, 0x20, 0x30, 0x40, 0x41.
enum class MessageId : std::uint8_t {
  kPoll = 0x01,           ///< server gives one vehicle the turn to answer
  kSlotSchedule = 0x02,   ///< broadcast: several vehicles answer in consecutive slots
  kTelemetry = 0x10,      ///< vehicle state
  kFireReport = 0x11,     ///< one geolocated fire detection
  kFireReportAck = 0x12,  ///< server has the report: the vehicle may drop it
  kMissionChunk = 0x20,   ///< part of a mission upload
  kMissionAck = 0x21,     ///< vehicle's answer to a chunk
  kCommand = 0x30,        ///< start, abort, return, land, investigate, ...
  kCommandAck = 0x31,     ///< vehicle's answer to a command
  kParamRead = 0x40,      ///< read one parameter
  kParamWrite = 0x41,     ///< write (and persist) one parameter
  kParamValue = 0x42,     ///< vehicle's answer to a read or write
  kHeartbeat = 0x50,      ///< liveness, either direction
};

/// Name of a known message ID ("telemetry", ...), nullopt for an unknown one.
std::optional<std::string_view> MessageName(std::uint8_t message_id);

/// Sender and sequence number: the first 3 bytes of every payload.
struct MessageHeader {
  std::uint8_t sender = 0;
  std::uint16_t sequence = 0;
  friend bool operator==(const MessageHeader&, const MessageHeader&) = default;
};

/// What a vehicle sends when given the turn.
enum class ReplyKind : std::uint8_t {
  kTelemetry = 1,   ///< one Telemetry frame
  kFireReport = 2,  ///< the oldest unacknowledged FireReport
  kAck = 3,         ///< the answer to the request addressed to it just before
};
/// "telemetry", "fire_report", "ack"; "unknown" outside the enum.
std::string_view ToString(ReplyKind kind);

struct Poll {
  MessageHeader header;
  ReplyKind reply = ReplyKind::kTelemetry;
  friend bool operator==(const Poll&, const Poll&) = default;
};

/// One reply slot in a SlotSchedule.
struct Slot {
  std::uint8_t receiver = 0;
  ReplyKind reply = ReplyKind::kTelemetry;
  std::uint8_t slot_bytes = 0;  ///< airtime of the slot in bytes at the link's baud
  friend bool operator==(const Slot&, const Slot&) = default;
};

inline constexpr std::size_t kMaxSlots = 64;

/// Broadcast grant of consecutive reply slots. Slot k starts at the end of this
/// frame + first_slot_delay + sum over j<k of (Airtime(slot_bytes_j) + guard).
struct SlotSchedule {
  MessageHeader header;
  std::uint32_t first_slot_delay_us = 0;  ///< wire: u16 microseconds (max 65,535)
  std::uint32_t guard_us = 0;             ///< wire: u16 microseconds between slots
  std::uint8_t slot_count = 0;
  std::array<Slot, kMaxSlots> slots{};
  std::span<const Slot> active() const { return {slots.data(), slot_count}; }
  friend bool operator==(const SlotSchedule&, const SlotSchedule&) = default;
};

enum class FlightMode : std::uint8_t {
  kIdle = 0,
  kTakeoff = 1,
  kSearch = 2,
  kInvestigate = 3,
  kReturnToLaunch = 4,
  kLand = 5,
  kLanded = 6,
  kHold = 7,
};
/// The mode's name in reports, logs and JSON: "idle", "takeoff", "search",
/// "investigate", "return_to_launch", "land", "landed", "hold"; "unknown" outside
/// the enum (possible only for messages built in memory, never decoded ones).
std::string_view ToString(FlightMode mode);

/// Telemetry flag bits.
namespace telemetry_flags {
inline constexpr std::uint8_t kReportPending = 1U << 0;  ///< a fire report waits for a turn
inline constexpr std::uint8_t kMissionValid = 1U << 1;   ///< a complete mission is stored
inline constexpr std::uint8_t kLowBattery = 1U << 2;
inline constexpr std::uint8_t kLinkLost = 1U << 3;  ///< returning: server not heard
inline constexpr std::uint8_t kGpsFix = 1U << 4;
}  // namespace telemetry_flags

struct Telemetry {
  MessageHeader header;
  std::uint32_t time_ms = 0;        ///< vehicle clock at sampling, ms since boot
  double lat_deg = 0.0;             ///< wire: i32, 1e-7 deg
  double lon_deg = 0.0;             ///< wire: i32, 1e-7 deg
  double altitude_m = 0.0;          ///< above launch ground; wire: i32 cm
  double velocity_north_mps = 0.0;  ///< wire: i16 cm/s
  double velocity_east_mps = 0.0;   ///< wire: i16 cm/s
  double climb_rate_mps = 0.0;      ///< up positive; wire: i16 cm/s
  double roll_deg = 0.0;            ///< wire: i16 0.01 deg
  double pitch_deg = 0.0;           ///< wire: i16 0.01 deg
  double heading_deg = 0.0;         ///< [0, 360) clockwise from north; wire: u16 0.01 deg
  double battery_v = 0.0;           ///< wire: u16 mV
  std::uint8_t battery_percent = 0;
  FlightMode mode = FlightMode::kIdle;
  std::uint8_t flags = 0;            ///< telemetry_flags
  std::uint8_t pending_reports = 0;  ///< fire reports queued, saturating at 255
  std::uint16_t mission_id = 0;
  std::uint16_t waypoint_index = 0;
  friend bool operator==(const Telemetry&, const Telemetry&) = default;
};

struct FireReport {
  MessageHeader header;
  std::uint16_t report_id = 0;  ///< per vehicle; a resend keeps its ID
  std::uint32_t time_ms = 0;    ///< detection time, vehicle clock
  double lat_deg = 0.0;         ///< estimated fire position; wire: i32 1e-7 deg
  double lon_deg = 0.0;
  double sigma_north_m = 0.0;     ///< 1-sigma; wire: u16 cm
  double sigma_east_m = 0.0;      ///< 1-sigma; wire: u16 cm
  double correlation = 0.0;       ///< north-east correlation in [-1, 1]; wire: i16 1e-4
  double observer_lat_deg = 0.0;  ///< vehicle position at detection; wire: i32 1e-7 deg
  double observer_lon_deg = 0.0;
  double observer_altitude_m = 0.0;  ///< wire: i16 dm
  std::uint16_t pixel_count = 0;     ///< size of the hot region
  double peak_temperature_c = 0.0;   ///< wire: i16 0.1 C
  double confidence = 0.0;           ///< [0, 1]; wire: u8 1/255
  friend bool operator==(const FireReport&, const FireReport&) = default;
};

struct FireReportAck {
  MessageHeader header;
  std::uint8_t vehicle = 0;  ///< the reporting vehicle
  std::uint16_t report_id = 0;
  friend bool operator==(const FireReportAck&, const FireReportAck&) = default;
};

/// One mission waypoint on the wire: 12 bytes.
struct Waypoint {
  double lat_deg = 0.0;     ///< wire: i32 1e-7 deg
  double lon_deg = 0.0;     ///< wire: i32 1e-7 deg
  double altitude_m = 0.0;  ///< above ground; wire: u16 dm
  double speed_mps = 0.0;   ///< wire: u8 0.1 m/s
  std::uint8_t flags = 0;   ///< kLaneStart or 0
  friend bool operator==(const Waypoint&, const Waypoint&) = default;

  /// `flags` bit 0: this waypoint starts a search lane.
  static constexpr std::uint8_t kLaneStart = 1U << 0;
};

inline constexpr std::size_t kMaxWaypointsPerChunk = 20;

struct MissionChunk {
  MessageHeader header;
  std::uint16_t mission_id = 0;
  std::uint8_t chunk_index = 0;
  std::uint8_t chunk_count = 0;
  std::uint16_t total_waypoints = 0;
  std::uint16_t first_waypoint = 0;  ///< index of waypoints[0] in the mission
  std::uint8_t waypoint_count = 0;
  std::array<Waypoint, kMaxWaypointsPerChunk> waypoints{};
  std::span<const Waypoint> active() const { return {waypoints.data(), waypoint_count}; }
  friend bool operator==(const MissionChunk&, const MissionChunk&) = default;
};

enum class MissionAckStatus : std::uint8_t {
  kAccepted = 0,  ///< chunk stored, more expected
  kComplete = 1,  ///< every chunk of the mission is stored: it may fly
  kRejected = 2,  ///< chunk inconsistent with the mission being uploaded
};
/// "accepted", "complete", "rejected"; "unknown" outside the enum.
std::string_view ToString(MissionAckStatus status);

struct MissionAck {
  MessageHeader header;
  std::uint16_t mission_id = 0;
  std::uint8_t chunk_index = 0;
  MissionAckStatus status = MissionAckStatus::kAccepted;
  friend bool operator==(const MissionAck&, const MissionAck&) = default;
};

enum class CommandType : std::uint8_t {
  kStartMission = 1,
  kHold = 2,
  kResume = 3,
  kReturnToLaunch = 4,
  kLand = 5,
  kInvestigate = 6,  ///< loiter around (lat, lon) at radius, keeping the camera on it
  kAbort = 7,
  /// Fly at altitude_m (above launch ground) for duration_s, horizontally as
  /// before: the server's tactical resolution of a predicted conflict (a climb, a
  /// descent, or "stay at this altitude", which holds a take-off, a landing or a
  /// climb where it is). altitude_m 0 ends an earlier one; duration_s 0 is refused.
  kAvoid = 8,
};
/// "start_mission", "hold", "resume", "return_to_launch", "land", "investigate",
/// "abort", "avoid"; "unknown" outside the enum.
std::string_view ToString(CommandType type);

struct Command {
  MessageHeader header;
  CommandType type = CommandType::kHold;
  std::uint16_t mission_id = 0;  ///< for kStartMission
  double lat_deg = 0.0;          ///< for kInvestigate; wire: i32 1e-7 deg
  double lon_deg = 0.0;
  double altitude_m = 0.0;       ///< for kInvestigate, kAvoid; wire: u16 dm
  double radius_m = 0.0;         ///< wire: u16 dm
  std::uint16_t duration_s = 0;  ///< loiter (avoid) time; 0 = until told otherwise
  friend bool operator==(const Command&, const Command&) = default;
};

enum class CommandResult : std::uint8_t { kAccepted = 0, kRejected = 1, kUnsupported = 2 };
/// "accepted", "rejected", "unsupported"; "unknown" outside the enum.
std::string_view ToString(CommandResult result);

struct CommandAck {
  MessageHeader header;
  std::uint16_t acked_sequence = 0;  ///< sequence number of the Command
  CommandType type = CommandType::kHold;
  CommandResult result = CommandResult::kAccepted;
  friend bool operator==(const CommandAck&, const CommandAck&) = default;
};

struct ParamRead {
  MessageHeader header;
  std::uint16_t param_id = 0;
  friend bool operator==(const ParamRead&, const ParamRead&) = default;
};

/// Parameter values are IEEE-754 binary32, little-endian: PID gains span too many
/// decades for one fixed-point scale (the seed also sent floats as raw bytes, 5.3.3).
struct ParamWrite {
  MessageHeader header;
  std::uint16_t param_id = 0;
  float value = 0.0F;
  friend bool operator==(const ParamWrite&, const ParamWrite&) = default;
};

enum class ParamStatus : std::uint8_t {
  kOk = 0,
  kUnknownParam = 1,
  kReadOnly = 2,
  kOutOfRange = 3
};
/// "ok", "unknown_param", "read_only", "out_of_range"; "unknown" outside the enum.
std::string_view ToString(ParamStatus status);

struct ParamValue {
  MessageHeader header;
  std::uint16_t param_id = 0;
  float value = 0.0F;
  ParamStatus status = ParamStatus::kOk;
  friend bool operator==(const ParamValue&, const ParamValue&) = default;
};

struct Heartbeat {
  MessageHeader header;
  std::uint32_t time_ms = 0;
  FlightMode mode = FlightMode::kIdle;
  std::uint8_t flags = 0;
  friend bool operator==(const Heartbeat&, const Heartbeat&) = default;
};

using Message =
    std::variant<Poll, SlotSchedule, Telemetry, FireReport, FireReportAck, MissionChunk, MissionAck,
                 Command, CommandAck, ParamRead, ParamWrite, ParamValue, Heartbeat>;

MessageId IdOf(const Message& message);
const MessageHeader& HeaderOf(const Message& message);

/// Why a payload did not decode. Bad payloads are values, never exceptions.
enum class DecodeError : std::uint8_t {
  kNone = 0,
  kUnknownMessageId,  ///< no payload layout for this ID
  kTooShort,          ///< fewer bytes than the layout needs
  kTooLong,           ///< trailing bytes after the layout
  kBadValue,          ///< an enum, a count or a range-limited field (heading, correlation)
                      ///< out of range, or a count that disagrees with the length
};
std::string_view ToString(DecodeError error);

struct DecodeResult {
  std::optional<Message> message;
  DecodeError error = DecodeError::kNone;
};

/// Decodes a frame's data as the payload of `message_id`. Never reads past `data`.
DecodeResult DecodePayload(std::uint8_t message_id, std::span<const std::uint8_t> data);

/// Appends the payload bytes of `message` (no frame) to `out`. Throws
/// std::invalid_argument (leaving `out` unchanged) when slot_count or waypoint_count
/// exceeds its array, which would make the payload too long for a frame.
void EncodePayload(const Message& message, std::vector<std::uint8_t>& out);

/// Appends `message` as one complete frame addressed to `receiver`.
void AppendMessageFrame(std::vector<std::uint8_t>& out, std::uint8_t receiver,
                        const Message& message, ChecksumMode mode);

/// Payload size of a message of this ID; for variable-length messages (SlotSchedule,
/// MissionChunk) the size with the given number of entries. Throws
/// std::invalid_argument for an ID outside MessageId.
std::size_t PayloadSize(MessageId id, std::size_t entries = 0);

}  // namespace fireswarm::radio
