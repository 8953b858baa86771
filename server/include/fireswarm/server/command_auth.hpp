// Authenticated operator commands (issue 17): every command carries who sent it
// (an operator ID), when (a utime on the server's LCM clock), a nonce and an
// HMAC-SHA256 tag under that operator's 256-bit key over a canonical byte
// encoding of all of it (docs/lcm.md "Operator command authentication" gives
// the encoding byte by byte; the page's JS builds the same bytes). Pure: no
// clock, file or socket; OpenSSL computes the MAC and compares it in constant
// time. The LCM bridge and the command-center page hand their commands to the
// server core, which verifies them here (Server::HandleSigned); the runner,
// `serve --start`, the tests and the benches sign here.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "fireswarm/common/secret_key.hpp"
#include "fireswarm/server/operator_command.hpp"

namespace fireswarm::server {

/// HMAC-SHA256 tag length, bytes.
inline constexpr std::size_t kCommandMacBytes = 32;
using CommandMac = std::array<std::uint8_t, kCommandMacBytes>;
/// The longest operator ID, bytes (IDs name key files: [A-Za-z0-9_.-], 1..64).
inline constexpr std::size_t kMaxOperatorIdBytes = 64;
/// The longest `reason` the encoding carries, bytes (its length is 16 bits).
inline constexpr std::size_t kMaxSignedReasonBytes = 65535;
/// Default acceptance window: a command's utime may differ from the server's
/// clock by at most this, microseconds (MAVLink 2 signing allows one minute).
inline constexpr std::int64_t kDefaultCommandWindowUs = 30'000'000;

/// Who sent a command, when, and the proof (operator_command_t's last fields).
struct CommandCredentials {
  std::string operator_id;  ///< names KEYS/operators/<operator_id>.key
  /// When the operator issued it, microseconds on the server's LCM clock (Unix
  /// epoch for `serve`, simulated for `run`: docs/lcm.md).
  std::int64_t utime = 0;
  /// Unique per operator within the window (random 64 bits, or a counter).
  std::int64_t nonce = 0;
  CommandMac mac{};
};

/// A command with its credentials, as it arrives over LCM or from the page.
struct SignedCommand {
  OperatorCommand command;
  CommandCredentials credentials;
};

/// Why a command was refused (or kAccepted). Counted per value in the server's
/// statistics (radio_stats_t's commands_* fields).
enum class CommandVerdict : std::uint8_t {
  kAccepted = 0,
  kMalformed = 1,        ///< a field out of range, or no credentials at all
  kUnknownOperator = 2,  ///< no key for the operator ID (or no keys loaded)
  kBadMac = 3,           ///< the tag does not match: forged or altered
  kStale = 4,            ///< utime outside the window around the server's clock
  kReplayed = 5,         ///< this operator's nonce was already taken in the window
};
/// "accepted", "malformed", "unknown_operator", "bad_mac", "stale", "replayed".
const char* ToString(CommandVerdict verdict);

/// True when `id` is a valid operator ID: 1..kMaxOperatorIdBytes of [A-Za-z0-9_.-],
/// not starting with '.'.
bool IsValidOperatorId(std::string_view id);

/// The canonical bytes the MAC covers (docs/lcm.md): the ASCII tag
/// "fireswarm-cmd-v1", then, big-endian: u8 operator ID length, its bytes, i64
/// utime, i64 nonce, i8 command, i16 target_vehicle, f64 lat_deg, f64 lon_deg,
/// f64 radius_m (IEEE 754 bits), u16 reason length, its bytes. Precondition:
/// operator_id and reason within their limits (longer ones are truncated, and
/// then the MAC cannot match what was sent).
std::vector<std::uint8_t> CommandMacInput(const OperatorCommand& command,
                                          const CommandCredentials& credentials);

/// HMAC-SHA256 under `key` of CommandMacInput(command, credentials).
CommandMac ComputeCommandMac(const common::SecretKey& key, const OperatorCommand& command,
                             const CommandCredentials& credentials);

/// `command` signed by `operator_id` with `key` at `utime` with `nonce`.
SignedCommand SignCommand(const OperatorCommand& command, const std::string& operator_id,
                          const common::SecretKey& key, std::int64_t utime, std::int64_t nonce);

/// 64 bits from OpenSSL's CSPRNG, for nonces. Throws std::runtime_error if it fails.
std::int64_t RandomNonce();

/// Checks commands: a known operator, a matching MAC, a utime within the window
/// of the server's clock, a nonce not seen from that operator within the window
/// (the nonces of accepted commands are kept until their utime leaves the window,
/// so a replay is refused as replayed inside the window and as stale after it).
class CommandVerifier {
 public:
  /// `operators`: ID -> key. `window_us`: the acceptance window, > 0.
  explicit CommandVerifier(std::map<std::string, common::SecretKey> operators = {},
                           std::int64_t window_us = kDefaultCommandWindowUs);

  /// The verdict on `command` at `now_utime` (the server's clock, microseconds).
  /// Accepted commands' nonces are remembered.
  CommandVerdict Verify(const SignedCommand& command, std::int64_t now_utime);

  /// Remembers that `operator_id` used `nonce` at `utime` (a restored server's
  /// journaled commands), as an accepted command's.
  void Remember(const std::string& operator_id, std::int64_t nonce, std::int64_t utime);
  /// Adds (or replaces) an operator's key.
  void AddOperator(const std::string& operator_id, const common::SecretKey& key);
  std::size_t operator_count() const { return keys_.size(); }
  std::int64_t window_us() const { return window_us_; }
  /// Nonces remembered now (for tests: the cache is pruned as time passes).
  std::size_t remembered() const { return seen_.size(); }

 private:
  void Forget(std::int64_t now_utime);

  std::map<std::string, common::SecretKey> keys_;
  std::int64_t window_us_;
  // (operator, nonce) of accepted commands, and the same by utime for pruning.
  std::set<std::pair<std::string, std::int64_t>> seen_;
  std::multimap<std::int64_t, std::pair<std::string, std::int64_t>> seen_by_utime_;
};

}  // namespace fireswarm::server
