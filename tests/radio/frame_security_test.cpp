#include "fireswarm/radio/frame_security.hpp"

#include <gtest/gtest.h>

#include <random>
#include <set>
#include <tuple>

#include "fireswarm/radio/secure_frame.hpp"
#include "radio/secure_link.hpp"

namespace fireswarm::radio {
namespace {

using Bytes = std::vector<std::uint8_t>;
using secure_test::Disk;
using secure_test::OpenAll;
using secure_test::ServerSecurity;
using secure_test::TestKey;
using secure_test::VehicleSecurity;

constexpr std::uint8_t kVehicle = 3;

Bytes Sealed(FrameSecurity& security, std::uint8_t receiver, const Message& message) {
  Bytes out;
  EXPECT_EQ(AppendFrameFor(out, receiver, message, ChecksumMode::kSecure, &security),
            SealStatus::kOk);
  return out;
}

const Message kRtl = Command{{kServerId, 1}, CommandType::kReturnToLaunch, {}};

TEST(FrameSecurity, VehicleOpensWhatTheServerSealedOnceAndRefusesTheReplay) {
  Disk server_disk, vehicle_disk;
  auto server = ServerSecurity({kVehicle}, server_disk);
  auto vehicle = VehicleSecurity(kVehicle, vehicle_disk);
  const Bytes frame = Sealed(*server, kVehicle, kRtl);
  std::vector<Bytes> plaintexts;
  EXPECT_EQ(OpenAll(*vehicle, frame, &plaintexts), std::vector{OpenStatus::kOk});
  Bytes expected;
  EncodePayload(kRtl, expected);
  EXPECT_EQ(plaintexts.at(0), expected);
  EXPECT_EQ(OpenAll(*vehicle, frame), std::vector{OpenStatus::kReplay});
  EXPECT_EQ(vehicle->stats().at(kVehicle).replays, 1U);
  EXPECT_EQ(vehicle->stats().at(kVehicle).opened, 1U);
}

TEST(FrameSecurity, WrongKeyIsCountedAsAnAuthenticationFailure) {
  Disk server_disk, vehicle_disk;
  auto server = ServerSecurity({}, server_disk);
  server->SetKey(kVehicle, TestKey(99));  // not the vehicle's key
  auto vehicle = VehicleSecurity(kVehicle, vehicle_disk);
  const Bytes frame = Sealed(*server, kVehicle, kRtl);
  EXPECT_EQ(OpenAll(*vehicle, frame), std::vector{OpenStatus::kAuthFailed});
  EXPECT_EQ(vehicle->stats().at(kVehicle).auth_failures, 1U);
  // The forgery did not move the window: the genuine frame with that counter still opens.
  server->SetKey(kVehicle, TestKey(kVehicle));
  Disk fresh_disk;
  auto honest = ServerSecurity({kVehicle}, fresh_disk);
  EXPECT_EQ(OpenAll(*vehicle, Sealed(*honest, kVehicle, kRtl)), std::vector{OpenStatus::kOk});
}

TEST(FrameSecurity, MissingKeyIsReportedOnBothSides) {
  Disk server_disk, vehicle_disk;
  auto server = ServerSecurity({}, server_disk);
  Bytes out;
  EXPECT_EQ(AppendFrameFor(out, kVehicle, kRtl, ChecksumMode::kSecure, server.get()),
            SealStatus::kNoKey);
  EXPECT_TRUE(out.empty());
  auto vehicle = VehicleSecurity(kVehicle, vehicle_disk);
  const Bytes telemetry = Sealed(*vehicle, kServerId, Telemetry{{kVehicle, 0}});
  EXPECT_EQ(OpenAll(*server, telemetry), std::vector{OpenStatus::kNoKey});
  EXPECT_EQ(server->stats().at(kVehicle).no_key, 2U);  // the seal above and this open
}

TEST(FrameSecurity, FramesForAnotherVehicleOrKeyedForItAreNotMine) {
  Disk server_disk, vehicle_disk;
  auto server = ServerSecurity({kVehicle, 4}, server_disk);
  auto vehicle = VehicleSecurity(kVehicle, vehicle_disk);
  EXPECT_EQ(OpenAll(*vehicle, Sealed(*server, 4, kRtl)), std::vector{OpenStatus::kNotForMe});
  // The vehicle's own frame reflected back at it.
  EXPECT_EQ(OpenAll(*vehicle, Sealed(*vehicle, kServerId, Telemetry{{kVehicle, 0}})),
            std::vector{OpenStatus::kNotForMe});
}

// Seals `count` frames, returning their nonces (key ID, direction, counter).
using Nonce = std::tuple<std::uint8_t, bool, std::uint32_t>;
void SealMany(FrameSecurity& security, std::uint8_t receiver, int count, std::set<Nonce>& nonces,
              int& reused) {
  for (int i = 0; i < count; ++i) {
    Bytes out;
    ASSERT_EQ(
        AppendFrameFor(out, receiver, Telemetry{{kVehicle, 0}}, ChecksumMode::kSecure, &security),
        SealStatus::kOk);
    FrameParser parser(ChecksumMode::kSecure);
    parser.Feed(out, [&](const FrameView& frame) {
      const SecureHeader header = ReadSecureHeader(frame);
      if (!nonces.emplace(header.key_id, frame.receiver == kServerId, header.counter).second) {
        ++reused;
      }
    });
  }
}

TEST(FrameSecurity, CounterPersistenceAcrossRestartsNeverReusesANonce) {
  Disk disk;
  std::set<Nonce> nonces;
  int reused = 0;
  // Restart after every few frames, at every position within a reserved range of 16.
  for (int life = 0; life < 40; ++life) {
    auto vehicle = VehicleSecurity(kVehicle, disk, 16);
    SealMany(*vehicle, kServerId, life % 23, nonces, reused);
    EXPECT_GE(disk.state.next_counter, vehicle->next_counter())
        << "a counter in use must be covered by the persisted reservation";
  }
  EXPECT_EQ(reused, 0);
  EXPECT_GT(nonces.size(), 300U);
  EXPECT_LT(disk.writes, 100) << "one write per reserved range, not per frame";
}

TEST(FrameSecurity, FrameIsNotSentWhenItsReservationCannotBePersisted) {
  Disk disk;
  disk.fail = true;
  auto vehicle = VehicleSecurity(kVehicle, disk);
  Bytes out;
  EXPECT_EQ(AppendFrameFor(out, kServerId, Telemetry{{kVehicle, 0}}, ChecksumMode::kSecure,
                           vehicle.get()),
            SealStatus::kPersistFailed);
  EXPECT_TRUE(out.empty());
}

TEST(FrameSecurity, RecordedRequestIsRefusedAfterTheVehicleRestarts) {
  Disk server_disk, vehicle_disk;
  auto server = ServerSecurity({kVehicle}, server_disk);
  const Bytes recorded = Sealed(*server, kVehicle, kRtl);
  {
    auto vehicle = VehicleSecurity(kVehicle, vehicle_disk);
    ASSERT_EQ(OpenAll(*vehicle, recorded), std::vector{OpenStatus::kOk});
  }
  auto restarted = VehicleSecurity(kVehicle, vehicle_disk);
  EXPECT_EQ(OpenAll(*restarted, recorded), std::vector{OpenStatus::kReplay});
  // The server's next frame still opens.
  EXPECT_EQ(OpenAll(*restarted, Sealed(*server, kVehicle, kRtl)), std::vector{OpenStatus::kOk});
}

TEST(FrameSecurity, RotatedKeyIsTakenWhileThePreviousStillWorksUntilTheVehicleSwitches) {
  Disk server_disk, old_disk;
  auto server = ServerSecurity({kVehicle}, server_disk);
  server->SetKey(kVehicle, TestKey(200));  // rotation: the old key becomes the previous one
  auto old_vehicle = VehicleSecurity(kVehicle, old_disk);
  // A vehicle still on the old key is heard, and answered under the old key.
  EXPECT_EQ(OpenAll(*server, Sealed(*old_vehicle, kServerId, Telemetry{{kVehicle, 0}})),
            std::vector{OpenStatus::kOk});
  EXPECT_EQ(server->stats().at(kVehicle).previous_key_used, 1U);
  EXPECT_EQ(OpenAll(*old_vehicle, Sealed(*server, kVehicle, kRtl)), std::vector{OpenStatus::kOk});
  // Re-provisioned with the new key, it is heard under it and the server switches.
  old_vehicle->SetKey(kVehicle, TestKey(200));
  EXPECT_EQ(OpenAll(*server, Sealed(*old_vehicle, kServerId, Telemetry{{kVehicle, 0}})),
            std::vector{OpenStatus::kOk});
  Disk probe_disk;
  FrameSecurityConfig probe_config;
  probe_config.self_id = kVehicle;
  FrameSecurity new_key_only(probe_config, {}, {});
  new_key_only.SetKey(kVehicle, TestKey(200));
  EXPECT_EQ(OpenAll(new_key_only, Sealed(*server, kVehicle, kRtl)), std::vector{OpenStatus::kOk});
  // A vehicle that only has the old key no longer gets through to a server without it.
  Disk dropped_disk;
  auto no_previous = ServerSecurity({}, dropped_disk);
  no_previous->SetKey(kVehicle, TestKey(200));
  auto stale = VehicleSecurity(kVehicle, probe_disk);
  EXPECT_EQ(OpenAll(*no_previous, Sealed(*stale, kServerId, Telemetry{{kVehicle, 0}})),
            std::vector{OpenStatus::kAuthFailed});
}

// >= 10^5 frames an attacker can make without the key: forged under a guessed key,
// replayed, truncated, bit-flipped (CRC fixed up so they reach authentication).
TEST(FrameSecurity, NoneOfOneHundredThousandForgedReplayedTruncatedOrFlippedFramesIsAccepted) {
  Disk server_disk, vehicle_disk;
  auto server = ServerSecurity({kVehicle}, server_disk);
  auto vehicle = VehicleSecurity(kVehicle, vehicle_disk);
  std::vector<Bytes> genuine;
  for (int i = 0; i < 64; ++i) genuine.push_back(Sealed(*server, kVehicle, kRtl));
  Bytes all;
  for (const Bytes& g : genuine) all.insert(all.end(), g.begin(), g.end());
  ASSERT_EQ(OpenAll(*vehicle, all), std::vector<OpenStatus>(64, OpenStatus::kOk));

  std::mt19937 random(17);
  constexpr int kAttempts = 100'000;
  int accepted = 0;
  int reached = 0;  // attempts that got past the parser to authentication
  const auto fix_crc = [](Bytes& frame) {
    const std::uint16_t crc = Crc16(std::span(frame).subspan(3, frame.size() - 5));
    frame[frame.size() - 2] = static_cast<std::uint8_t>(crc & 0xFF);
    frame[frame.size() - 1] = static_cast<std::uint8_t>(crc >> 8);
  };
  for (int i = 0; i < kAttempts; ++i) {
    Bytes frame = genuine[random() % genuine.size()];
    switch (i % 4) {
      case 0: {  // forged under a guessed key, a fresh counter
        Bytes forged;
        common::SecretKey guess{};
        for (auto& b : guess) b = static_cast<std::uint8_t>(random());
        AppendSecureFrame(forged, kVehicle, static_cast<std::uint8_t>(MessageId::kCommand),
                          Bytes(frame.begin() + 11, frame.end() - 10),
                          SecureHeader{kVehicle, 1'000'000U + static_cast<std::uint32_t>(i)},
                          guess);
        frame = forged;
        break;
      }
      case 1:  // replayed as recorded
        break;
      case 2: {  // truncated: a length byte that claims less, CRC recomputed
        frame.erase(frame.end() - 3);
        frame[5] = static_cast<std::uint8_t>(frame[5] - 1);
        fix_crc(frame);
        break;
      }
      case 3: {  // one bit flipped in receiver..tag (not the length), CRC recomputed
        const std::size_t at = 3 + random() % (frame.size() - 5);
        if (at == 5) break;
        frame[at] ^= static_cast<std::uint8_t>(1U << (random() % 8));
        fix_crc(frame);
        break;
      }
    }
    for (const OpenStatus status : OpenAll(*vehicle, frame)) {
      ++reached;
      if (status == OpenStatus::kOk) ++accepted;
    }
  }
  EXPECT_EQ(accepted, 0);
  EXPECT_GT(reached, kAttempts * 9 / 10);
}

TEST(FrameSecurity, AVehicleOnTheWrongKeyIsReportedAsAuthenticationFailingNotSilent) {
  Disk server_disk, vehicle_disk;
  auto server = ServerSecurity({kVehicle}, server_disk);
  FrameSecurityConfig config = VehicleSecurityConfig(kVehicle);
  FrameSecurity wrong(config, {}, {});
  wrong.SetKey(kVehicle, TestKey(99));
  auto right = VehicleSecurity(kVehicle, vehicle_disk);
  EXPECT_EQ(LinkStateOf(KeySecurityStats{}), KeyLinkState::kUnheard);
  for (int i = 0; i < 3; ++i) OpenAll(*server, Sealed(wrong, kServerId, Telemetry{{kVehicle, 0}}));
  EXPECT_EQ(LinkStateOf(server->stats().at(kVehicle)), KeyLinkState::kAuthFailing);
  EXPECT_EQ(ToString(KeyLinkState::kAuthFailing), "authentication failing");
  OpenAll(*server, Sealed(*right, kServerId, Telemetry{{kVehicle, 0}}));
  EXPECT_EQ(LinkStateOf(server->stats().at(kVehicle)), KeyLinkState::kOk);
}

}  // namespace
}  // namespace fireswarm::radio
