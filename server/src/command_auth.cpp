// Operator command MACs and their checks (command_auth.hpp; docs/lcm.md gives
// the byte encoding the page's JS reproduces).
#include "fireswarm/server/command_auth.hpp"

#include <openssl/crypto.h>
#include <openssl/evp.h>
#include <openssl/hmac.h>
#include <openssl/rand.h>

#include <algorithm>
#include <bit>
#include <stdexcept>

namespace fireswarm::server {

namespace {

constexpr std::string_view kMacDomainTag = "fireswarm-cmd-v1";

// Appends `value`'s `bytes` low bytes, most significant first.
void PutBigEndian(std::vector<std::uint8_t>& out, std::uint64_t value, int bytes) {
  for (int shift = 8 * (bytes - 1); shift >= 0; shift -= 8) {
    out.push_back(static_cast<std::uint8_t>(value >> shift));
  }
}

void PutText(std::vector<std::uint8_t>& out, std::string_view text, std::size_t max_bytes,
             int length_bytes) {
  const std::size_t size = std::min(text.size(), max_bytes);
  PutBigEndian(out, size, length_bytes);
  out.insert(out.end(), text.begin(), text.begin() + static_cast<std::ptrdiff_t>(size));
}

void PutDouble(std::vector<std::uint8_t>& out, double value) {
  PutBigEndian(out, std::bit_cast<std::uint64_t>(value), 8);
}

}  // namespace

const char* ToString(CommandVerdict verdict) {
  switch (verdict) {
    case CommandVerdict::kAccepted:
      return "accepted";
    case CommandVerdict::kMalformed:
      return "malformed";
    case CommandVerdict::kUnknownOperator:
      return "unknown_operator";
    case CommandVerdict::kBadMac:
      return "bad_mac";
    case CommandVerdict::kStale:
      return "stale";
    case CommandVerdict::kReplayed:
      return "replayed";
  }
  return "unknown";
}

bool IsValidOperatorId(std::string_view id) {
  if (id.empty() || id.size() > kMaxOperatorIdBytes || id.front() == '.') return false;
  return std::all_of(id.begin(), id.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' ||
           c == '.' || c == '-';
  });
}

std::vector<std::uint8_t> CommandMacInput(const OperatorCommand& command,
                                          const CommandCredentials& credentials) {
  std::vector<std::uint8_t> out(kMacDomainTag.begin(), kMacDomainTag.end());
  out.reserve(out.size() + 1 + credentials.operator_id.size() + 8 + 8 + 1 + 2 + 3 * 8 + 2 +
              command.reason.size());
  PutText(out, credentials.operator_id, kMaxOperatorIdBytes, 1);
  PutBigEndian(out, static_cast<std::uint64_t>(credentials.utime), 8);
  PutBigEndian(out, static_cast<std::uint64_t>(credentials.nonce), 8);
  PutBigEndian(out, static_cast<std::uint8_t>(command.kind), 1);
  PutBigEndian(out, command.vehicle, 2);  // operator_command_t's int16 target_vehicle, 0..254
  PutDouble(out, command.point.lat_deg);
  PutDouble(out, command.point.lon_deg);
  PutDouble(out, command.radius_m);
  PutText(out, command.reason, kMaxSignedReasonBytes, 2);
  return out;
}

CommandMac ComputeCommandMac(const common::SecretKey& key, const OperatorCommand& command,
                             const CommandCredentials& credentials) {
  const std::vector<std::uint8_t> input = CommandMacInput(command, credentials);
  CommandMac mac{};
  unsigned int size = 0;
  HMAC(EVP_sha256(), key.data(), static_cast<int>(key.size()), input.data(), input.size(),
       mac.data(), &size);
  return mac;
}

SignedCommand SignCommand(const OperatorCommand& command, const std::string& operator_id,
                          const common::SecretKey& key, std::int64_t utime, std::int64_t nonce) {
  SignedCommand signed_command{command, {operator_id, utime, nonce, {}}};
  signed_command.credentials.mac = ComputeCommandMac(key, command, signed_command.credentials);
  return signed_command;
}

std::int64_t RandomNonce() {
  std::array<unsigned char, 8> bytes{};
  if (RAND_bytes(bytes.data(), static_cast<int>(bytes.size())) != 1) {
    throw std::runtime_error("OpenSSL RAND_bytes failed to make a command nonce");
  }
  return std::bit_cast<std::int64_t>(bytes);
}

CommandVerifier::CommandVerifier(std::map<std::string, common::SecretKey> operators,
                                 std::int64_t window_us)
    : keys_(std::move(operators)), window_us_(window_us) {
  if (window_us_ <= 0) throw std::invalid_argument("command window: must be > 0 us");
}

void CommandVerifier::AddOperator(const std::string& operator_id, const common::SecretKey& key) {
  keys_[operator_id] = key;
}

void CommandVerifier::Remember(const std::string& operator_id, std::int64_t nonce,
                               std::int64_t utime) {
  if (seen_.emplace(operator_id, nonce).second) {
    seen_by_utime_.emplace(utime, std::pair{operator_id, nonce});
  }
}

void CommandVerifier::Forget(std::int64_t now_utime) {
  // A remembered nonce whose utime left the window: its command would be stale now.
  const auto end = seen_by_utime_.lower_bound(now_utime - window_us_);
  for (auto it = seen_by_utime_.begin(); it != end; ++it) seen_.erase(it->second);
  seen_by_utime_.erase(seen_by_utime_.begin(), end);
}

CommandVerdict CommandVerifier::Verify(const SignedCommand& command, std::int64_t now_utime) {
  const CommandCredentials& credentials = command.credentials;
  if (!IsValidOperatorId(credentials.operator_id) ||
      command.command.reason.size() > kMaxSignedReasonBytes) {
    return CommandVerdict::kMalformed;
  }
  const auto key = keys_.find(credentials.operator_id);
  if (key == keys_.end()) return CommandVerdict::kUnknownOperator;
  const CommandMac expected = ComputeCommandMac(key->second, command.command, credentials);
  if (CRYPTO_memcmp(expected.data(), credentials.mac.data(), expected.size()) != 0) {
    return CommandVerdict::kBadMac;
  }
  // A utime so far off that the difference overflows is stale too.
  std::int64_t age_us = 0;
  if (__builtin_sub_overflow(now_utime, credentials.utime, &age_us) || age_us > window_us_ ||
      age_us < -window_us_) {
    return CommandVerdict::kStale;
  }
  Forget(now_utime);
  const std::pair<std::string, std::int64_t> seen{credentials.operator_id, credentials.nonce};
  if (!seen_.insert(seen).second) return CommandVerdict::kReplayed;
  seen_by_utime_.emplace(credentials.utime, seen);
  return CommandVerdict::kAccepted;
}

}  // namespace fireswarm::server
