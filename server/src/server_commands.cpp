// The server's operator commands: checking them, carrying them out over the
// radio, journaling them and keeping their status records (server.hpp says
// what each does and how its targets' states are told).
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "fireswarm/common/time.hpp"
#include "fireswarm/server/server.hpp"
#include "local_point.hpp"

namespace fireswarm::server {

namespace {

using Kind = OperatorCommand::Kind;

// The radio command a per-drone or fleet order sends.
radio::CommandType RadioCommandOf(Kind kind) {
  switch (kind) {
    case Kind::kHold:
    case Kind::kHoldAll:
      return radio::CommandType::kHold;
    case Kind::kResume:
    case Kind::kResumeAll:
      return radio::CommandType::kResume;
    case Kind::kReturnVehicle:
    case Kind::kReturnAll:
      return radio::CommandType::kReturnToLaunch;
    case Kind::kLand:
      return radio::CommandType::kLand;
    case Kind::kAbort:
    case Kind::kStart:
    case Kind::kInvestigatePoint:
    case Kind::kRetaskVehicle:
      break;
  }
  // Not called for these: should it ever be, the harmless order.
  return radio::CommandType::kHold;
}

// The refusal HandleSigned journals for `verdict`, its text naming the reason.
CommandRefused RefusalOf(const SignedCommand& command, CommandVerdict verdict,
                         std::int64_t now_utime, const CommandVerifier& verifier) {
  const CommandCredentials& c = command.credentials;
  CommandRefused refusal{verdict,
                         static_cast<int>(command.command.kind),
                         command.command.vehicle,
                         c.operator_id.substr(0, kMaxOperatorIdBytes),
                         c.utime,
                         c.nonce,
                         {}};
  const std::string who = "operator '" + refusal.operator_id + "'";
  std::string why = ToString(verdict);
  switch (verdict) {
    case CommandVerdict::kMalformed:
      why +=
          ": the operator ID must be 1..64 of A-Z a-z 0-9 _ . - and the reason at most 65535 "
          "bytes";
      break;
    case CommandVerdict::kUnknownOperator:
      why += verifier.operator_count() == 0
                 ? ": no operator keys are loaded (serve --keys DIR): every command is refused"
                 : ": no key for " + who + " in the key store";
      break;
    case CommandVerdict::kBadMac:
      why +=
          ": the MAC does not match " + who + "'s key (forged, altered or signed with another key)";
      break;
    case CommandVerdict::kStale:
      why += ": utime " + std::to_string(c.utime) + " is outside the window of +-" +
             std::to_string(verifier.window_us() / 1'000'000) + " s around the server's clock (" +
             std::to_string(now_utime) + ")";
      break;
    case CommandVerdict::kReplayed:
      why += ": " + who + " already used nonce " + std::to_string(c.nonce) + " within the window";
      break;
    case CommandVerdict::kAccepted:
      break;
  }
  refusal.why = std::move(why);
  return refusal;
}

}  // namespace

bool Server::Handle(const OperatorCommand& command, common::Nanos now, std::string* why,
                    std::int32_t* command_id) {
  return Carry(command, now, why, command_id, nullptr);
}

bool Server::HandleSigned(const SignedCommand& command, common::Nanos now, std::int64_t now_utime,
                          std::string* why, std::int32_t* command_id, CommandVerdict* verdict) {
  const CommandVerdict checked = verifier_.Verify(command, now_utime);
  if (verdict != nullptr) *verdict = checked;
  if (checked == CommandVerdict::kAccepted) {
    return Carry(command.command, now, why, command_id, &command.credentials);
  }
  CommandRefused refusal = RefusalOf(command, checked, now_utime, verifier_);
  if (why != nullptr) *why = refusal.why;
  Refuse(std::move(refusal), now);
  return false;
}

void Server::Refuse(CommandRefused refusal, common::Nanos now) {
  ++command_refusals_.at(static_cast<std::size_t>(refusal.verdict));
  ++refusal_count_;
  if (refusal.operator_id.size() > kMaxOperatorIdBytes) {
    refusal.operator_id.resize(kMaxOperatorIdBytes);
  }
  recent_refusals_.push_back(refusal);
  if (recent_refusals_.size() > kKeptRefusals) recent_refusals_.pop_front();
  Record(common::ToSeconds(now), std::move(refusal));
}

bool Server::Carry(const OperatorCommand& command, common::Nanos now, std::string* why,
                   std::int32_t* command_id, const CommandCredentials* signer) {
  const double now_s = common::ToSeconds(now);
  std::int32_t id = 0;
  std::optional<std::string> refusal;
  const auto accept = [&](std::vector<std::uint8_t> targets) {
    id = commands_.Open(command.kind, now_s, command.reason, std::move(targets));
    Record(now_s, CommandAccepted{
                      command.kind, command.vehicle, command.point, command.reason, id, {}, 0, 0});
  };
  switch (command.kind) {
    case Kind::kStart:
      if (!mission_) {
        refusal = "no mission is loaded";
      } else if (state_ != MissionState::kIdle) {
        refusal = "the mission has already started";
      } else {
        accept(mission_->vehicles());
        start_command_id_ = id;
        mission_->Begin();
        mission_started_s_ = now_s;
        state_ = MissionState::kUploading;
      }
      break;
    case Kind::kAbort:
      accept(registry_.ids());
      SendToAll(radio::CommandType::kAbort, id);
      state_ = MissionState::kAborted;
      if (mission_) mission_->StopSorties();
      break;
    case Kind::kReturnAll:
      accept(registry_.ids());
      SendToAll(radio::CommandType::kReturnToLaunch, id);
      if (state_ != MissionState::kAborted) state_ = MissionState::kReturning;
      // Home means home: no drone takes off for its next sortie after this.
      if (mission_) mission_->StopSorties();
      break;
    case Kind::kHoldAll:
    case Kind::kResumeAll:
      if (registry_.size() == 0) {
        refusal = std::string(ToString(command.kind)) + ": no vehicle is registered";
        break;
      }
      accept(registry_.ids());
      SendToAll(RadioCommandOf(command.kind), id);
      CallOff(CommandAccepted{command.kind, 0, {}, {}, id, {}, 0, 0}, now_s);
      break;
    case Kind::kHold:
    case Kind::kResume:
    case Kind::kReturnVehicle:
    case Kind::kLand:
      refusal = HandleDroneOrder(command, now_s, &id);
      break;
    case Kind::kInvestigatePoint:
    case Kind::kRetaskVehicle:
      refusal = HandleInvestigation(command, now_s, &id);
      break;
    default:
      refusal = "unknown command " + std::to_string(static_cast<int>(command.kind));
      break;
  }
  if (refusal) {
    if (why != nullptr) *why = std::move(*refusal);
    return false;
  }
  if (signer != nullptr) Attribute(id, *signer);
  if (command_id != nullptr) *command_id = id;
  return true;
}

void Server::Attribute(std::int32_t command_id, const CommandCredentials& signer) {
  commands_.Attribute(command_id, signer.operator_id, signer.nonce);
  // The command's journal entry, recorded just now, names its signer too.
  for (auto entry = journal_.rbegin(); entry != journal_.rend(); ++entry) {
    auto* accepted = std::get_if<CommandAccepted>(&entry->event);
    if (accepted == nullptr || accepted->command_id != command_id) continue;
    accepted->operator_id = signer.operator_id;
    accepted->utime = signer.utime;
    accepted->nonce = signer.nonce;
    break;
  }
}

std::optional<std::string> Server::HandleDroneOrder(const OperatorCommand& command, double now_s,
                                                    std::int32_t* command_id) {
  const std::uint8_t vehicle = command.vehicle;
  if (vehicle == 0) return std::string(ToString(command.kind)) + " needs a vehicle";
  if (!registry_.Contains(vehicle)) {
    return "vehicle " + std::to_string(vehicle) + " is not registered";
  }
  *command_id = commands_.Open(command.kind, now_s, command.reason, {vehicle});
  const CommandAccepted accepted{
      command.kind, vehicle, command.point, command.reason, *command_id, {}, 0, 0};
  Record(now_s, accepted);
  radio::Command order;
  order.type = RadioCommandOf(command.kind);
  commands_.Track(*command_id, vehicle, scheduler_->SendCommand(vehicle, order));
  CallOff(accepted, now_s);
  return std::nullopt;
}

std::optional<std::string> Server::HandleInvestigation(const OperatorCommand& command, double now_s,
                                                       std::int32_t* command_id) {
  if (!common::IsValidLatLon(command.point)) return "the point is not a valid lat/lon";
  if (command.vehicle != 0 && !registry_.Contains(command.vehicle)) {
    return "vehicle " + std::to_string(command.vehicle) + " is not registered";
  }
  if (command.vehicle == 0 && command.kind == Kind::kRetaskVehicle) {
    return "re-task needs a vehicle";
  }
  const Eigen::Vector2d point_en_m = LocalM(frame_, command.point);
  const double radius_m = investigations_.RadiusM(command.radius_m);
  if (std::optional<std::string> no = investigations_.CircleRefusal(point_en_m, radius_m)) {
    return no;
  }
  std::optional<std::uint8_t> vehicle;
  if (command.vehicle != 0) {
    std::optional<std::string> no =
        investigations_.ApproachRefusal(registry_, command.vehicle, point_en_m, radius_m);
    if (no) return no;
    vehicle = command.vehicle;
  } else {
    std::string why_none;
    vehicle = investigations_.BestPlacedFor(registry_, point_en_m, radius_m, 0, now_s, &why_none);
    if (!vehicle) return why_none;
  }
  *command_id = commands_.Open(command.kind, now_s, command.reason, {*vehicle});
  Record(now_s,
         CommandAccepted{
             command.kind, command.vehicle, command.point, command.reason, *command_id, {}, 0, 0});
  commands_.Track(*command_id, *vehicle,
                  Investigate(*vehicle, command.point, command.radius_m, 0, now_s));
  return std::nullopt;
}

void Server::SendToAll(radio::CommandType type, std::int32_t command_id) {
  radio::Command command;
  command.type = type;
  for (const std::uint8_t id : registry_.ids()) {
    commands_.Track(command_id, id, scheduler_->SendCommand(id, command));
  }
}

radio::RequestId Server::Investigate(std::uint8_t vehicle, common::LatLon point, double radius_m,
                                     std::int32_t track_id, double now_s) {
  const InvestigationOrder order =
      investigations_.Open(registry_, vehicle, point, radius_m, track_id, now_s);
  const radio::RequestId request = scheduler_->SendCommand(vehicle, order.command);
  Record(now_s, InvestigationOpened{vehicle, track_id, order.investigation.until_s,
                                    order.investigation.point_en_m});
  return request;
}

// A drone the operator holds, resumes, sends home or lands is off any
// investigation it was on (also when replayed from the journal).
void Server::CallOff(const CommandAccepted& command, double now_s) {
  switch (command.command) {
    case Kind::kHold:
    case Kind::kResume:
    case Kind::kReturnVehicle:
    case Kind::kLand:
      investigations_.CallOff(command.vehicle, now_s);
      break;
    case Kind::kHoldAll:
    case Kind::kResumeAll:
      for (const std::uint8_t id : registry_.ids()) investigations_.CallOff(id, now_s);
      break;
    default:
      break;
  }
}

void Server::UpdateStartCommand(const radio::SchedulerEvent& event) {
  if (start_command_id_ == 0 || !mission_) return;
  if (const auto* sent = std::get_if<radio::RequestSent>(&event);
      sent != nullptr && mission_->Owns(sent->id)) {
    commands_.Advance(start_command_id_, sent->vehicle, TargetState::kSent);
  }
  for (const std::uint8_t id : mission_->vehicles()) {
    const DroneProgress& progress = mission_->progress(id);
    if (progress.phase == DronePhase::kFlying || progress.phase == DronePhase::kDone ||
        progress.phase == DronePhase::kSwapping || progress.sorties_flown > 0) {
      commands_.Advance(start_command_id_, id, TargetState::kAcknowledged);
    } else if (progress.phase == DronePhase::kFailed) {
      commands_.Advance(start_command_id_, id, TargetState::kFailed, progress.failure);
    }
  }
  // Every target finished: nothing more to follow.
  const TargetState summary = commands_.Find(start_command_id_)->Summary();
  if (summary == TargetState::kAcknowledged || summary == TargetState::kFailed) {
    start_command_id_ = 0;
  }
}

}  // namespace fireswarm::server
