// The server's side of the poll-and-answer discipline (seed 5.3.1.1): the server is
// the master and decides who speaks. Each cycle, in priority order: (1) fire-report
// turns for vehicles known to hold unacknowledged reports, (2) the FireReportAcks it
// owes (at the head of the burst, no reply), (3) queued requests with ack (commands,
// mission chunks, parameter reads and writes; one outstanding per vehicle, retried
// with the same sequence number), (4) telemetry turns, most overdue first, at
// per-vehicle rates. Poll mode runs one exchange at a time; slots mode grants a batch
// of consecutive reply slots with one broadcast SlotSchedule.
//
// A pure core: Step(now, received bytes) -> bursts to transmit; NextWakeup() says
// when to call it again without new bytes. No clock, no socket.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <variant>
#include <vector>

#include "fireswarm/radio/discipline.hpp"
#include "fireswarm/radio/frame_security.hpp"
#include "fireswarm/radio/messages.hpp"
#include "fireswarm/radio/parser.hpp"
#include "fireswarm/radio/time.hpp"

namespace fireswarm::radio {

namespace internal {
struct SchedulerState;  // radio/src/scheduler_state.hpp
}  // namespace internal

struct SchedulerConfig {
  LinkMode mode = LinkMode::kSlots;
  ChecksumMode checksum = ChecksumMode::kCrc16;
  /// Secure mode: the server's keys (one per vehicle, the broadcast key), counter and
  /// replay windows (self_id == kServerId). Required when checksum is kSecure.
  std::shared_ptr<FrameSecurity> security;
  LinkTiming timing;
  /// Slots mode: idle time between consecutive slots (wire: whole microseconds).
  Nanos slot_guard{std::chrono::microseconds(500)};
  /// Added to every reply deadline beyond the reply's computed end.
  Nanos reply_margin{std::chrono::milliseconds(1)};
  /// Resends of a request whose ack did not come before it fails.
  int max_retries = 3;
  double default_telemetry_hz = 1.0;  ///< per vehicle unless set otherwise, Hz
  /// Slots mode: most slots in one SlotSchedule (at most kMaxSlots).
  std::size_t max_slots = kMaxSlots;
  /// Slots mode: a cycle (burst, turnaround and slots) is kept under this airtime;
  /// short cycles keep fire-report latency low. One slot is always granted.
  Nanos max_cycle_airtime{std::chrono::milliseconds(200)};
  /// Slots mode: vehicles due within this fraction of their period are served early
  /// to fill a cycle. Their rate is kept: the next due time stays on the period grid.
  double early_fraction = 0.25;
  /// Requests may not starve telemetry during a bulk upload. Slots mode: request
  /// frames and their ack slots take at most this fraction of max_cycle_airtime
  /// (one request always fits). Poll mode: when above 0, a request turn is followed
  /// by a due telemetry turn before the next request.
  double request_share = 0.5;
  /// Slots mode: report slots granted to one vehicle per cycle.
  std::size_t max_report_slots_per_vehicle = 2;
  /// Consecutive missed replies after which a vehicle is reported silent and gets
  /// no more report turns until it is heard again.
  int silent_after_missed_replies = 5;
  /// Sequence number of the first frame. A server restarted mid-mission starts far
  /// from where its predecessor stopped, so no vehicle takes a new request for a
  /// resend of the last one it answered (same message ID and sequence).
  std::uint16_t first_sequence = 0;
  /// Throws std::invalid_argument naming the field when a value is out of range.
  void Validate() const;
};

using RequestId = std::uint32_t;

/// A telemetry frame arrived (every one, also fallbacks in report turns).
struct TelemetryReceived {
  std::uint8_t vehicle = 0;
  Nanos received{0};
  Telemetry telemetry;
  /// The telemetry turn this frame served: its due time on the vehicle's period grid
  /// (it may arrive early, within the early window, or late, after lost replies).
  /// Empty for a frame beyond the rate (a report turn's fallback before the window).
  /// A vehicle late by more than a period starts a new grid: the turns it skipped
  /// are never served, so counting served turns measures the rate delivered.
  std::optional<Nanos> served_due;
};

/// A fire report arrived for the first time; resends of a (vehicle, report_id)
/// already seen are acknowledged again but not reported twice.
struct FireReportReceived {
  std::uint8_t vehicle = 0;
  Nanos received{0};
  FireReport report;
};

enum class RequestStatus : std::uint8_t { kCompleted, kFailed };

/// A request finished: acknowledged (with the vehicle's ack), or failed after
/// max_retries resends without an ack.
struct RequestFinished {
  RequestId id = 0;
  std::uint8_t vehicle = 0;
  RequestStatus status = RequestStatus::kCompleted;
  std::optional<Message> ack;  ///< CommandAck, MissionAck or ParamValue when completed
  int retries = 0;
  Nanos finished{0};
};

/// A request's frame went out: it is in the burst the Step() that produced this
/// event returned (the first send, or a resend with the same sequence number).
struct RequestSent {
  RequestId id = 0;
  std::uint8_t vehicle = 0;
  int attempt = 0;  ///< 0: the first send; n: the nth resend
  Nanos sent{0};    ///< start of the burst that carries it
};

/// A vehicle missed silent_after_missed_replies replies in a row (once per silence).
struct VehicleSilent {
  std::uint8_t vehicle = 0;
  Nanos last_heard{0};  ///< -1 ns when never heard
};

using SchedulerEvent = std::variant<TelemetryReceived, FireReportReceived, RequestSent,
                                    RequestFinished, VehicleSilent>;

struct SchedulerStats {
  std::uint64_t bursts = 0;
  std::uint64_t polls = 0;      ///< Poll frames sent
  std::uint64_t schedules = 0;  ///< SlotSchedule frames sent
  std::uint64_t slots_granted = 0;
  std::uint64_t requests_sent = 0;  ///< request frames, resends included
  std::uint64_t retries = 0;        ///< request resends
  std::uint64_t requests_completed = 0;
  std::uint64_t requests_failed = 0;
  std::uint64_t replies = 0;         ///< frames from known vehicles
  std::uint64_t missed_replies = 0;  ///< turns given that got no (matching) reply
  std::uint64_t telemetry = 0;
  std::uint64_t fire_reports = 0;       ///< first receipts
  std::uint64_t duplicate_reports = 0;  ///< resends of reports already received
  std::uint64_t report_acks_sent = 0;
  std::uint64_t payload_bytes = 0;  ///< data bytes of frames addressed to the server
  std::uint64_t decode_errors = 0;
  std::uint64_t unknown_senders = 0;
  /// Frames from a vehicle that had no turn in the current exchange: dropped (turn
  /// discipline as a defence: a forger must also hit the right slot).
  std::uint64_t out_of_turn = 0;
  /// Secure mode: frames to the server refused (bad tag, replay, no key, or a
  /// payload whose sender is not the vehicle whose key sealed it); counted per
  /// vehicle in the FrameSecurity's stats.
  std::uint64_t refused_frames = 0;
  /// Secure mode: frames not sent because they could not be sealed (no key for the
  /// vehicle, counter range not persisted).
  std::uint64_t seal_failures = 0;
};

/// The current exchange: one burst and the window its replies may arrive in.
struct ExchangeTiming {
  Nanos burst_start{0};
  Nanos burst_end{0};
  /// Replies are no longer expected after this: the burst's end + turnaround + the
  /// airtime of the largest expected reply + reply_margin (poll mode), or the last
  /// slot's end + reply_margin (slots mode).
  Nanos deadline{0};
  std::size_t replies_expected = 0;
};

class MasterScheduler {
 public:
  /// Throws std::invalid_argument when the configuration is invalid.
  explicit MasterScheduler(const SchedulerConfig& config);
  ~MasterScheduler();
  MasterScheduler(const MasterScheduler&) = delete;
  MasterScheduler& operator=(const MasterScheduler&) = delete;

  /// Registers a vehicle (receiver ID 1..254) with telemetry every 1/telemetry_hz s
  /// from `first_due` on (stagger first_due across vehicles to spread the load);
  /// telemetry_hz <= 0 takes default_telemetry_hz. Throws std::invalid_argument for a
  /// bad or duplicate ID or a non-finite rate.
  void AddVehicle(std::uint8_t vehicle, double telemetry_hz = 0.0, Nanos first_due = Nanos{0});
  /// Changes a vehicle's telemetry rate (Hz > 0). Throws std::invalid_argument.
  void SetTelemetryRate(std::uint8_t vehicle, double telemetry_hz);
  /// The rate a vehicle is polled for telemetry at, Hz. Throws std::invalid_argument
  /// for an unknown vehicle.
  double TelemetryRateHz(std::uint8_t vehicle) const;

  /// Queue a request for `vehicle`; the scheduler sets the header. Requests to one
  /// vehicle go one at a time, in order. Throws std::invalid_argument for an unknown
  /// vehicle (or, for a chunk, more than kMaxWaypointsPerChunk waypoints).
  /// An urgent command (a conflict's resolution) goes before the vehicle's other
  /// queued requests (after the one in flight, which keeps its sequence number)
  /// and takes the next turn before fire reports and other vehicles' requests.
  RequestId SendCommand(std::uint8_t vehicle, const Command& command, bool urgent = false);
  RequestId SendMissionChunk(std::uint8_t vehicle, const MissionChunk& chunk);
  RequestId ReadParam(std::uint8_t vehicle, std::uint16_t param_id);
  RequestId WriteParam(std::uint8_t vehicle, std::uint16_t param_id, float value);

  /// Feeds the bytes received up to `now` and returns what to transmit: at most one
  /// burst, starting at now + turnaround. Call it whenever bytes arrive and at
  /// NextWakeup(). `now` must not decrease. Never throws.
  std::vector<Burst> Step(Nanos now, std::span<const std::uint8_t> received);

  /// When Step() must next be called if no bytes arrive: the current exchange's
  /// deadline, or when the next turn is due; Nanos::max() with nothing to do.
  Nanos NextWakeup() const;

  /// Events since the last call, in the order they happened.
  std::vector<SchedulerEvent> TakeEvents();

  /// The exchange in progress, if any.
  std::optional<ExchangeTiming> exchange() const;
  const SchedulerStats& stats() const;
  const ParserStats& parser_stats() const;
  const SchedulerConfig& config() const;
  /// Sequence number the next frame will carry.
  std::uint16_t next_sequence() const;

 private:
  std::unique_ptr<internal::SchedulerState> state_;
};

}  // namespace fireswarm::radio
