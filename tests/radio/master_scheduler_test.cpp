#include "fireswarm/radio/master_scheduler.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <ostream>
#include <vector>

#include "radio/sim_net.hpp"

namespace fireswarm::radio {
namespace {

using sim_test::kBaud;
using sim_test::kChecksum;
using sim_test::kTurnaround;
using sim_test::ServerConfig;
using sim_test::SimNet;
using std::chrono::milliseconds;
using std::chrono::seconds;

std::map<int, int> TelemetryCounts(const SimNet& net) {
  std::map<int, int> counts;
  for (const auto& e : net.EventsOf<TelemetryReceived>()) ++counts[e.vehicle];
  return counts;
}

// Every message in a server burst, with its receiver.
std::vector<std::pair<std::uint8_t, Message>> DecodeServerBurst(const Burst& burst) {
  std::vector<std::pair<std::uint8_t, Message>> out;
  FrameParser parser(kChecksum);
  parser.Feed(burst.bytes, [&](const FrameView& f) {
    out.emplace_back(f.receiver, *DecodePayload(f.message_id, f.data).message);
  });
  return out;
}

}  // namespace

// Readable parameter names in test output.
void PrintTo(LinkMode mode, std::ostream* out) {
  *out << ToString(mode);
}

namespace {

class MasterSchedulerModes : public ::testing::TestWithParam<LinkMode> {};

TEST_P(MasterSchedulerModes, EqualRatesGiveEqualTelemetry) {
  constexpr int kVehicles = 10;
  SimNet net(ServerConfig(GetParam()), kVehicles);
  for (int i = 1; i <= kVehicles; ++i) net.server().AddVehicle(static_cast<std::uint8_t>(i));
  net.RunUntil(seconds(60) - Nanos{1});
  const auto counts = TelemetryCounts(net);
  ASSERT_EQ(counts.size(), static_cast<std::size_t>(kVehicles));
  for (const auto& [vehicle, count] : counts) {
    EXPECT_NEAR(count, 60, 1) << "vehicle " << vehicle;
  }
}

TEST_P(MasterSchedulerModes, PerVehicleRatesAreHonoured) {
  SimNet net(ServerConfig(GetParam()), 3);
  net.server().AddVehicle(1, 4.0);
  net.server().AddVehicle(2, 0.5);
  net.server().AddVehicle(3);  // default 1 Hz
  net.server().SetTelemetryRate(3, 2.0);
  net.RunUntil(seconds(30) - Nanos{1});
  const auto counts = TelemetryCounts(net);
  EXPECT_NEAR(counts.at(1), 120, 2);
  EXPECT_NEAR(counts.at(2), 15, 1);
  EXPECT_NEAR(counts.at(3), 60, 1);
}

TEST_P(MasterSchedulerModes, DeliversEveryReportAndRequestWithoutLoss) {
  constexpr int kVehicles = 20;
  SimNet net(ServerConfig(GetParam()), kVehicles);
  int requests = 0;
  for (int i = 1; i <= kVehicles; ++i) {
    const auto id = static_cast<std::uint8_t>(i);
    net.server().AddVehicle(id, 1.0, milliseconds(50 * i));
    for (int r = 0; r < i % 3 + 1; ++r) net.vehicle(i).endpoint.QueueFireReport(FireReport{});
    net.server().SendCommand(id, Command{{}, CommandType::kStartMission});
    net.server().WriteParam(id, 7, 1.5F);
    requests += 2;
  }
  net.RunUntil(seconds(10));
  std::size_t queued = 0;
  for (int i = 1; i <= kVehicles; ++i) queued += static_cast<std::size_t>(i % 3 + 1);
  EXPECT_EQ(net.EventsOf<FireReportReceived>().size(), queued);
  const auto finished = net.EventsOf<RequestFinished>();
  EXPECT_EQ(finished.size(), static_cast<std::size_t>(requests));
  for (const auto& f : finished) EXPECT_EQ(f.status, RequestStatus::kCompleted);
  for (int i = 1; i <= kVehicles; ++i) EXPECT_EQ(net.vehicle(i).endpoint.pending_reports(), 0U);
  EXPECT_EQ(net.channel().stats().collisions, 0U);
  EXPECT_EQ(net.server().stats().missed_replies, 0U);
  EXPECT_EQ(net.server().stats().retries, 0U);
}

TEST_P(MasterSchedulerModes, LostRepliesAreRetriedWithTheSameSequence) {
  SimNet net(ServerConfig(GetParam()), 1);
  net.server().AddVehicle(1, 1.0, seconds(100));  // no telemetry in the way
  const RequestId id = net.server().SendCommand(1, Command{{}, CommandType::kLand});
  int acks_dropped = 0;
  net.drop_reply = [&](std::uint8_t, const Burst& burst) {
    return burst.bytes.at(4) == static_cast<std::uint8_t>(MessageId::kCommandAck) &&
           acks_dropped++ < 2;
  };
  std::vector<std::uint16_t> sequences;
  net.drop_server_burst = [&](const Burst& burst) {
    for (const auto& [receiver, message] : DecodeServerBurst(burst)) {
      if (const auto* c = std::get_if<Command>(&message)) sequences.push_back(c->header.sequence);
    }
    return false;
  };
  net.RunUntil(seconds(5));
  ASSERT_EQ(sequences.size(), 3U);
  EXPECT_EQ(sequences[1], sequences[0]);
  EXPECT_EQ(sequences[2], sequences[0]);
  const auto finished = net.EventsOf<RequestFinished>();
  ASSERT_EQ(finished.size(), 1U);
  EXPECT_EQ(finished[0].id, id);
  EXPECT_EQ(finished[0].status, RequestStatus::kCompleted);
  EXPECT_EQ(finished[0].retries, 2);
  EXPECT_EQ(net.server().stats().retries, 2U);
  // The vehicle heard all three, executed one.
  EXPECT_EQ(net.vehicle(1).handler.executed, 1);
  EXPECT_EQ(net.vehicle(1).endpoint.stats().duplicate_requests, 2U);
}

// The server learns when a command's frame went out (the command center shows it
// as "sent"): one RequestSent per transmission, in the burst that carried it,
// before the request finishes.
TEST_P(MasterSchedulerModes, EverySendOfARequestIsReportedWithTheBurstThatCarriedIt) {
  SimNet net(ServerConfig(GetParam()), 1);
  net.server().AddVehicle(1, 1.0, seconds(100));  // no telemetry in the way
  const RequestId id = net.server().SendCommand(1, Command{{}, CommandType::kHold});
  int acks_dropped = 0;
  net.drop_reply = [&](std::uint8_t, const Burst& burst) {
    return burst.bytes.at(4) == static_cast<std::uint8_t>(MessageId::kCommandAck) &&
           acks_dropped++ < 1;
  };
  std::vector<Nanos> command_bursts;  // starts of the bursts holding the command
  net.drop_server_burst = [&](const Burst& burst) {
    for (const auto& [receiver, message] : DecodeServerBurst(burst)) {
      if (std::holds_alternative<Command>(message)) command_bursts.push_back(burst.start);
    }
    return false;
  };
  net.RunUntil(seconds(5));
  const auto sent = net.EventsOf<RequestSent>();
  ASSERT_EQ(sent.size(), 2U);
  ASSERT_EQ(command_bursts.size(), 2U);
  for (std::size_t i = 0; i < sent.size(); ++i) {
    EXPECT_EQ(sent[i].id, id);
    EXPECT_EQ(sent[i].vehicle, 1);
    EXPECT_EQ(sent[i].attempt, static_cast<int>(i));
    EXPECT_EQ(sent[i].sent, command_bursts[i]);
  }
  // Sent first, finished after.
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < net.events().size(); ++i) {
    if (std::holds_alternative<RequestSent>(net.events()[i]) ||
        std::holds_alternative<RequestFinished>(net.events()[i])) {
      order.push_back(net.events()[i].index());
    }
  }
  const std::size_t sent_index = SchedulerEvent{RequestSent{}}.index();
  const std::size_t finished_index = SchedulerEvent{RequestFinished{}}.index();
  EXPECT_EQ(order, (std::vector<std::size_t>{sent_index, sent_index, finished_index}));
}

// A request queued behind another is not sent (nor said to be) before the first
// one finished, here failed unanswered.
TEST_P(MasterSchedulerModes, ARequestWaitingItsTurnIsNotReportedSent) {
  SimNet net(ServerConfig(GetParam()), 1);
  net.server().AddVehicle(1, 1.0, seconds(100));
  const RequestId first = net.server().SendCommand(1, Command{{}, CommandType::kHold});
  const RequestId second = net.server().SendCommand(1, Command{{}, CommandType::kResume});
  net.drop_reply = [](std::uint8_t, const Burst&) { return true; };  // the vehicle is unheard
  net.RunUntil(seconds(5));
  bool first_finished = false;
  int second_sent = 0;
  for (const SchedulerEvent& e : net.events()) {
    if (const auto* f = std::get_if<RequestFinished>(&e); f != nullptr && f->id == first) {
      first_finished = true;
    }
    if (const auto* s = std::get_if<RequestSent>(&e); s != nullptr && s->id == second) {
      EXPECT_TRUE(first_finished) << "request " << second << " sent before " << first << " ended";
      ++second_sent;
    }
  }
  EXPECT_EQ(second_sent, net.server().config().max_retries + 1);
}

TEST_P(MasterSchedulerModes, RequestFailsAfterMaxRetries) {
  SchedulerConfig config = ServerConfig(GetParam());
  config.max_retries = 3;
  SimNet net(config, 1);
  net.server().AddVehicle(1, 1.0, seconds(100));
  net.drop_reply = [](std::uint8_t, const Burst&) { return true; };  // the vehicle is unheard
  const RequestId id = net.server().ReadParam(1, 3);
  net.RunUntil(seconds(5));
  const auto finished = net.EventsOf<RequestFinished>();
  ASSERT_EQ(finished.size(), 1U);
  EXPECT_EQ(finished[0].id, id);
  EXPECT_EQ(finished[0].status, RequestStatus::kFailed);
  EXPECT_EQ(finished[0].retries, 3);
  EXPECT_EQ(net.server().stats().requests_sent, 4U);
  EXPECT_EQ(net.server().stats().requests_failed, 1U);
}

TEST_P(MasterSchedulerModes, LostAckMeansResendButOneReportEvent) {
  SimNet net(ServerConfig(GetParam()), 1);
  net.server().AddVehicle(1);
  net.vehicle(1).endpoint.QueueFireReport(FireReport{});
  // The vehicle's first FireReportAck is lost: it keeps the report and resends it.
  bool ack_lost = false;
  net.drop_server_burst = [&](const Burst& burst) {
    for (const auto& [receiver, message] : DecodeServerBurst(burst)) {
      if (std::holds_alternative<FireReportAck>(message) && !ack_lost) return ack_lost = true;
    }
    return false;
  };
  net.RunUntil(seconds(5));
  EXPECT_EQ(net.EventsOf<FireReportReceived>().size(), 1U);
  EXPECT_EQ(net.server().stats().duplicate_reports, 1U);
  EXPECT_EQ(net.vehicle(1).endpoint.pending_reports(), 0U);
}

TEST_P(MasterSchedulerModes, ChannelLossCostsRetriesButNothingIsLost) {
  constexpr int kVehicles = 10;
  constexpr double kLoss = 0.2;
  SchedulerConfig config = ServerConfig(GetParam());
  config.max_retries = 10;  // a request then fails with probability ~0.36^11
  SimNet net(config, kVehicles, kLoss);
  for (int i = 1; i <= kVehicles; ++i) {
    const auto id = static_cast<std::uint8_t>(i);
    net.server().AddVehicle(id);
    net.vehicle(i).endpoint.QueueFireReport(FireReport{});
    net.server().SendCommand(id, Command{{}, CommandType::kHold});
  }
  net.RunUntil(seconds(20));
  EXPECT_EQ(net.EventsOf<FireReportReceived>().size(), static_cast<std::size_t>(kVehicles));
  for (const auto& f : net.EventsOf<RequestFinished>()) {
    EXPECT_EQ(f.status, RequestStatus::kCompleted);
  }
  EXPECT_EQ(net.EventsOf<RequestFinished>().size(), static_cast<std::size_t>(kVehicles));
  EXPECT_GT(net.server().stats().missed_replies, 0U);
  for (int i = 1; i <= kVehicles; ++i) EXPECT_EQ(net.vehicle(i).handler.executed, 1);
}

INSTANTIATE_TEST_SUITE_P(BothModes, MasterSchedulerModes,
                         ::testing::Values(LinkMode::kPoll, LinkMode::kSlots),
                         [](const auto& param_info) {
                           return std::string(ToString(param_info.param));
                         });

// --- pure-core tests: the scheduler alone, replies encoded by hand.

std::vector<std::uint8_t> VehicleFrame(const Message& message) {
  std::vector<std::uint8_t> bytes;
  AppendMessageFrame(bytes, kServerId, message, kChecksum);
  return bytes;
}

Nanos AirtimeOf(std::size_t bytes) {
  return Airtime(bytes, kBaud);
}

TEST(MasterScheduler, PollDeadlineIsDerivedFromAirtime) {
  MasterScheduler server(ServerConfig(LinkMode::kPoll));
  server.AddVehicle(1);
  const auto bursts = server.Step(Nanos{0}, {});
  ASSERT_EQ(bursts.size(), 1U);
  const Nanos burst_end = bursts[0].start + AirtimeOf(bursts[0].bytes.size());
  const Nanos reply = AirtimeOf(MessageFrameSize(MessageId::kTelemetry, kChecksum));
  const Nanos expected = burst_end + kTurnaround + reply + server.config().reply_margin;
  EXPECT_EQ(bursts[0].start, kTurnaround);
  EXPECT_EQ(server.exchange()->burst_end, burst_end);
  EXPECT_EQ(server.exchange()->deadline, expected);
  EXPECT_EQ(server.NextWakeup(), expected);
}

TEST(MasterScheduler, RequestDeadlineUsesTheAckSize) {
  MasterScheduler server(ServerConfig(LinkMode::kPoll));
  server.AddVehicle(1, 1.0, seconds(10));
  server.SendCommand(1, Command{{}, CommandType::kHold});
  const auto bursts = server.Step(Nanos{0}, {});
  ASSERT_EQ(bursts.size(), 1U);
  const Nanos burst_end = bursts[0].start + AirtimeOf(bursts[0].bytes.size());
  const Nanos ack = AirtimeOf(MessageFrameSize(MessageId::kCommandAck, kChecksum));
  EXPECT_EQ(server.NextWakeup(), burst_end + kTurnaround + ack + server.config().reply_margin);
}

TEST(MasterScheduler, SlotsDeadlineIsTheLastSlotEndPlusMargin) {
  MasterScheduler server(ServerConfig(LinkMode::kSlots));
  for (std::uint8_t id = 1; id <= 3; ++id) server.AddVehicle(id);
  const auto bursts = server.Step(Nanos{0}, {});
  ASSERT_EQ(bursts.size(), 1U);
  const auto messages = DecodeServerBurst(bursts[0]);
  const auto& schedule = std::get<SlotSchedule>(messages.back().second);
  ASSERT_EQ(schedule.slot_count, 3);
  const Nanos burst_end = bursts[0].start + AirtimeOf(bursts[0].bytes.size());
  const auto telemetry_bytes = MessageFrameSize(MessageId::kTelemetry, kChecksum);
  const Nanos guard = std::chrono::microseconds(schedule.guard_us);
  const Nanos last_slot_end = burst_end + kTurnaround + 3 * AirtimeOf(telemetry_bytes) + 2 * guard;
  EXPECT_EQ(server.NextWakeup(), last_slot_end + server.config().reply_margin);
}

TEST(MasterScheduler, PendingReportIsServedBeforeDueTelemetry) {
  MasterScheduler server(ServerConfig(LinkMode::kPoll));
  for (std::uint8_t id = 1; id <= 3; ++id) server.AddVehicle(id);
  auto bursts = server.Step(Nanos{0}, {});
  const auto first = DecodeServerBurst(bursts.at(0));
  ASSERT_EQ(first.at(0).first, 1);  // all due; the first one first
  // Vehicle 1 answers: it has a report waiting. Vehicles 2 and 3 are overdue.
  Telemetry telemetry{{1, 0}};
  telemetry.flags = telemetry_flags::kReportPending;
  telemetry.pending_reports = 1;
  const Nanos arrival = milliseconds(25);
  bursts = server.Step(arrival, VehicleFrame(telemetry));
  ASSERT_EQ(bursts.size(), 1U);
  EXPECT_EQ(bursts[0].start, arrival + kTurnaround);  // the reply ended the exchange
  const auto next = DecodeServerBurst(bursts[0]);
  ASSERT_EQ(next.size(), 1U);
  EXPECT_EQ(next[0].first, 1);
  EXPECT_EQ(std::get<Poll>(next[0].second).reply, ReplyKind::kFireReport);
}

TEST(MasterScheduler, SlotsPutReportSlotsFirstAndAcksAtTheHead) {
  MasterScheduler server(ServerConfig(LinkMode::kSlots));
  server.AddVehicle(1);
  server.AddVehicle(2);
  server.Step(Nanos{0}, {});
  FireReport report{{2, 0}};
  report.report_id = 9;
  Telemetry telemetry{{2, 1}};
  telemetry.pending_reports = 2;
  std::vector<std::uint8_t> replies = VehicleFrame(report);
  const auto more = VehicleFrame(telemetry);
  replies.insert(replies.end(), more.begin(), more.end());
  server.Step(milliseconds(30), replies);
  // Vehicle 1 stays silent: the cycle ends at its deadline.
  const auto bursts = server.Step(server.NextWakeup(), {});
  ASSERT_EQ(bursts.size(), 1U);
  const auto messages = DecodeServerBurst(bursts[0]);
  const auto& ack = std::get<FireReportAck>(messages.front().second);
  EXPECT_EQ(ack.vehicle, 2);
  EXPECT_EQ(ack.report_id, 9);
  const auto& schedule = std::get<SlotSchedule>(messages.back().second);
  ASSERT_GE(schedule.slot_count, 1);
  EXPECT_EQ(schedule.slots[0].receiver, 2);
  EXPECT_EQ(schedule.slots[0].reply, ReplyKind::kFireReport);
}

TEST(MasterScheduler, ReplyHeldBackByACorruptedFrameCountsAtTheDeadline) {
  MasterScheduler server(ServerConfig(LinkMode::kPoll));
  server.AddVehicle(1);
  server.Step(Nanos{0}, {});
  // A corrupted length (255) before the reply makes the parser wait for bytes that
  // never come; at the deadline the reply behind it is applied.
  std::vector<std::uint8_t> bytes{0x70, 0x96, 0xAC, kServerId, 0x10, 0xFF};
  const auto reply = VehicleFrame(Telemetry{{1, 0}});
  bytes.insert(bytes.end(), reply.begin(), reply.end());
  server.Step(milliseconds(20), bytes);
  EXPECT_TRUE(server.exchange().has_value());
  server.Step(server.NextWakeup(), {});
  EXPECT_EQ(server.stats().telemetry, 1U);
  EXPECT_EQ(server.stats().missed_replies, 0U);
}

TEST(MasterScheduler, SilentVehicleIsReportedOnce) {
  SchedulerConfig config = ServerConfig(LinkMode::kPoll);
  config.silent_after_missed_replies = 2;
  MasterScheduler server(config);
  server.AddVehicle(1, 10.0);
  for (int i = 0; i < 5; ++i) server.Step(server.NextWakeup(), {});
  int silent = 0;
  for (const auto& e : server.TakeEvents()) silent += std::holds_alternative<VehicleSilent>(e);
  EXPECT_EQ(silent, 1);
  EXPECT_GE(server.stats().missed_replies, 2U);
}

// Each telemetry frame names the grid turn it served. Replies lost for less than a
// period: the turn is served late and the grid goes on (1 s, 2 s, 3 s). Lost for
// more than a period: the late frame serves the first turn, the skipped one is
// never served and a new grid starts when the vehicle is heard.
std::vector<Nanos> TurnsServed(Nanos replies_lost_until, Nanos run_until) {
  SimNet net(ServerConfig(LinkMode::kSlots), 1);
  net.server().AddVehicle(1, 1.0, Nanos{0});
  net.drop_reply = [&](std::uint8_t, const Burst& burst) {
    return burst.start < replies_lost_until;
  };
  net.RunUntil(run_until);
  std::vector<Nanos> served;
  for (const auto& e : net.EventsOf<TelemetryReceived>()) {
    EXPECT_GE(e.received, replies_lost_until);
    EXPECT_TRUE(e.served_due.has_value()) << "every frame here answers a telemetry turn";
    if (e.served_due) served.push_back(*e.served_due);
  }
  return served;
}

TEST(MasterScheduler, TelemetryNamesTheTurnItServedAfterLostReplies) {
  EXPECT_EQ(TurnsServed(milliseconds(400), milliseconds(3500)),
            (std::vector<Nanos>{Nanos{0}, seconds(1), seconds(2), seconds(3)}));

  const std::vector<Nanos> late = TurnsServed(milliseconds(1500), milliseconds(3500));
  ASSERT_GE(late.size(), 2U);
  EXPECT_EQ(late[0], Nanos{0});
  EXPECT_GE(late[1], milliseconds(1500)) << "the turn due at 1 s is skipped, not made up";
  EXPECT_EQ(std::count(late.begin(), late.end(), seconds(1)), 0);
}

TEST(MasterScheduler, TellsTheTelemetryRateItPollsAt) {
  MasterScheduler server(ServerConfig(LinkMode::kSlots));
  server.AddVehicle(1, 4.0);
  server.AddVehicle(2);  // default_telemetry_hz
  EXPECT_DOUBLE_EQ(server.TelemetryRateHz(1), 4.0);
  EXPECT_DOUBLE_EQ(server.TelemetryRateHz(2), server.config().default_telemetry_hz);
  server.SetTelemetryRate(2, 0.5);
  EXPECT_DOUBLE_EQ(server.TelemetryRateHz(2), 0.5);
  EXPECT_THROW(server.TelemetryRateHz(3), std::invalid_argument);
}

TEST(MasterScheduler, RejectsBadVehiclesAndConfig) {
  MasterScheduler server(ServerConfig(LinkMode::kSlots));
  EXPECT_THROW(server.AddVehicle(0), std::invalid_argument);
  EXPECT_THROW(server.AddVehicle(255), std::invalid_argument);
  server.AddVehicle(1);
  EXPECT_THROW(server.AddVehicle(1), std::invalid_argument);
  EXPECT_THROW(server.SendCommand(2, Command{}), std::invalid_argument);
  EXPECT_THROW(server.SetTelemetryRate(1, 0.0), std::invalid_argument);
  SchedulerConfig bad = ServerConfig(LinkMode::kSlots);
  bad.max_slots = 0;
  EXPECT_THROW(MasterScheduler{bad}, std::invalid_argument);
}

}  // namespace
}  // namespace fireswarm::radio
