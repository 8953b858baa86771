#include "fireswarm/radio/vehicle_endpoint.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include "fireswarm/radio/parser.hpp"
#include "radio/sim_net.hpp"

namespace fireswarm::radio {
namespace {

using std::chrono::milliseconds;

constexpr std::uint8_t kMe = 3;
constexpr std::uint8_t kOther = 4;
constexpr ChecksumMode kMode = ChecksumMode::kCrc16;
using sim_test::kBaud;
using sim_test::kTurnaround;
constexpr Nanos kNow = milliseconds(1'000);

class CountingHandler final : public VehicleRequestHandler {
 public:
  CommandResult OnCommand(const Command& /*command*/) override {
    ++commands;
    return CommandResult::kAccepted;
  }
  MissionAckStatus OnMissionChunk(const MissionChunk& /*chunk*/) override {
    ++chunks;
    return MissionAckStatus::kAccepted;
  }
  ParamValue OnParamRead(const ParamRead& /*read*/) override {
    return ParamValue{{}, 0, kValue, ParamStatus::kOk};
  }
  ParamValue OnParamWrite(const ParamWrite& write) override {
    return ParamValue{{}, 0, write.value, ParamStatus::kOk};
  }
  static constexpr float kValue = 0.25F;
  int commands = 0;
  int chunks = 0;
};

VehicleEndpointConfig Config(LinkMode mode) {
  VehicleEndpointConfig config;
  config.id = kMe;
  config.mode = mode;
  config.checksum = kMode;
  config.timing = LinkTiming{kBaud, kBitsPerByte8N1, kTurnaround};
  return config;
}

// Server frames as they come off the air.
std::vector<std::uint8_t> Frames(std::initializer_list<std::pair<std::uint8_t, Message>> frames) {
  std::vector<std::uint8_t> bytes;
  for (const auto& [receiver, message] : frames)
    AppendMessageFrame(bytes, receiver, message, kMode);
  return bytes;
}

// Messages in a burst, decoded with the real parser; fails on anything not to the server.
std::vector<Message> Decode(const Burst& burst) {
  std::vector<Message> out;
  FrameParser parser(kMode);
  parser.Feed(burst.bytes, [&](const FrameView& frame) {
    EXPECT_EQ(frame.receiver, kServerId);
    out.push_back(*DecodePayload(frame.message_id, frame.data).message);
  });
  return out;
}

Message Only(const std::vector<Burst>& bursts) {
  EXPECT_EQ(bursts.size(), 1U);
  const std::vector<Message> messages = Decode(bursts.at(0));
  EXPECT_EQ(messages.size(), 1U);
  return messages.at(0);
}

Poll PollFor(ReplyKind kind, std::uint16_t sequence = 1) {
  return Poll{{kServerId, sequence}, kind};
}

std::size_t TelemetryFrameBytes() {
  return MessageFrameSize(MessageId::kTelemetry, kMode);
}

class VehicleEndpointTest : public ::testing::Test {
 protected:
  CountingHandler handler_;
  VehicleEndpoint endpoint_{Config(LinkMode::kPoll), handler_};
};

TEST_F(VehicleEndpointTest, AnswersOnlyItsOwnPollOneTurnaroundAfterIt) {
  EXPECT_TRUE(
      endpoint_.OnReceive(kNow, Frames({{kOther, PollFor(ReplyKind::kTelemetry)}})).empty());
  EXPECT_TRUE(
      endpoint_.OnReceive(kNow, Frames({{kBroadcastId, PollFor(ReplyKind::kTelemetry)}})).empty());

  const auto bursts = endpoint_.OnReceive(kNow, Frames({{kMe, PollFor(ReplyKind::kTelemetry)}}));
  ASSERT_EQ(bursts.size(), 1U);
  EXPECT_EQ(bursts[0].start, kNow + kTurnaround);
  const auto telemetry = std::get<Telemetry>(Only(bursts));
  EXPECT_EQ(telemetry.header.sender, kMe);
  EXPECT_EQ(endpoint_.stats().replies_sent, 1U);
  EXPECT_EQ(endpoint_.stats().frames_for_me, 1U);
}

TEST_F(VehicleEndpointTest, NeverTransmitsUnprompted) {
  endpoint_.QueueFireReport(FireReport{});
  endpoint_.SetTelemetry(Telemetry{});
  std::vector<std::uint8_t> noise = Frames({
      {kOther, Command{{kServerId, 9}, CommandType::kLand}},
      {kServerId, Telemetry{{kOther, 4}}},
      {kMe, FireReportAck{{kServerId, 5}, kMe, 99}},  // an ack for no queued report
      {kMe, Telemetry{}},                             // not a turn
  });
  noise.insert(noise.end(), {0x70, 0x96, 0xAC, kMe, 0x01});  // truncated poll
  for (int i = 0; i < 3; ++i) {
    EXPECT_TRUE(endpoint_.OnReceive(kNow + milliseconds(i), noise).empty());
  }
  EXPECT_EQ(endpoint_.stats().replies_sent, 0U);
  EXPECT_EQ(endpoint_.pending_reports(), 1U);
}

TEST_F(VehicleEndpointTest, PollHeldBackByTheParserIsNotAnsweredLate) {
  // A header with a corrupted length (40) swallows the Poll behind it: the parser
  // waits for 40 data bytes before it can reject the candidate and find the Poll.
  std::vector<std::uint8_t> bytes{0x70, 0x96, 0xAC, kMe, 0x01, 40};
  const auto poll = Frames({{kMe, PollFor(ReplyKind::kTelemetry)}});
  bytes.insert(bytes.end(), poll.begin(), poll.end());
  EXPECT_TRUE(endpoint_.OnReceive(kNow, bytes).empty());
  // The Poll surfaces a second later, when its turn is long over: no reply.
  const std::vector<std::uint8_t> filler(40, 0x00);
  EXPECT_TRUE(endpoint_.OnReceive(2 * kNow, filler).empty());
  EXPECT_EQ(endpoint_.stats().turns_skipped, 1U);
  EXPECT_EQ(endpoint_.stats().replies_sent, 0U);
  // The next Poll is answered as usual.
  EXPECT_EQ(endpoint_.OnReceive(3 * kNow, poll).size(), 1U);
}

TEST_F(VehicleEndpointTest, OwnSequenceNumbersCountFramesSent) {
  for (std::uint16_t expected = 0; expected < 3; ++expected) {
    const auto bursts =
        endpoint_.OnReceive(kNow * (expected + 1), Frames({{kMe, PollFor(ReplyKind::kTelemetry)}}));
    EXPECT_EQ(HeaderOf(Only(bursts)).sequence, expected);
  }
}

TEST_F(VehicleEndpointTest, ReportIsResentWithItsIdUntilAcknowledged) {
  const std::uint16_t id = endpoint_.QueueFireReport(FireReport{});
  const auto poll_report = Frames({{kMe, PollFor(ReplyKind::kFireReport)}});

  const auto first = std::get<FireReport>(Only(endpoint_.OnReceive(kNow, poll_report)));
  // No ack (lost): the next report turn carries the same report, a new sequence.
  const auto again = std::get<FireReport>(Only(endpoint_.OnReceive(2 * kNow, poll_report)));
  EXPECT_EQ(first.report_id, id);
  EXPECT_EQ(again.report_id, id);
  EXPECT_NE(first.header.sequence, again.header.sequence);

  const auto flagged = std::get<Telemetry>(
      Only(endpoint_.OnReceive(3 * kNow, Frames({{kMe, PollFor(ReplyKind::kTelemetry)}}))));
  EXPECT_EQ(flagged.pending_reports, 1);
  EXPECT_NE(flagged.flags & telemetry_flags::kReportPending, 0);

  // The ack at the head of the burst clears the queue before the turn is answered:
  // the report turn then gets telemetry saying nothing is pending.
  const auto after_ack =
      Only(endpoint_.OnReceive(4 * kNow, Frames({{kMe, FireReportAck{{kServerId, 7}, kMe, id}},
                                                 {kMe, PollFor(ReplyKind::kFireReport)}})));
  const auto& telemetry = std::get<Telemetry>(after_ack);
  EXPECT_EQ(telemetry.pending_reports, 0);
  EXPECT_EQ(telemetry.flags & telemetry_flags::kReportPending, 0);
  EXPECT_EQ(endpoint_.stats().reports_acked, 1U);
  EXPECT_EQ(endpoint_.pending_reports(), 0U);
}

TEST_F(VehicleEndpointTest, RetriedRequestIsAnsweredFromCacheNotExecutedAgain) {
  const Command land{{kServerId, 42}, CommandType::kLand};
  const auto first = Only(endpoint_.OnReceive(kNow, Frames({{kMe, land}})));
  const auto retry = Only(endpoint_.OnReceive(2 * kNow, Frames({{kMe, land}})));
  EXPECT_EQ(handler_.commands, 1);
  EXPECT_EQ(std::get<CommandAck>(first).acked_sequence, 42);
  EXPECT_EQ(std::get<CommandAck>(retry).acked_sequence, 42);
  EXPECT_EQ(endpoint_.stats().duplicate_requests, 1U);

  Command next = land;
  next.header.sequence = 43;
  EXPECT_EQ(std::get<CommandAck>(Only(endpoint_.OnReceive(3 * kNow, Frames({{kMe, next}}))))
                .acked_sequence,
            43);
  EXPECT_EQ(handler_.commands, 2);
}

// A vehicle's reboot (agents::NonVolatileStore): a new endpoint restored from the
// old one's state goes on with its report IDs and sequence numbers, re-sends the
// reports not acknowledged with their IDs, and answers a retry of the last
// request from the restored ack instead of executing it again.
TEST_F(VehicleEndpointTest, RestoredStateKeepsCountersReportsAndTheLastRequest) {
  const std::uint16_t first = endpoint_.QueueFireReport(FireReport{});
  const std::uint16_t second = endpoint_.QueueFireReport(FireReport{});
  const Command land{{kServerId, 42}, CommandType::kLand};
  const auto acked = Frames({{kMe, FireReportAck{{kServerId, 7}, kMe, first}}, {kMe, land}});
  const std::uint64_t changes = endpoint_.state_changes();
  const std::uint16_t ack_sequence = HeaderOf(Only(endpoint_.OnReceive(kNow, acked))).sequence;
  EXPECT_GT(endpoint_.state_changes(), changes);

  CountingHandler handler;
  VehicleEndpoint rebooted(Config(LinkMode::kPoll), handler);
  rebooted.Restore(endpoint_.state());
  ASSERT_EQ(rebooted.pending_reports(), 1U);
  EXPECT_EQ(rebooted.QueueFireReport(FireReport{}), second + 1);
  const auto resent =
      Only(rebooted.OnReceive(2 * kNow, Frames({{kMe, PollFor(ReplyKind::kFireReport)}})));
  EXPECT_EQ(std::get<FireReport>(resent).report_id, second);
  EXPECT_EQ(HeaderOf(resent).sequence, ack_sequence + 1);
  const auto retry = Only(rebooted.OnReceive(3 * kNow, Frames({{kMe, land}})));
  EXPECT_EQ(std::get<CommandAck>(retry).acked_sequence, 42);
  EXPECT_EQ(handler.commands, 0);
}

TEST_F(VehicleEndpointTest, ParamReadIsAnsweredWithTheHandlersValue) {
  const auto value = std::get<ParamValue>(
      Only(endpoint_.OnReceive(kNow, Frames({{kMe, ParamRead{{kServerId, 1}, 17}}}))));
  EXPECT_EQ(value.param_id, 17);
  EXPECT_EQ(value.value, CountingHandler::kValue);
}

// A schedule granting slots to several vehicles, ours among them.
SlotSchedule Schedule(std::uint8_t slot_bytes) {
  SlotSchedule s;
  s.header = {kServerId, 5};
  s.first_slot_delay_us = 5'000;
  s.guard_us = 500;
  const std::vector<Slot> slots{{1, ReplyKind::kTelemetry, slot_bytes},
                                {kMe, ReplyKind::kTelemetry, slot_bytes},
                                {kOther, ReplyKind::kTelemetry, slot_bytes},
                                {kMe, ReplyKind::kFireReport, slot_bytes}};
  s.slot_count = static_cast<std::uint8_t>(slots.size());
  std::copy(slots.begin(), slots.end(), s.slots.begin());
  return s;
}

TEST(VehicleEndpointSlots, RepliesStartExactlyAtTheirSlots) {
  CountingHandler handler;
  VehicleEndpoint endpoint(Config(LinkMode::kSlots), handler);
  constexpr std::uint8_t kSlotBytes = 60;
  // A frame after the schedule in the same burst: the schedule ended its airtime earlier.
  const auto trailer = Frames({{kOther, FireReportAck{{kServerId, 6}, kOther, 1}}});
  auto bytes = Frames({{kBroadcastId, Schedule(kSlotBytes)}});
  bytes.insert(bytes.end(), trailer.begin(), trailer.end());

  const auto bursts = endpoint.OnReceive(kNow, bytes);
  const Nanos schedule_end = kNow - Airtime(trailer.size(), kBaud);
  const Nanos slot = Airtime(kSlotBytes, kBaud) + std::chrono::microseconds(500);
  const Nanos first_slot = schedule_end + std::chrono::microseconds(5'000);
  ASSERT_EQ(bursts.size(), 2U);
  EXPECT_EQ(bursts[0].start, first_slot + 1 * slot);
  EXPECT_EQ(bursts[1].start, first_slot + 3 * slot);
  EXPECT_EQ(bursts[0].bytes.size(), TelemetryFrameBytes());
  // Nothing to report: the report slot carries telemetry.
  EXPECT_TRUE(std::holds_alternative<Telemetry>(Decode(bursts[1]).at(0)));
}

TEST(VehicleEndpointSlots, ReplyThatDoesNotFitItsSlotIsNotSent) {
  CountingHandler handler;
  VehicleEndpoint endpoint(Config(LinkMode::kSlots), handler);
  const auto small = static_cast<std::uint8_t>(TelemetryFrameBytes() - 1);
  EXPECT_TRUE(endpoint.OnReceive(kNow, Frames({{kBroadcastId, Schedule(small)}})).empty());
  EXPECT_EQ(endpoint.stats().turns_skipped, 2U);
}

TEST(VehicleEndpointSlots, RequestIsAnsweredInItsAckSlotNotAtOnce) {
  CountingHandler handler;
  VehicleEndpoint endpoint(Config(LinkMode::kSlots), handler);
  const Command hold{{kServerId, 11}, CommandType::kHold};
  EXPECT_TRUE(endpoint.OnReceive(kNow, Frames({{kMe, hold}})).empty());
  EXPECT_EQ(handler.commands, 1);

  SlotSchedule schedule;
  schedule.first_slot_delay_us = 5'000;
  schedule.slot_count = 1;
  schedule.slots[0] = Slot{kMe, ReplyKind::kAck, 40};
  const auto bursts = endpoint.OnReceive(2 * kNow, Frames({{kBroadcastId, schedule}}));
  ASSERT_EQ(bursts.size(), 1U);
  EXPECT_EQ(bursts[0].start, 2 * kNow + std::chrono::microseconds(5'000));
  EXPECT_EQ(std::get<CommandAck>(Only(bursts)).acked_sequence, 11);
}

TEST(VehicleEndpointSlots, SecondReportSlotCarriesTheSecondReport) {
  CountingHandler handler;
  VehicleEndpoint endpoint(Config(LinkMode::kSlots), handler);
  endpoint.QueueFireReport(FireReport{});
  endpoint.QueueFireReport(FireReport{});
  SlotSchedule schedule;
  schedule.first_slot_delay_us = 5'000;
  schedule.slot_count = 2;
  schedule.slots[0] = Slot{kMe, ReplyKind::kFireReport, 60};
  schedule.slots[1] = Slot{kMe, ReplyKind::kFireReport, 60};
  const auto bursts = endpoint.OnReceive(kNow, Frames({{kBroadcastId, schedule}}));
  ASSERT_EQ(bursts.size(), 2U);
  EXPECT_EQ(std::get<FireReport>(Decode(bursts[0]).at(0)).report_id, 0);
  EXPECT_EQ(std::get<FireReport>(Decode(bursts[1]).at(0)).report_id, 1);
}

TEST(VehicleEndpointConfig, RejectsServerAndBroadcastIds) {
  CountingHandler handler;
  for (const std::uint8_t id : {kServerId, kBroadcastId}) {
    VehicleEndpointConfig config = Config(LinkMode::kPoll);
    config.id = id;
    EXPECT_THROW(VehicleEndpoint(config, handler), std::invalid_argument);
  }
}

}  // namespace
}  // namespace fireswarm::radio
