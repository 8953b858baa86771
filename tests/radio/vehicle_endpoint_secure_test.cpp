// The vehicle in secure mode: forged, replayed and plain requests never reach its
// handler (no mission upload, no RTL, no parameter write); the server's do.
#include <gtest/gtest.h>

#include <vector>

#include "fireswarm/radio/vehicle_endpoint.hpp"
#include "radio/secure_link.hpp"
#include "radio/sim_net.hpp"

namespace fireswarm::radio {
namespace {

using secure_test::Disk;
using secure_test::ServerSecurity;
using secure_test::TestKey;
using secure_test::VehicleSecurity;
using std::chrono::milliseconds;
using Bytes = std::vector<std::uint8_t>;

constexpr std::uint8_t kSecureVehicle = 3;

class RecordingHandler final : public VehicleRequestHandler {
 public:
  CommandResult OnCommand(const Command& /*command*/) override {
    ++commands;
    return CommandResult::kAccepted;
  }
  MissionAckStatus OnMissionChunk(const MissionChunk& /*chunk*/) override {
    ++chunks;
    return MissionAckStatus::kAccepted;
  }
  ParamValue OnParamRead(const ParamRead& /*read*/) override { return {}; }
  ParamValue OnParamWrite(const ParamWrite& write) override {
    ++param_writes;
    return ParamValue{{}, 0, write.value, ParamStatus::kOk};
  }
  int commands = 0;
  int chunks = 0;
  int param_writes = 0;
  int total() const { return commands + chunks + param_writes; }
};

std::vector<Message> Requests(std::uint16_t sequence) {
  MissionChunk chunk;
  chunk.header = {kServerId, sequence};
  chunk.mission_id = 9;
  chunk.chunk_count = 1;
  chunk.total_waypoints = 1;
  chunk.waypoint_count = 1;
  return {
      chunk,
      Command{{kServerId, static_cast<std::uint16_t>(sequence + 1)}, CommandType::kReturnToLaunch},
      ParamWrite{{kServerId, static_cast<std::uint16_t>(sequence + 2)}, 1, 99.0F}};
}

class VehicleEndpointSecure : public ::testing::Test {
 protected:
  VehicleEndpointSecure() : endpoint_(Config(), handler_) {}
  VehicleEndpointConfig Config() {
    VehicleEndpointConfig config;
    config.id = kSecureVehicle;
    config.mode = LinkMode::kPoll;
    config.checksum = ChecksumMode::kSecure;
    config.security = VehicleSecurity(kSecureVehicle, vehicle_disk_);
    config.timing = LinkTiming{sim_test::kBaud, kBitsPerByte8N1, sim_test::kTurnaround};
    return config;
  }
  Bytes Sealed(FrameSecurity& sealer, const std::vector<Message>& messages) {
    Bytes out;
    for (const Message& m : messages) {
      EXPECT_EQ(AppendFrameFor(out, kSecureVehicle, m, ChecksumMode::kSecure, &sealer),
                SealStatus::kOk);
    }
    return out;
  }
  std::vector<Burst> Feed(const Bytes& bytes) {
    now_ += milliseconds(100);
    return endpoint_.OnReceive(now_, bytes);
  }
  Disk vehicle_disk_, server_disk_;
  RecordingHandler handler_;
  VehicleEndpoint endpoint_;
  Nanos now_{0};
};

TEST_F(VehicleEndpointSecure, ForgedMissionUploadRtlAndParamWriteAreIgnored) {
  FrameSecurityConfig attacker_config;
  attacker_config.self_id = kServerId;
  FrameSecurity attacker(attacker_config, {}, {});
  attacker.SetKey(kSecureVehicle, TestKey(77));  // a guessed key
  EXPECT_TRUE(Feed(Sealed(attacker, Requests(100))).empty());
  EXPECT_EQ(handler_.total(), 0);
  EXPECT_EQ(endpoint_.config().security->stats().at(kSecureVehicle).auth_failures, 3U);
  EXPECT_EQ(endpoint_.stats().refused_frames, 3U);
}

TEST_F(VehicleEndpointSecure, PlainFramesAreNotFramesInSecureMode) {
  Bytes plain;
  for (const Message& m : Requests(100))
    AppendMessageFrame(plain, kSecureVehicle, m, ChecksumMode::kCrc16);
  EXPECT_TRUE(Feed(plain).empty());
  EXPECT_EQ(handler_.total(), 0);
}

TEST_F(VehicleEndpointSecure, GenuineRequestsRunOnceAndTheirRecordingIsRefusedAlsoAfterRestart) {
  auto server = ServerSecurity({kSecureVehicle}, server_disk_);
  const Bytes recorded = Sealed(*server, Requests(100));
  EXPECT_EQ(Feed(recorded).size(), 1U) << "poll mode: the vehicle answers the last request";
  EXPECT_EQ(handler_.commands, 1);
  EXPECT_EQ(handler_.chunks, 1);
  EXPECT_EQ(handler_.param_writes, 1);
  EXPECT_TRUE(Feed(recorded).empty());
  EXPECT_EQ(endpoint_.config().security->stats().at(kSecureVehicle).replays, 3U);

  // The vehicle restarts: a new endpoint and security restored from its disk.
  RecordingHandler after_restart;
  VehicleEndpoint restarted(Config(), after_restart);
  EXPECT_TRUE(restarted.OnReceive(now_ + milliseconds(500), recorded).empty());
  EXPECT_EQ(after_restart.total(), 0);
  // What the server sends next still gets through.
  restarted.OnReceive(now_ + milliseconds(900), Sealed(*server, Requests(200)));
  EXPECT_EQ(after_restart.total(), 3);
}

TEST_F(VehicleEndpointSecure, ReplyIsSealedAndOpensOnlyAtTheServer) {
  auto server = ServerSecurity({kSecureVehicle}, server_disk_);
  const std::vector<Burst> replies = Feed(Sealed(*server, {Poll{{kServerId, 1}}}));
  ASSERT_EQ(replies.size(), 1U);
  EXPECT_EQ(replies[0].bytes.size(),
            FrameSize(PayloadSize(MessageId::kTelemetry), ChecksumMode::kSecure));
  EXPECT_EQ(secure_test::OpenAll(*server, replies[0].bytes), std::vector{OpenStatus::kOk});
}

}  // namespace
}  // namespace fireswarm::radio
