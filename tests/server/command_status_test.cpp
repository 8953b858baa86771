// CommandLog alone, fed with the scheduler's events by hand (the Server tests
// carry commands over a simulated channel).
#include "fireswarm/server/command_status.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace fireswarm::server {
namespace {

using Kind = OperatorCommand::Kind;

radio::RequestFinished Acked(radio::RequestId id, std::uint8_t vehicle,
                             radio::CommandResult result) {
  radio::CommandAck ack;
  ack.result = result;
  return radio::RequestFinished{id,  vehicle, radio::RequestStatus::kCompleted,
                                ack, 0,       common::Nanos{0}};
}

TEST(CommandLog, IdsStartAtOneAndNeverComeBack) {
  CommandLog log;
  EXPECT_EQ(log.Open(Kind::kHold, 1.0, "", {3}), 1);
  EXPECT_EQ(log.Open(Kind::kHoldAll, 2.0, "", {3, 1, 2}), 2);
  log.Reserve(1);  // below: nothing changes
  EXPECT_EQ(log.next_id(), 3);
  log.Reserve(10);
  EXPECT_EQ(log.Open(Kind::kLand, 3.0, "", {1}), 11);
  ASSERT_NE(log.Find(2), nullptr);
  EXPECT_EQ(log.Find(2)->targets.size(), 3U);
  EXPECT_EQ(log.Find(2)->targets[0].vehicle, 1) << "targets ascending";
  EXPECT_EQ(log.Find(2)->targets[2].vehicle, 3);
  EXPECT_EQ(log.Find(5), nullptr);
}

TEST(CommandLog, ATargetGoesQueuedSentAcknowledgedAndEveryChangeRaisesItsVersion) {
  CommandLog log;
  const std::int32_t id = log.Open(Kind::kHold, 0.0, "why", {4});
  const std::uint64_t opened = log.version();
  EXPECT_EQ(log.Find(id)->version, opened);
  EXPECT_EQ(log.Find(id)->targets[0].state, TargetState::kQueued);
  log.Track(id, 4, 77);
  log.OnEvent(radio::RequestSent{76, 4, 0, common::Nanos{0}});  // someone else's request
  EXPECT_EQ(log.version(), opened);
  log.OnEvent(radio::RequestSent{77, 4, 0, common::Nanos{0}});
  EXPECT_EQ(log.Find(id)->targets[0].state, TargetState::kSent);
  EXPECT_GT(log.Find(id)->version, opened);
  const std::uint64_t sent = log.version();
  log.OnEvent(radio::RequestSent{77, 4, 1, common::Nanos{0}});  // a resend: no change
  EXPECT_EQ(log.version(), sent);
  log.OnEvent(Acked(77, 4, radio::CommandResult::kAccepted));
  EXPECT_EQ(log.Find(id)->targets[0].state, TargetState::kAcknowledged);
  EXPECT_EQ(log.Find(id)->Summary(), TargetState::kAcknowledged);
  // Finished is final.
  log.Advance(id, 4, TargetState::kFailed, "late");
  EXPECT_EQ(log.Find(id)->targets[0].state, TargetState::kAcknowledged);
}

TEST(CommandLog, ARefusalOrNoAnswerFailsTheTargetSayingWhy) {
  CommandLog log;
  const std::int32_t id = log.Open(Kind::kHoldAll, 0.0, "", {1, 2, 3});
  log.Track(id, 1, 10);
  log.Track(id, 2, 11);
  log.Track(id, 3, 12);
  EXPECT_EQ(log.Find(id)->Summary(), TargetState::kQueued);
  log.OnEvent(radio::RequestSent{10, 1, 0, common::Nanos{0}});
  EXPECT_EQ(log.Find(id)->Summary(), TargetState::kSent);
  log.OnEvent(Acked(10, 1, radio::CommandResult::kRejected));
  log.OnEvent(radio::RequestFinished{11, 2, radio::RequestStatus::kFailed, std::nullopt, 3,
                                     common::Nanos{0}});
  const CommandRecord& record = *log.Find(id);
  EXPECT_EQ(record.targets[0].state, TargetState::kFailed);
  EXPECT_EQ(record.targets[0].detail, "refused by the vehicle: rejected");
  EXPECT_EQ(record.targets[1].state, TargetState::kFailed);
  EXPECT_EQ(record.targets[1].detail, "no acknowledgement after 3 resends");
  EXPECT_EQ(record.Summary(), TargetState::kSent) << "target 3 is still queued";
  log.OnEvent(Acked(12, 3, radio::CommandResult::kAccepted));
  EXPECT_EQ(log.Find(id)->Summary(), TargetState::kFailed);
}

TEST(CommandLog, StatesHaveTheApisNames) {
  EXPECT_STREQ(ToString(TargetState::kQueued), "queued");
  EXPECT_STREQ(ToString(TargetState::kSent), "sent");
  EXPECT_STREQ(ToString(TargetState::kAcknowledged), "acknowledged");
  EXPECT_STREQ(ToString(TargetState::kFailed), "failed");
  EXPECT_STREQ(ToString(Kind::kReturnVehicle), "return");
  EXPECT_STREQ(ToString(Kind::kRetaskVehicle), "retask");
  EXPECT_STREQ(ToString(Kind::kInvestigatePoint), "investigate");
  EXPECT_STREQ(ToString(Kind::kResumeAll), "resume_all");
}

}  // namespace
}  // namespace fireswarm::server
