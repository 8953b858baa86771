// The server's operator commands over a real simulated channel to fake vehicles:
// each reaches its vehicles, and its record follows each target from queued to
// sent to acknowledged or failed.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <map>
#include <string>
#include <variant>
#include <vector>

#include "fireswarm/server/server.hpp"
#include "server/fake_fleet.hpp"
#include "server/server_fixture.hpp"

namespace fireswarm::server {
namespace {

using common::Nanos;
using testing::Air;
using testing::Fleet;
using testing::kFrame;
using testing::kSecond;
using testing::LastOf;
using testing::Missions;
using testing::Searching;
using Kind = OperatorCommand::Kind;

const CommandRecord& RecordOf(const Server& server, std::int32_t id) {
  const auto& all = server.commands();
  const auto found =
      std::find_if(all.begin(), all.end(), [&](const CommandRecord& r) { return r.id == id; });
  if (found == all.end()) throw std::out_of_range("no command " + std::to_string(id));
  return *found;
}

const CommandTarget& TargetOf(const Server& server, std::int32_t id, std::uint8_t vehicle) {
  for (const CommandTarget& target : RecordOf(server, id).targets) {
    if (target.vehicle == vehicle) return target;
  }
  throw std::out_of_range("command " + std::to_string(id) + " has no target " +
                          std::to_string(vehicle));
}

bool Finished(TargetState state) {
  return state == TargetState::kAcknowledged || state == TargetState::kFailed;
}

using StateLog = std::map<std::uint8_t, std::vector<TargetState>>;

// Runs the air until every target of command `id` is acknowledged or failed (or
// `limit` of simulated time passed) and returns the states each went through.
StateLog WatchUntilFinished(Air& air, Server& server, std::int32_t id, Nanos limit = 30 * kSecond) {
  StateLog seen;
  const auto look = [&] {
    bool all_finished = true;
    for (const CommandTarget& target : RecordOf(server, id).targets) {
      std::vector<TargetState>& states = seen[target.vehicle];
      if (states.empty() || states.back() != target.state) states.push_back(target.state);
      all_finished = all_finished && Finished(target.state);
    }
    return all_finished;
  };
  look();
  air.Run(server, air.channel().now() + limit, look);
  return seen;
}

Nanos Now(const Fleet& fleet) {
  return fleet.air.channel().now();
}

const std::vector<TargetState> kDelivered{TargetState::kQueued, TargetState::kSent,
                                          TargetState::kAcknowledged};
const std::vector<TargetState> kUndelivered{TargetState::kQueued, TargetState::kSent,
                                            TargetState::kFailed};

TEST(Server, EachDroneCommandReachesItsVehicleQueuedSentAcknowledged) {
  Fleet fleet;
  const std::pair<Kind, radio::CommandType> orders[] = {
      {Kind::kHold, radio::CommandType::kHold},
      {Kind::kResume, radio::CommandType::kResume},
      {Kind::kReturnVehicle, radio::CommandType::kReturnToLaunch},
      {Kind::kLand, radio::CommandType::kLand}};
  std::int32_t expected_id = 2;  // the start was 1
  for (const auto& [kind, radio_type] : orders) {
    std::int32_t id = -1;
    std::string why;
    ASSERT_TRUE(fleet.server.Handle({kind, 2, {}, 0.0, "smoke"}, Now(fleet), &why, &id)) << why;
    EXPECT_EQ(id, expected_id++);
    const CommandRecord& record = RecordOf(fleet.server, id);
    EXPECT_EQ(record.kind, kind);
    EXPECT_EQ(record.reason, "smoke");
    EXPECT_DOUBLE_EQ(record.issued_s, common::ToSeconds(Now(fleet)));
    ASSERT_EQ(record.targets.size(), 1U);
    EXPECT_EQ(record.targets[0].vehicle, 2);

    const StateLog seen = WatchUntilFinished(fleet.air, fleet.server, id);
    EXPECT_EQ(seen.at(2), kDelivered) << ToString(kind);
    EXPECT_EQ(RecordOf(fleet.server, id).Summary(), TargetState::kAcknowledged);
    EXPECT_NE(LastOf(fleet.air.vehicle(2), radio_type), nullptr) << ToString(kind);
    EXPECT_EQ(LastOf(fleet.air.vehicle(1), radio_type), nullptr) << ToString(kind);
  }
}

// A holding drone neither searches nor heads home: the mission goes on.
TEST(Server, HoldAllReachesEveryVehicleAndTheMissionKeepsRunning) {
  Fleet fleet;
  std::int32_t id = 0;
  ASSERT_TRUE(fleet.server.Handle({Kind::kHoldAll, 0, {}, 0.0, ""}, Now(fleet), nullptr, &id));
  const StateLog seen = WatchUntilFinished(fleet.air, fleet.server, id);
  ASSERT_EQ(seen.size(), 3U);
  for (std::uint8_t vehicle = 1; vehicle <= 3; ++vehicle) {
    EXPECT_EQ(seen.at(vehicle), kDelivered) << int{vehicle};
    EXPECT_NE(LastOf(fleet.air.vehicle(vehicle), radio::CommandType::kHold), nullptr);
    radio::Telemetry holding = Searching(100.0 * vehicle, 0, 20'000);
    holding.mode = radio::FlightMode::kHold;
    fleet.air.vehicle(vehicle).endpoint().SetTelemetry(holding);
  }
  fleet.RunFor(10 * kSecond);
  EXPECT_EQ(fleet.server.state(), MissionState::kRunning);

  ASSERT_TRUE(fleet.server.Handle({Kind::kResumeAll, 0, {}, 0.0, ""}, Now(fleet), nullptr, &id));
  for (const auto& [vehicle, states] : WatchUntilFinished(fleet.air, fleet.server, id)) {
    EXPECT_EQ(states, kDelivered) << int{vehicle};
    EXPECT_NE(LastOf(fleet.air.vehicle(vehicle), radio::CommandType::kResume), nullptr);
  }
}

TEST(Server, ACommandToASilentVehicleEndsFailed) {
  Fleet fleet;
  fleet.air.silent.insert(3);
  std::int32_t id = 0;
  ASSERT_TRUE(
      fleet.server.Handle({Kind::kReturnVehicle, 3, {}, 0.0, ""}, Now(fleet), nullptr, &id));
  const StateLog seen = WatchUntilFinished(fleet.air, fleet.server, id);
  EXPECT_EQ(seen.at(3), kUndelivered);
  EXPECT_EQ(TargetOf(fleet.server, id, 3).detail, "no acknowledgement after 3 resends");
  EXPECT_EQ(RecordOf(fleet.server, id).Summary(), TargetState::kFailed);
}

TEST(Server, ACommandTheVehicleRefusesEndsFailedWithItsAnswer) {
  Fleet fleet;
  fleet.air.vehicle(2).refused.insert(radio::CommandType::kLand);
  std::int32_t id = 0;
  ASSERT_TRUE(fleet.server.Handle({Kind::kLand, 2, {}, 0.0, ""}, Now(fleet), nullptr, &id));
  EXPECT_EQ(WatchUntilFinished(fleet.air, fleet.server, id).at(2), kUndelivered);
  EXPECT_EQ(TargetOf(fleet.server, id, 2).detail, "refused by the vehicle: rejected");
}

TEST(Server, DroneAndFleetCommandsWithoutTheirVehiclesAreRefusedWithAReason) {
  Server server(ServerConfig{}, kFrame);
  std::string why;
  std::int32_t id = -1;
  EXPECT_FALSE(server.Handle({Kind::kHoldAll, 0, {}, 0.0, ""}, Nanos{0}, &why, &id));
  EXPECT_EQ(why, "hold_all: no vehicle is registered");
  EXPECT_FALSE(server.Handle({Kind::kResumeAll, 0, {}, 0.0, ""}, Nanos{0}, &why, &id));
  EXPECT_EQ(why, "resume_all: no vehicle is registered");
  server.AddVehicle(1);
  const std::pair<Kind, const char*> needs_vehicle[] = {
      {Kind::kHold, "hold needs a vehicle"},
      {Kind::kResume, "resume needs a vehicle"},
      {Kind::kReturnVehicle, "return needs a vehicle"},
      {Kind::kLand, "land needs a vehicle"}};
  for (const auto& [kind, reason] : needs_vehicle) {
    EXPECT_FALSE(server.Handle({kind, 0, {}, 0.0, ""}, Nanos{0}, &why, &id));
    EXPECT_EQ(why, reason);
    EXPECT_FALSE(server.Handle({kind, 9, {}, 0.0, ""}, Nanos{0}, &why, &id));
    EXPECT_EQ(why, "vehicle 9 is not registered");
  }
  EXPECT_EQ(id, -1) << "a refused command has no ID";
  EXPECT_TRUE(server.commands().empty());
  EXPECT_EQ(server.next_command_id(), 1);
  for (const JournalEntry& entry : server.TakeJournalEntries()) {
    EXPECT_FALSE(std::holds_alternative<CommandAccepted>(entry.event))
        << "refusals are not journaled";
  }
}

// A start's targets follow their drone's upload and start: the one that answers
// is acknowledged once it accepted the start, the silent one fails with why.
TEST(Server, AStartFollowsEachDronesUploadAndStart) {
  Air air(0.0);
  Server server(ServerConfig{}, kFrame);
  for (std::uint8_t id = 1; id <= 2; ++id) {
    air.Add(id);
    server.AddVehicle(id);
  }
  air.silent.insert(2);
  air.vehicle(1).endpoint().SetTelemetry(testing::OnItsStand(-100.0, 50.0, 1'000));
  server.LoadMission(Missions({1, 2}));
  std::int32_t id = 0;
  ASSERT_TRUE(server.Handle({Kind::kStart, 0, {}, 0.0, "go"}, Nanos{0}, nullptr, &id));
  EXPECT_EQ(id, 1);
  const StateLog seen = WatchUntilFinished(air, server, id, 120 * kSecond);
  EXPECT_EQ(seen.at(1), kDelivered);
  EXPECT_EQ(seen.at(2), kUndelivered);
  EXPECT_EQ(TargetOf(server, id, 2).detail, server.mission()->progress(2).failure);
  EXPECT_NE(TargetOf(server, id, 2).detail.find("unanswered"), std::string::npos);
  EXPECT_EQ(air.vehicle(1).starts_accepted(), 1);
}

// A start waits until its drone has been heard on its stand: started blind, its
// take-off would be in no clearance's prediction. Heard on the ground without a
// GPS fix, it has no stand yet; with one, it is cleared and started.
TEST(Server, AStartWaitsUntilItsDroneIsHeardOnItsStand) {
  Air air(0.0);
  Server server(ServerConfig{}, kFrame);
  air.Add(1);
  server.AddVehicle(1);
  radio::Telemetry no_fix = testing::OnItsStand(-100.0, 50.0, 1'000);
  no_fix.flags = radio::telemetry_flags::kMissionValid;
  air.vehicle(1).endpoint().SetTelemetry(no_fix);
  server.LoadMission(Missions({1}));
  ASSERT_TRUE(server.Handle({Kind::kStart, 0, {}, 0.0, "go"}, Nanos{0}));
  air.RunUntil(server, 30 * kSecond);
  EXPECT_EQ(server.mission()->progress(1).phase, DronePhase::kStarting);
  EXPECT_GT(server.mission()->progress(1).start_holds, 0);
  EXPECT_EQ(air.vehicle(1).starts_accepted(), 0);

  air.vehicle(1).endpoint().SetTelemetry(testing::OnItsStand(-100.0, 50.0, 31'000));
  air.Run(server, 60 * kSecond, [&] { return air.vehicle(1).starts_accepted() == 1; });
  EXPECT_EQ(air.vehicle(1).starts_accepted(), 1);
}

// Drones 1 and 2, heard on their stands 300 m apart, started on their missions.
void StartTwoFromTheirStands(Air& air, Server& server) {
  for (std::uint8_t id = 1; id <= 2; ++id) {
    air.Add(id);
    server.AddVehicle(id);
  }
  air.vehicle(1).endpoint().SetTelemetry(testing::OnItsStand(0.0, -300.0, 1'000));
  air.vehicle(2).endpoint().SetTelemetry(testing::OnItsStand(300.0, -300.0, 1'000));
  server.LoadMission(Missions({1, 2}));
  ASSERT_TRUE(server.Handle({Kind::kStart, 0, {}, 0.0, "go"}, Nanos{0}));
  air.Run(server, 60 * kSecond, [&] {
    return air.vehicle(1).starts_accepted() == 1 && air.vehicle(2).starts_accepted() == 1;
  });
}

// A drone at its sortie's last waypoint flies home to its stand next (the
// vehicle's return to launch): the watch predicts that way, and sees drone 2,
// hovering on it, before drone 1 has turned. Hovering at the last waypoint, as
// a route's end was predicted before, it would see nothing.
TEST(Server, ADroneEndingItsSortieIsPredictedOnItsWayHome) {
  Air air(0.0);
  Server server(ServerConfig{}, kFrame);
  StartTwoFromTheirStands(air, server);
  ASSERT_EQ(air.vehicle(1).starts_accepted(), 1);
  ASSERT_EQ(air.vehicle(2).starts_accepted(), 1);
  // Drone 1 at (200, 50), its last waypoint, 60 m up; drone 2 holding 60 m
  // up halfway between there and drone 1's stand.
  radio::Telemetry ending = Searching(200.0, 50.0, 70'000);
  ending.waypoint_index = 2;
  air.vehicle(1).endpoint().SetTelemetry(ending);
  radio::Telemetry holding = Searching(100.0, -125.0, 70'000);
  holding.mode = radio::FlightMode::kHold;
  air.vehicle(2).endpoint().SetTelemetry(holding);
  const auto seen = [&] {
    return std::ranges::any_of(server.traffic().conflicts(), [](const Conflict& c) {
      return c.vehicle_a == 1 && c.vehicle_b == 2;
    });
  };
  air.Run(server, air.channel().now() + 20 * kSecond, seen);
  EXPECT_TRUE(seen());
}

// Drones that refuse every avoid order (as when the radio gives up on one
// after its resends): the watch does not take an order as obeyed once it hears
// it was not, and orders again. Taken as obeyed, the first order would be
// predicted to clear the pair, and no other would follow.
TEST(Server, AnAvoidOrderTheDroneDidNotTakeIsGivenAgain) {
  Air air(0.0);
  Server server(ServerConfig{}, kFrame);
  StartTwoFromTheirStands(air, server);
  ASSERT_EQ(air.vehicle(1).starts_accepted(), 1);
  ASSERT_EQ(air.vehicle(2).starts_accepted(), 1);
  // Head-on at one altitude, 500 m apart at 10 m/s each: 25 s to meet.
  const auto head_on = [&](std::uint8_t id, double north_m, double velocity_north_mps) {
    radio::Telemetry telemetry = Searching(0.0, north_m, 70'000);
    telemetry.mode = radio::FlightMode::kHold;
    telemetry.velocity_north_mps = velocity_north_mps;
    air.vehicle(id).endpoint().SetTelemetry(telemetry);
    air.vehicle(id).refused.insert(radio::CommandType::kAvoid);
  };
  head_on(1, -250.0, 10.0);
  head_on(2, 250.0, -10.0);
  const auto avoid_orders = [&] {
    int n = 0;
    for (std::uint8_t id = 1; id <= 2; ++id) {
      n += static_cast<int>(std::ranges::count_if(
          air.vehicle(id).commands(),
          [](const radio::Command& c) { return c.type == radio::CommandType::kAvoid; }));
    }
    return n;
  };
  air.Run(server, air.channel().now() + 20 * kSecond, [&] { return avoid_orders() >= 3; });
  EXPECT_GE(avoid_orders(), 3);
  EXPECT_GE(server.traffic().counts().not_taken, 2U);
}

// The operator's hold interrupts an investigation: it ends at once and judges
// nothing (the track would otherwise be rejected for not being seen again).
TEST(Server, AHoldTakesTheDroneOffItsInvestigationWithoutAVerdict) {
  Fleet fleet;
  const common::LatLon point = kFrame.ToGeodetic({50.0, 50.0});
  ASSERT_TRUE(fleet.server.Handle({Kind::kRetaskVehicle, 1, point, 0.0, ""}, Now(fleet)));
  ASSERT_EQ(fleet.server.investigations().size(), 1U);
  EXPECT_GT(fleet.server.investigations()[0].until_s, common::ToSeconds(Now(fleet)) + 30.0);
  fleet.RunFor(2 * kSecond);
  ASSERT_TRUE(fleet.server.Handle({Kind::kHold, 1, {}, 0.0, ""}, Now(fleet)));
  const Investigation& called_off = fleet.server.investigations()[0];
  EXPECT_DOUBLE_EQ(called_off.until_s, common::ToSeconds(Now(fleet)));
  EXPECT_TRUE(called_off.judged);
}

// Command IDs are unique for the server's life, a restart from its journal
// included; the restored server calls off the same investigations.
TEST(Server, ARestoredServerGivesNoCommandIdTwice) {
  Fleet fleet;  // the start: command 1
  const common::LatLon point = kFrame.ToGeodetic({50.0, 50.0});
  std::int32_t id = 0;
  ASSERT_TRUE(fleet.server.Handle({Kind::kRetaskVehicle, 1, point, 0.0, ""}, Now(fleet)));
  ASSERT_TRUE(fleet.server.Handle({Kind::kHold, 1, {}, 0.0, ""}, Now(fleet), nullptr, &id));
  ASSERT_TRUE(fleet.server.Handle({Kind::kResumeAll, 0, {}, 0.0, ""}, Now(fleet), nullptr, &id));
  EXPECT_EQ(id, 4);
  std::vector<std::int32_t> journaled_ids;
  const std::vector<JournalEntry> journal = fleet.server.TakeJournalEntries();
  for (const JournalEntry& entry : journal) {
    if (const auto* c = std::get_if<CommandAccepted>(&entry.event)) {
      journaled_ids.push_back(c->command_id);
    }
  }
  EXPECT_EQ(journaled_ids, (std::vector<std::int32_t>{1, 2, 3, 4}));

  Server restored = Server::Restore(ServerConfig{}, kFrame, journal);
  EXPECT_EQ(restored.next_command_id(), 5);
  EXPECT_TRUE(restored.commands().empty()) << "records are of this server's life";
  ASSERT_EQ(restored.investigations().size(), 1U);
  EXPECT_TRUE(restored.investigations()[0].judged);
  ASSERT_TRUE(restored.Handle({Kind::kLand, 2, {}, 0.0, ""}, Now(fleet), nullptr, &id));
  EXPECT_EQ(id, 5);
}

// ---- Signed commands (command_auth.hpp) -------------------------------------

constexpr std::int64_t kUtimeNow = 1'764'000'000'000'000;  // the LCM clock, us

common::SecretKey AnnsKey() {
  common::SecretKey key{};
  key.fill(0xA5);
  return key;
}

ServerConfig WithAnn() {
  ServerConfig config;
  config.operators = {{"ann", AnnsKey()}};
  return config;
}

OperatorCommand HoldOne() {
  return {Kind::kHold, 1, {}, 0.0, "signed hold"};
}

template <typename Event>
std::vector<Event> EventsOf(const std::vector<JournalEntry>& entries) {
  std::vector<Event> events;
  for (const JournalEntry& entry : entries) {
    if (const auto* event = std::get_if<Event>(&entry.event)) events.push_back(*event);
  }
  return events;
}

TEST(Server, TakesASignedCommandAndNamesItsOperator) {
  Fleet fleet(WithAnn());
  fleet.server.TakeJournalEntries();
  std::int32_t id = 0;
  CommandVerdict verdict = CommandVerdict::kMalformed;
  std::string why;
  ASSERT_TRUE(fleet.server.HandleSigned(SignCommand(HoldOne(), "ann", AnnsKey(), kUtimeNow, 9),
                                        Now(fleet), kUtimeNow + 500'000, &why, &id, &verdict))
      << why;
  EXPECT_EQ(verdict, CommandVerdict::kAccepted);
  EXPECT_EQ(RecordOf(fleet.server, id).operator_id, "ann");
  EXPECT_EQ(RecordOf(fleet.server, id).nonce, 9);
  const auto accepted = EventsOf<CommandAccepted>(fleet.server.TakeJournalEntries());
  ASSERT_EQ(accepted.size(), 1u);
  EXPECT_EQ(accepted[0].operator_id, "ann");
  EXPECT_EQ(accepted[0].utime, kUtimeNow);
  EXPECT_EQ(accepted[0].nonce, 9);
  WatchUntilFinished(fleet.air, fleet.server, id);
  EXPECT_NE(LastOf(fleet.air.vehicle(1), radio::CommandType::kHold), nullptr);
}

TEST(Server, RefusesForgedStaleReplayedAndUnknownCommandsJournalingAndCountingEach) {
  Fleet fleet(WithAnn());
  fleet.server.TakeJournalEntries();
  const std::size_t records = fleet.server.commands().size();
  const SignedCommand good = SignCommand(HoldOne(), "ann", AnnsKey(), kUtimeNow, 1);
  ASSERT_TRUE(fleet.server.HandleSigned(good, Now(fleet), kUtimeNow));
  SignedCommand unsigned_hold{HoldOne(), {"ann", kUtimeNow, 2, {}}};
  common::SecretKey bobs_key = AnnsKey();
  bobs_key[0] ^= 1;
  const std::vector<std::pair<SignedCommand, CommandVerdict>> refused = {
      {unsigned_hold, CommandVerdict::kBadMac},
      {SignCommand(HoldOne(), "bob", bobs_key, kUtimeNow, 3), CommandVerdict::kUnknownOperator},
      {SignCommand(HoldOne(), "ann", AnnsKey(), kUtimeNow - 31'000'000, 4), CommandVerdict::kStale},
      {good, CommandVerdict::kReplayed},
  };
  for (const auto& [command, expected] : refused) {
    std::string why;
    CommandVerdict verdict = CommandVerdict::kAccepted;
    EXPECT_FALSE(
        fleet.server.HandleSigned(command, Now(fleet), kUtimeNow, &why, nullptr, &verdict));
    EXPECT_EQ(verdict, expected);
    EXPECT_TRUE(why.starts_with(ToString(expected))) << why;
  }
  EXPECT_EQ(fleet.server.commands().size(), records + 1) << "only the good one has a record";
  const auto& counts = fleet.server.command_refusals();
  for (const CommandVerdict v : {CommandVerdict::kBadMac, CommandVerdict::kUnknownOperator,
                                 CommandVerdict::kStale, CommandVerdict::kReplayed}) {
    EXPECT_EQ(counts.at(static_cast<std::size_t>(v)), 1u) << ToString(v);
  }
  EXPECT_EQ(fleet.server.refusal_count(), 4u);
  ASSERT_EQ(fleet.server.recent_refusals().size(), 4u);
  const auto journaled = EventsOf<CommandRefused>(fleet.server.TakeJournalEntries());
  ASSERT_EQ(journaled.size(), 4u);
  EXPECT_EQ(journaled[1].operator_id, "bob") << "who it claimed to come from";
  EXPECT_EQ(journaled[1].command, static_cast<int>(Kind::kHold));
  EXPECT_EQ(journaled[1].vehicle, 1);
  EXPECT_NE(journaled[2].why.find("window"), std::string::npos) << journaled[2].why;
}

TEST(Server, WithoutOperatorKeysEverySignedCommandIsRefused) {
  Fleet fleet;
  std::string why;
  EXPECT_FALSE(fleet.server.HandleSigned(SignCommand(HoldOne(), "ann", AnnsKey(), kUtimeNow, 1),
                                         Now(fleet), kUtimeNow, &why));
  EXPECT_NE(why.find("no operator keys"), std::string::npos) << why;
}

TEST(Server, ARestoredServerStillRefusesAReplayedCommand) {
  Fleet fleet(WithAnn());
  const SignedCommand hold = SignCommand(HoldOne(), "ann", AnnsKey(), kUtimeNow, 77);
  ASSERT_TRUE(fleet.server.HandleSigned(hold, Now(fleet), kUtimeNow));
  Server restored = Server::Restore(WithAnn(), kFrame, fleet.server.TakeJournalEntries());
  CommandVerdict verdict = CommandVerdict::kAccepted;
  EXPECT_FALSE(
      restored.HandleSigned(hold, Now(fleet), kUtimeNow + 1'000'000, nullptr, nullptr, &verdict));
  EXPECT_EQ(verdict, CommandVerdict::kReplayed);
}

}  // namespace
}  // namespace fireswarm::server
