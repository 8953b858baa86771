// Test helpers for secure mode: deterministic keys, a FrameSecurity per side with
// its state on a simulated disk, and feeding sealed bytes through the real parser.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "fireswarm/radio/frame_security.hpp"
#include "fireswarm/radio/parser.hpp"

namespace fireswarm::radio::secure_test {

inline common::SecretKey TestKey(std::uint8_t fill) {
  common::SecretKey key{};
  for (std::size_t i = 0; i < key.size(); ++i) key[i] = static_cast<std::uint8_t>(fill + i);
  return key;
}
inline constexpr std::uint8_t kBroadcastFill = 0xB0;

/// What a side persisted: survives "restarts" (new FrameSecurity objects).
struct Disk {
  SecurityState state;
  int writes = 0;
  bool fail = false;
};

inline PersistSecurityState PersistTo(Disk& disk) {
  return [&disk](const SecurityState& state) {
    if (disk.fail) return false;
    disk.state = state;
    ++disk.writes;
    return true;
  };
}

/// A vehicle's security (key TestKey(id), broadcast key) restored from `disk`.
inline std::shared_ptr<FrameSecurity> VehicleSecurity(std::uint8_t id, Disk& disk,
                                                      std::uint32_t reserve = 16) {
  FrameSecurityConfig config;
  config.self_id = id;
  config.counter_reserve = reserve;
  config.persist_floor_on = {static_cast<std::uint8_t>(MessageId::kCommand),
                             static_cast<std::uint8_t>(MessageId::kMissionChunk),
                             static_cast<std::uint8_t>(MessageId::kParamWrite)};
  auto security = std::make_shared<FrameSecurity>(config, disk.state, PersistTo(disk));
  security->SetKey(id, TestKey(id));
  security->SetKey(kBroadcastKeyId, TestKey(kBroadcastFill));
  return security;
}

/// The server's security with keys for `vehicles` and the broadcast key.
inline std::shared_ptr<FrameSecurity> ServerSecurity(std::initializer_list<std::uint8_t> vehicles,
                                                     Disk& disk) {
  FrameSecurityConfig config;
  config.self_id = kServerId;
  config.counter_reserve = 16;
  config.persist_floor_on = {static_cast<std::uint8_t>(MessageId::kFireReport)};
  auto security = std::make_shared<FrameSecurity>(config, disk.state, PersistTo(disk));
  for (const std::uint8_t id : vehicles) security->SetKey(id, TestKey(id));
  security->SetKey(kBroadcastKeyId, TestKey(kBroadcastFill));
  return security;
}

/// Every frame in `bytes` opened by `security`: the status of each.
inline std::vector<OpenStatus> OpenAll(
    FrameSecurity& security, std::span<const std::uint8_t> bytes,
    std::vector<std::vector<std::uint8_t>>* plaintexts = nullptr) {
  std::vector<OpenStatus> out;
  FrameParser parser(ChecksumMode::kSecure);
  std::vector<std::uint8_t> plaintext;
  parser.Feed(bytes, [&](const FrameView& frame) {
    out.push_back(security.Open(frame, plaintext));
    if (plaintexts != nullptr) plaintexts->push_back(plaintext);
  });
  parser.Finish();
  return out;
}

}  // namespace fireswarm::radio::secure_test
