// The server's receive path as a defence: frames outside a granted turn, forged,
// replayed or keyed for another vehicle never become events.
#include <gtest/gtest.h>

#include <vector>

#include "fireswarm/radio/master_scheduler.hpp"
#include "fireswarm/radio/secure_frame.hpp"
#include "radio/secure_link.hpp"
#include "radio/sim_net.hpp"

namespace fireswarm::radio {
namespace {

using secure_test::Disk;
using secure_test::ServerSecurity;
using secure_test::TestKey;
using secure_test::VehicleSecurity;
using sim_test::ServerConfig;
using std::chrono::milliseconds;
using std::chrono::seconds;
using Bytes = std::vector<std::uint8_t>;

FireReport ReportFrom(std::uint8_t vehicle, std::uint16_t report_id) {
  FireReport report;
  report.header = MessageHeader{vehicle, report_id};
  report.report_id = report_id;
  report.lat_deg = 46.5;
  report.lon_deg = 7.5;
  return report;
}

int FireEvents(MasterScheduler& server) {
  int count = 0;
  for (const SchedulerEvent& e : server.TakeEvents()) {
    count += std::holds_alternative<FireReportReceived>(e) ? 1 : 0;
  }
  return count;
}

TEST(SchedulerReceive, EightyForgedFireReportsOutsideAnyTurnNeverBecomeEvents) {
  MasterScheduler server(ServerConfig(LinkMode::kSlots));
  server.AddVehicle(1, 1.0, seconds(10));
  server.AddVehicle(2, 1.0, seconds(10));
  ASSERT_TRUE(server.Step(Nanos{0}, {}).empty()) << "nobody is due: no turn granted";
  for (std::uint16_t i = 0; i < 80; ++i) {
    Bytes forged;
    AppendMessageFrame(forged, kServerId, ReportFrom(static_cast<std::uint8_t>(1 + i % 2), i),
                       ChecksumMode::kCrc16);
    server.Step(milliseconds(100 + i), forged);
  }
  EXPECT_EQ(FireEvents(server), 0);
  EXPECT_EQ(server.stats().out_of_turn, 80U);
  EXPECT_EQ(server.stats().fire_reports, 0U);
}

// Secure mode, inside a granted slot: only the vehicle's own key gets a report in.
class SecureReceive : public ::testing::Test {
 protected:
  SecureReceive() : server_(Config()) {
    server_.AddVehicle(1);
    grant_ = server_.Step(Nanos{0}, {});
  }
  SchedulerConfig Config() {
    SchedulerConfig config = ServerConfig(LinkMode::kSlots);
    config.checksum = ChecksumMode::kSecure;
    config.security = ServerSecurity({1}, server_disk_);
    return config;
  }
  // Feeds `bytes` inside the granted exchange.
  int Deliver(const Bytes& bytes, Nanos at = milliseconds(40)) {
    server_.Step(at, bytes);
    return FireEvents(server_);
  }
  Bytes SealedReport(FrameSecurity& sealer, std::uint8_t sender, std::uint16_t id) {
    Bytes out;
    EXPECT_EQ(
        AppendFrameFor(out, kServerId, ReportFrom(sender, id), ChecksumMode::kSecure, &sealer),
        SealStatus::kOk);
    return out;
  }
  Disk server_disk_, vehicle_disk_, attacker_disk_;
  MasterScheduler server_;
  std::vector<Burst> grant_;
};

TEST_F(SecureReceive, ForgedUnderAnotherKeyIsCountedAsAnAuthenticationFailure) {
  ASSERT_EQ(grant_.size(), 1U);
  FrameSecurityConfig attacker_config;
  attacker_config.self_id = 1;
  FrameSecurity attacker(attacker_config, {}, {});
  attacker.SetKey(1, TestKey(99));
  EXPECT_EQ(Deliver(SealedReport(attacker, 1, 5)), 0);
  EXPECT_EQ(server_.config().security->stats().at(1).auth_failures, 1U);
  EXPECT_EQ(server_.stats().refused_frames, 1U);
}

TEST_F(SecureReceive, PlainFrameIsNotEvenAFrameInSecureMode) {
  Bytes plain;
  AppendMessageFrame(plain, kServerId, ReportFrom(1, 5), ChecksumMode::kCrc16);
  EXPECT_EQ(Deliver(plain), 0);
  EXPECT_EQ(server_.parser_stats().frames, 0U);
}

TEST_F(SecureReceive, GenuineReportIsTakenOnceAndItsReplayRefused) {
  auto vehicle = VehicleSecurity(1, vehicle_disk_);
  const Bytes genuine = SealedReport(*vehicle, 1, 5);
  EXPECT_EQ(Deliver(genuine), 1);
  // The next exchange: the recorded frame again.
  ASSERT_FALSE(server_.Step(seconds(2), {}).empty());
  EXPECT_EQ(Deliver(genuine, seconds(2) + milliseconds(40)), 0);
  EXPECT_EQ(server_.config().security->stats().at(1).replays, 1U);
}

TEST_F(SecureReceive, AVehicleKeyCannotSpeakForAnotherVehicle) {
  server_.AddVehicle(2);
  auto vehicle = VehicleSecurity(1, vehicle_disk_);
  // Vehicle 1's key, vehicle 2's name in the payload.
  EXPECT_EQ(Deliver(SealedReport(*vehicle, 2, 5)), 0);
  EXPECT_EQ(server_.stats().refused_frames, 1U);
}

class SecureLinkModes : public ::testing::TestWithParam<LinkMode> {};

TEST_P(SecureLinkModes, TelemetryAndRequestsFlowEndToEnd) {
  Disk server_disk;
  SchedulerConfig config = ServerConfig(GetParam());
  config.checksum = ChecksumMode::kSecure;
  config.security = ServerSecurity({1, 2, 3}, server_disk);
  sim_test::SimNet net(config, 3);
  for (std::uint8_t id = 1; id <= 3; ++id) net.server().AddVehicle(id);
  net.server().SendCommand(2, Command{{}, CommandType::kReturnToLaunch});
  net.RunUntil(seconds(10));
  EXPECT_GE(net.EventsOf<TelemetryReceived>().size(), 27U);
  const auto finished = net.EventsOf<RequestFinished>();
  ASSERT_EQ(finished.size(), 1U);
  EXPECT_EQ(finished[0].status, RequestStatus::kCompleted);
  EXPECT_EQ(net.vehicle(2).handler.executed, 1);
  EXPECT_EQ(net.server().stats().refused_frames, 0U);
  EXPECT_EQ(net.server().stats().out_of_turn, 0U);
}

INSTANTIATE_TEST_SUITE_P(BothModes, SecureLinkModes,
                         ::testing::Values(LinkMode::kPoll, LinkMode::kSlots));

}  // namespace
}  // namespace fireswarm::radio
