// Counter reservation (write "next safe" before using counters up to it), replay
// windows and key choice around the AES-256-GCM codec of secure_frame.cpp.
#include "fireswarm/radio/frame_security.hpp"

#include <algorithm>
#include <utility>

#include "fireswarm/radio/secure_frame.hpp"

namespace fireswarm::radio {
namespace {

constexpr std::uint64_t kCounterLimit = std::uint64_t{1} << 32;  // counters are u32 on the wire

}  // namespace

FrameSecurityConfig ServerSecurityConfig() {
  FrameSecurityConfig config;
  config.self_id = kServerId;
  config.persist_floor_on = {static_cast<std::uint8_t>(MessageId::kFireReport)};
  return config;
}

FrameSecurityConfig VehicleSecurityConfig(std::uint8_t id) {
  FrameSecurityConfig config;
  config.self_id = id;
  config.persist_floor_on = {static_cast<std::uint8_t>(MessageId::kMissionChunk),
                             static_cast<std::uint8_t>(MessageId::kCommand),
                             static_cast<std::uint8_t>(MessageId::kParamWrite)};
  return config;
}

std::string_view ToString(KeyLinkState state) {
  switch (state) {
    case KeyLinkState::kUnheard:
      return "unheard";
    case KeyLinkState::kOk:
      return "ok";
    case KeyLinkState::kAuthFailing:
      return "authentication failing";
    case KeyLinkState::kNoKey:
      return "no key";
  }
  return "unknown";
}

KeyLinkState LinkStateOf(const KeySecurityStats& stats) {
  if (stats.failures_in_a_row >= kFailuresToReport) {
    return stats.no_key > 0 && stats.auth_failures == 0 ? KeyLinkState::kNoKey
                                                        : KeyLinkState::kAuthFailing;
  }
  if (stats.opened > 0) return KeyLinkState::kOk;
  return KeyLinkState::kUnheard;
}

std::string_view ToString(SealStatus status) {
  switch (status) {
    case SealStatus::kOk:
      return "ok";
    case SealStatus::kNoKey:
      return "no_key";
    case SealStatus::kCounterExhausted:
      return "counter_exhausted";
    case SealStatus::kPersistFailed:
      return "persist_failed";
  }
  return "unknown";
}

std::string_view ToString(OpenStatus status) {
  switch (status) {
    case OpenStatus::kOk:
      return "ok";
    case OpenStatus::kNotForMe:
      return "not_for_me";
    case OpenStatus::kNoKey:
      return "no_key";
    case OpenStatus::kReplay:
      return "replay";
    case OpenStatus::kAuthFailed:
      return "auth_failed";
  }
  return "unknown";
}

FrameSecurity::FrameSecurity(const FrameSecurityConfig& config, SecurityState restored,
                             PersistSecurityState persist)
    : config_(config),
      persist_(std::move(persist)),
      persisted_(std::move(restored)),
      // Counters below the restored value may have been used before the restart;
      // the first Seal() reserves a new range before it uses one.
      next_counter_(persisted_.next_counter) {}

void FrameSecurity::SetKey(std::uint8_t key_id, const common::SecretKey& key) {
  const auto found = keys_.find(key_id);
  if (found == keys_.end()) {
    keys_.emplace(key_id, Keys{key, std::nullopt, false});
    return;
  }
  if (found->second.current == key) return;
  found->second.previous = found->second.current;
  found->second.current = key;
  found->second.peer_uses_previous = false;
}

void FrameSecurity::SetPreviousKey(std::uint8_t key_id, const common::SecretKey& key) {
  const auto found = keys_.find(key_id);
  if (found == keys_.end()) return;
  found->second.previous = key;
  // Until the vehicle is heard under its new key, the server speaks under the old one.
  found->second.peer_uses_previous = config_.self_id == kServerId;
}

bool FrameSecurity::Persist(const SecurityState& state) {
  if (persist_ && !persist_(state)) return false;
  persisted_ = state;
  return true;
}

ReplayWindow& FrameSecurity::WindowFor(std::uint8_t key_id) {
  const auto found = windows_.find(key_id);
  if (found != windows_.end()) return found->second;
  const auto floor = persisted_.floors.find(key_id);
  return windows_
      .emplace(key_id, ReplayWindow(floor == persisted_.floors.end() ? 0 : floor->second))
      .first->second;
}

std::uint8_t FrameSecurity::KeyIdOf(const FrameView& frame) {
  return ReadSecureHeader(frame).key_id;
}

SealStatus FrameSecurity::Seal(std::vector<std::uint8_t>& out, std::uint8_t receiver,
                               std::uint8_t message_id, std::span<const std::uint8_t> plaintext) {
  const std::uint8_t key_id = config_.self_id == kServerId
                                  ? (receiver == kBroadcastId ? kBroadcastKeyId : receiver)
                                  : config_.self_id;
  KeySecurityStats& stats = stats_[key_id];
  const auto keys = keys_.find(key_id);
  if (keys == keys_.end()) {
    ++stats.no_key;
    return SealStatus::kNoKey;
  }
  if (next_counter_ >= kCounterLimit) return SealStatus::kCounterExhausted;
  if (next_counter_ >= persisted_.next_counter) {
    // Reserve the next range durably before using any counter in it.
    SecurityState state = persisted_;
    state.next_counter = std::min(kCounterLimit, next_counter_ + config_.counter_reserve);
    if (!Persist(state)) return SealStatus::kPersistFailed;
  }
  const Keys& k = keys->second;
  const common::SecretKey& key = k.peer_uses_previous && k.previous ? *k.previous : k.current;
  AppendSecureFrame(out, receiver, message_id, plaintext,
                    SecureHeader{key_id, static_cast<std::uint32_t>(next_counter_)}, key);
  ++next_counter_;
  ++stats.sealed;
  return SealStatus::kOk;
}

OpenStatus FrameSecurity::Open(const FrameView& frame, std::vector<std::uint8_t>& plaintext) {
  plaintext.clear();
  const SecureHeader header = ReadSecureHeader(frame);
  // The server takes frames to itself under a vehicle key; a vehicle takes frames to
  // itself under its own key and broadcasts under the broadcast key. Anything else
  // was sealed for another side (or by this side) and is not ours to count.
  const bool for_me =
      config_.self_id == kServerId
          ? frame.receiver == kServerId && header.key_id >= kFirstVehicleId &&
                header.key_id <= kLastVehicleId
          : (frame.receiver == config_.self_id && header.key_id == config_.self_id) ||
                (frame.receiver == kBroadcastId && header.key_id == kBroadcastKeyId);
  if (!for_me) return OpenStatus::kNotForMe;
  KeySecurityStats& stats = stats_[header.key_id];
  const auto keys = keys_.find(header.key_id);
  if (keys == keys_.end()) {
    ++stats.no_key;
    ++stats.failures_in_a_row;
    return OpenStatus::kNoKey;
  }
  ReplayWindow& window = WindowFor(header.key_id);
  if (!window.IsFresh(header.counter)) {
    ++stats.replays;
    return OpenStatus::kReplay;
  }
  Keys& k = keys->second;
  bool under_previous = false;
  if (!OpenSecureFrame(frame, k.current, plaintext)) {
    under_previous = k.previous && OpenSecureFrame(frame, *k.previous, plaintext);
    if (!under_previous) {
      ++stats.auth_failures;
      ++stats.failures_in_a_row;
      return OpenStatus::kAuthFailed;
    }
    ++stats.previous_key_used;
  }
  // Only an authentic frame moves the window, so forgeries cannot push it ahead.
  window.Mark(header.counter);
  k.peer_uses_previous = under_previous;
  ++stats.opened;
  stats.failures_in_a_row = 0;
  const bool persist_floor =
      std::find(config_.persist_floor_on.begin(), config_.persist_floor_on.end(),
                frame.message_id) != config_.persist_floor_on.end();
  if (persist_floor) {
    SecurityState state = persisted_;
    state.floors[header.key_id] = window.NextFloor();
    // A failed write leaves the old floor: the frame is still taken (refusing it
    // would turn a full disk into a lost link), and the next one retries.
    Persist(state);
  }
  return OpenStatus::kOk;
}

SealStatus AppendFrameFor(std::vector<std::uint8_t>& out, std::uint8_t receiver,
                          const Message& message, ChecksumMode mode, FrameSecurity* security) {
  if (mode != ChecksumMode::kSecure) {
    AppendMessageFrame(out, receiver, message, mode);
    return SealStatus::kOk;
  }
  if (security == nullptr) return SealStatus::kNoKey;
  std::vector<std::uint8_t> payload;
  payload.reserve(kMaxDataSize);
  EncodePayload(message, payload);
  return security->Seal(out, receiver, static_cast<std::uint8_t>(IdOf(message)), payload);
}

OpenedData OpenFrameData(const FrameView& frame, ChecksumMode mode, FrameSecurity* security,
                         std::vector<std::uint8_t>& scratch) {
  if (mode != ChecksumMode::kSecure) return {OpenStatus::kOk, frame.data};
  if (security == nullptr) return {OpenStatus::kNoKey, {}};
  const OpenStatus status = security->Open(frame, scratch);
  if (status != OpenStatus::kOk) return {status, {}};
  return {status, scratch};
}

}  // namespace fireswarm::radio
