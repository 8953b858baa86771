// One side's secure-mode state: its keys, its frame counter and a replay window per
// key. Seals outgoing frames and opens incoming ones; both return values, never
// throw (they run in radio callbacks). Persistence is the caller's: the counter's
// reserved range and the replay floors are handed to a PersistSecurityState
// function before they are relied on, and restored through the constructor.
//
// Keys: a vehicle's key (key ID = its receiver ID) secures both directions between
// it and the server; the fleet broadcast key (key ID 255) secures what the server
// sends to receiver 255. A side may hold a previous key per key ID during a rotation
// (docs/protocol.md "Key rotation"): frames under it are still accepted, and the
// server answers a vehicle under the key that vehicle last used.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <vector>

#include "fireswarm/common/secret_key.hpp"
#include "fireswarm/radio/frame.hpp"
#include "fireswarm/radio/messages.hpp"
#include "fireswarm/radio/replay_window.hpp"
#include "fireswarm/radio/secure_frame.hpp"

namespace fireswarm::radio {

/// What a side persists so that a restart neither reuses a nonce nor takes an old frame.
struct SecurityState {
  /// First counter this side may use after a restart: one past its reserved range.
  std::uint64_t next_counter = 0;
  /// Per key ID: the lowest counter still accepted from the other side.
  std::map<std::uint8_t, std::uint32_t> floors;
  friend bool operator==(const SecurityState&, const SecurityState&) = default;
};

/// Writes the state durably; false when it could not (the frame is then not sent).
using PersistSecurityState = std::function<bool(const SecurityState&)>;

struct FrameSecurityConfig {
  /// kServerId for the server, 1..254 for a vehicle.
  std::uint8_t self_id = kServerId;
  /// Counters reserved per persisted write: a restart skips at most this many.
  std::uint32_t counter_reserve = 1024;
  /// Message IDs whose acceptance persists the sender's replay floor at once, so a
  /// recorded frame of that kind is refused after a restart too. Requests that change
  /// a vehicle (mission, command, parameter write) on a vehicle; fire reports on the server.
  std::vector<std::uint8_t> persist_floor_on;
};

/// The server's configuration: fire reports persist their vehicle's replay floor.
FrameSecurityConfig ServerSecurityConfig();
/// Vehicle `id`'s: mission chunks, commands and parameter writes persist the server's floor.
FrameSecurityConfig VehicleSecurityConfig(std::uint8_t id);

enum class SealStatus : std::uint8_t {
  kOk,
  kNoKey,             ///< no key for the receiver
  kCounterExhausted,  ///< all 2^32 counters used: rotate the keys
  kPersistFailed,     ///< the next reserved range could not be persisted
};

enum class OpenStatus : std::uint8_t {
  kOk,
  kNotForMe,    ///< addressed or keyed for another side (not counted)
  kNoKey,       ///< no key for the frame's key ID
  kReplay,      ///< counter already seen, below the floor or older than the window
  kAuthFailed,  ///< the tag did not verify: wrong key, forgery or tampering
};

/// "ok", "no_key", ...
std::string_view ToString(SealStatus status);
std::string_view ToString(OpenStatus status);

/// Counted per key ID (a vehicle's ID, or 255 for broadcasts).
struct KeySecurityStats {
  std::uint64_t sealed = 0;
  std::uint64_t opened = 0;
  std::uint64_t auth_failures = 0;
  std::uint64_t replays = 0;
  std::uint64_t no_key = 0;
  std::uint64_t previous_key_used = 0;  ///< frames authenticated under the previous key
  /// Authentication failures (or frames with no key) since the last frame that opened.
  std::uint64_t failures_in_a_row = 0;
};

/// What a key's counters say about its link, for operators and logs.
enum class KeyLinkState : std::uint8_t {
  kUnheard,      ///< nothing under this key yet
  kOk,           ///< its frames authenticate
  kAuthFailing,  ///< kFailuresToReport frames in a row failed: wrong key or forgery
  kNoKey,        ///< frames came under a key ID this side holds no key for
};
inline constexpr std::uint64_t kFailuresToReport = 3;
/// "unheard", "ok", "authentication failing", "no key".
std::string_view ToString(KeyLinkState state);
/// The state `stats` shows.
KeyLinkState LinkStateOf(const KeySecurityStats& stats);

class FrameSecurity {
 public:
  /// `restored` is what `persist` last wrote (default: a first start). `persist` may
  /// be empty: nothing is persisted (simulations).
  FrameSecurity(const FrameSecurityConfig& config, SecurityState restored,
                PersistSecurityState persist);

  /// Installs the key for `key_id`; a key already there becomes the previous key.
  void SetKey(std::uint8_t key_id, const common::SecretKey& key);
  /// Installs `key` as the previous key of `key_id` (a restart during a rotation).
  void SetPreviousKey(std::uint8_t key_id, const common::SecretKey& key);
  bool HasKey(std::uint8_t key_id) const { return keys_.contains(key_id); }

  /// Appends `plaintext` as a sealed frame to `receiver` with the next counter.
  /// On failure `out` is unchanged.
  SealStatus Seal(std::vector<std::uint8_t>& out, std::uint8_t receiver, std::uint8_t message_id,
                  std::span<const std::uint8_t> plaintext);
  /// Authenticates and decrypts a secure-mode frame. kOk: `plaintext` holds the data.
  OpenStatus Open(const FrameView& frame, std::vector<std::uint8_t>& plaintext);

  /// The key ID a frame carries (0 when it is not a secure frame).
  static std::uint8_t KeyIdOf(const FrameView& frame);

  const std::map<std::uint8_t, KeySecurityStats>& stats() const { return stats_; }
  /// The state as last handed to `persist`.
  const SecurityState& persisted() const { return persisted_; }
  /// The counter the next Seal() uses.
  std::uint64_t next_counter() const { return next_counter_; }

 private:
  struct Keys {
    common::SecretKey current{};
    std::optional<common::SecretKey> previous;
    bool peer_uses_previous = false;  // server: the vehicle was last heard under `previous`
  };

  bool Persist(const SecurityState& state);
  ReplayWindow& WindowFor(std::uint8_t key_id);

  FrameSecurityConfig config_;
  PersistSecurityState persist_;
  SecurityState persisted_;
  std::uint64_t next_counter_;
  std::map<std::uint8_t, Keys> keys_;
  std::map<std::uint8_t, ReplayWindow> windows_;
  std::map<std::uint8_t, KeySecurityStats> stats_;
};

/// Appends `message` as one frame to `receiver`: xor and crc16 modes as
/// AppendMessageFrame(), secure mode sealed by `security` (which must then be set).
/// On failure `out` is unchanged. The one way the discipline's cores build frames.
SealStatus AppendFrameFor(std::vector<std::uint8_t>& out, std::uint8_t receiver,
                          const Message& message, ChecksumMode mode, FrameSecurity* security);

/// The data of a received frame: `frame.data` in xor and crc16 modes; in secure mode
/// decrypted into `scratch` by `security` (status other than kOk: no data). The one
/// way the discipline's cores read frames.
struct OpenedData {
  OpenStatus status = OpenStatus::kOk;
  std::span<const std::uint8_t> data;
};
OpenedData OpenFrameData(const FrameView& frame, ChecksumMode mode, FrameSecurity* security,
                         std::vector<std::uint8_t>& scratch);

}  // namespace fireswarm::radio
