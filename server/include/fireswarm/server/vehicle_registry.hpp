// The fleet as the server knows it: one entry per vehicle, keyed by its radio
// receiver ID, holding the latest telemetry, when it arrived, how many turns went
// unanswered, and the state of the link derived from those.
//
// Pure: every call that depends on time takes the server's mission clock
// (seconds); nothing here reads a clock or touches the radio.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "fireswarm/radio/messages.hpp"

namespace fireswarm::server {

/// Lowest and highest receiver ID a vehicle may have (0 is the server, 255 broadcast).
inline constexpr int kFirstVehicleId = radio::kFirstVehicleId;
inline constexpr int kLastVehicleId = radio::kLastVehicleId;

/// The server's view of the radio link to one vehicle. The values are those of
/// lcmtypes/vehicle_state_t.lcm's LINK_* constants, so the LCM bridge maps one to one.
enum class LinkState : std::int8_t {
  kNeverHeard = 0,  ///< registered, but no reply received yet
  kOk = 1,          ///< last heard less than degraded_after_s ago
  kDegraded = 2,    ///< last heard at least degraded_after_s but less than lost_after_s ago
  kLost = 3,        ///< last heard lost_after_s ago or more
};

/// "never_heard", "ok", "degraded", "lost".
std::string_view ToString(LinkState state);

/// Degraded after 3 s of silence: several telemetry turns (polled at about 1 Hz
/// or faster) have gone unanswered, which a single collision or bit error does not
/// explain.
inline constexpr double kDefaultDegradedAfterS = 3.0;

/// Lost after 10 s of silence. Deliberately below the vehicle's own link-lost
/// timeout (agents parameter safety.link_lost_timeout_s, default 30 s): a vehicle
/// that stops hearing the server flies home after 30 s, and by then the server has
/// already counted it lost for 20 s and can hand its search lanes to others. The
/// two clocks measure different directions: the vehicle times frames it hears from
/// the server, the server times replies it hears from the vehicle; a vehicle whose
/// replies alone are lost keeps flying its mission while the server calls it Lost.
/// A vehicle configured with a timeout below this value would return before the
/// server notices; keep safety.link_lost_timeout_s above lost_after_s.
inline constexpr double kDefaultLostAfterS = 10.0;

/// Silence thresholds of the link state, in seconds since the vehicle was last heard.
struct LinkThresholds {
  double degraded_after_s = kDefaultDegradedAfterS;
  double lost_after_s = kDefaultLostAfterS;
};

/// Everything the registry holds about one vehicle.
struct VehicleState {
  std::uint8_t id = 0;  ///< receiver ID, 1..254
  /// Latest telemetry received; nullopt until the first arrives.
  std::optional<radio::Telemetry> telemetry;
  /// Mission-clock time the latest telemetry was received, seconds; meaningful only
  /// when `telemetry` holds a value.
  double telemetry_time_s = 0.0;
  /// Mission-clock time of the latest reply of any kind (telemetry, fire report,
  /// acknowledgement), seconds; nullopt until the first. The link state follows it.
  std::optional<double> last_heard_s;
  /// Turns given to the vehicle without an answer since its last reply.
  std::uint32_t missed_replies = 0;
  std::uint64_t total_missed_replies = 0;  ///< since registration
  std::uint64_t total_replies = 0;         ///< since registration, telemetry included
};

/// The registered vehicles. Not thread-safe.
class VehicleRegistry {
 public:
  /// Throws std::invalid_argument unless 0 < degraded_after_s < lost_after_s, both finite.
  explicit VehicleRegistry(LinkThresholds thresholds = {});

  /// Adds a vehicle. The ID is an int so a configured 300 is refused rather than
  /// wrapped. Throws std::invalid_argument naming the ID when it is outside
  /// [kFirstVehicleId, kLastVehicleId] or already registered.
  void Register(int receiver_id);

  /// True when `receiver_id` is registered.
  bool Contains(std::uint8_t receiver_id) const;

  /// Records telemetry from vehicle `telemetry.header.sender`, received at `now_s`
  /// (mission clock, seconds). It is also that vehicle's answer to its turn, with
  /// the effect of OnReply: call one or the other for one answer, not both. Returns
  /// false and changes nothing when the sender is not registered, `now_s` is not
  /// finite, or `now_s` is earlier than the telemetry already held (a late
  /// duplicate must not replace newer data). Never throws: radio callbacks call it.
  bool OnTelemetry(const radio::Telemetry& telemetry, double now_s);

  /// The vehicle answered its turn at `now_s` (seconds) with something other than
  /// telemetry (a fire report, an acknowledgement): clears the consecutive
  /// missed-reply count and refreshes the link. Returns false and changes nothing
  /// for an unknown ID or a non-finite `now_s`. Never throws.
  bool OnReply(std::uint8_t receiver_id, double now_s);

  /// The vehicle was given a turn and did not answer. Returns false for an unknown
  /// ID. Never throws.
  bool OnMissedReply(std::uint8_t receiver_id);

  /// Everything known about a vehicle. Throws std::out_of_range naming the ID when
  /// it is not registered.
  const VehicleState& state(std::uint8_t receiver_id) const;

  /// Link state of a registered vehicle at `now_s` (seconds). Throws
  /// std::out_of_range naming the ID when it is not registered.
  LinkState LinkAt(std::uint8_t receiver_id, double now_s) const;

  /// Seconds between the latest telemetry and `now_s`, never negative; nullopt when
  /// none has been received. Throws std::out_of_range for an unregistered ID.
  std::optional<double> TelemetryAgeS(std::uint8_t receiver_id, double now_s) const;

  /// Registered IDs, ascending.
  std::vector<std::uint8_t> ids() const;
  /// IDs whose link is kLost at `now_s`, ascending (never-heard vehicles are not lost).
  std::vector<std::uint8_t> LostAt(double now_s) const;
  /// IDs whose link is kOk or kDegraded at `now_s`, ascending.
  std::vector<std::uint8_t> ActiveAt(double now_s) const;

  std::size_t size() const { return size_; }
  const LinkThresholds& thresholds() const { return thresholds_; }

 private:
  VehicleState* Find(std::uint8_t receiver_id);
  const VehicleState& Get(std::uint8_t receiver_id) const;
  LinkState LinkOf(const VehicleState& vehicle, double now_s) const;
  std::vector<std::uint8_t> IdsWhere(double now_s, bool (*keep)(LinkState)) const;

  LinkThresholds thresholds_;
  // By receiver ID: the server looks vehicles up several times per step for
  // each of up to 254 drones, and walks them in ascending ID order.
  std::array<std::optional<VehicleState>, 256> vehicles_;
  std::size_t size_ = 0;
};

}  // namespace fireswarm::server
