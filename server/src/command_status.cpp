#include "fireswarm/server/command_status.hpp"

#include <algorithm>
#include <string>
#include <utility>
#include <variant>

namespace fireswarm::server {

namespace {

bool Finished(TargetState state) {
  return state == TargetState::kAcknowledged || state == TargetState::kFailed;
}

// Why a finished request did not acknowledge the command; empty when it did.
std::string FailureOf(const radio::RequestFinished& finished) {
  if (finished.status == radio::RequestStatus::kFailed) {
    return "no acknowledgement after " + std::to_string(finished.retries) + " resends";
  }
  const auto* ack = finished.ack ? std::get_if<radio::CommandAck>(&*finished.ack) : nullptr;
  if (ack == nullptr) return "the vehicle's answer was not a command acknowledgement";
  if (ack->result != radio::CommandResult::kAccepted) {
    return "refused by the vehicle: " + std::string(radio::ToString(ack->result));
  }
  return {};
}

}  // namespace

const char* ToString(TargetState state) {
  switch (state) {
    case TargetState::kQueued:
      return "queued";
    case TargetState::kSent:
      return "sent";
    case TargetState::kAcknowledged:
      return "acknowledged";
    case TargetState::kFailed:
      return "failed";
  }
  return "unknown";
}

TargetState CommandRecord::Summary() const {
  const auto all = [&](auto predicate) { return std::ranges::all_of(targets, predicate); };
  if (all([](const CommandTarget& t) { return t.state == TargetState::kAcknowledged; })) {
    return TargetState::kAcknowledged;
  }
  if (all([](const CommandTarget& t) { return Finished(t.state); })) return TargetState::kFailed;
  if (all([](const CommandTarget& t) { return t.state == TargetState::kQueued; })) {
    return TargetState::kQueued;
  }
  return TargetState::kSent;
}

std::int32_t CommandLog::Open(OperatorCommand::Kind kind, double issued_s, std::string reason,
                              std::vector<std::uint8_t> targets) {
  std::ranges::sort(targets);
  CommandRecord record;
  record.id = next_id_++;
  record.kind = kind;
  record.issued_s = issued_s;
  record.reason = std::move(reason);
  for (const std::uint8_t vehicle : targets)
    record.targets.push_back({vehicle, TargetState::kQueued, {}});
  record.version = ++version_;
  records_.push_back(std::move(record));
  return records_.back().id;
}

void CommandLog::Track(std::int32_t command_id, std::uint8_t vehicle, radio::RequestId request) {
  requests_[request] = {command_id, vehicle};
}

void CommandLog::OnEvent(const radio::SchedulerEvent& event) {
  if (const auto* sent = std::get_if<radio::RequestSent>(&event)) {
    const auto found = requests_.find(sent->id);
    if (found == requests_.end()) return;
    Advance(found->second.first, found->second.second, TargetState::kSent);
  } else if (const auto* finished = std::get_if<radio::RequestFinished>(&event)) {
    const auto found = requests_.find(finished->id);
    if (found == requests_.end()) return;
    const auto [command_id, vehicle] = found->second;
    requests_.erase(found);
    std::string failure = FailureOf(*finished);
    if (failure.empty()) {
      Advance(command_id, vehicle, TargetState::kAcknowledged);
    } else {
      Advance(command_id, vehicle, TargetState::kFailed, std::move(failure));
    }
  }
}

void CommandLog::Advance(std::int32_t command_id, std::uint8_t vehicle, TargetState state,
                         std::string detail) {
  CommandRecord* record = FindMutable(command_id);
  if (record == nullptr) return;
  for (CommandTarget& target : record->targets) {
    if (target.vehicle != vehicle) continue;
    if (Finished(target.state) || static_cast<int>(state) <= static_cast<int>(target.state)) {
      return;
    }
    target.state = state;
    target.detail = std::move(detail);
    record->version = ++version_;
    return;
  }
}

void CommandLog::Attribute(std::int32_t command_id, std::string operator_id, std::int64_t nonce) {
  CommandRecord* record = FindMutable(command_id);
  if (record == nullptr) return;
  record->operator_id = std::move(operator_id);
  record->nonce = nonce;
  record->version = ++version_;
}

void CommandLog::Reserve(std::int32_t id) {
  next_id_ = std::max(next_id_, id + 1);
}

const CommandRecord* CommandLog::Find(std::int32_t id) const {
  // Records are in ID order: IDs only grow.
  const auto found = std::ranges::lower_bound(records_, id, {}, &CommandRecord::id);
  return found != records_.end() && found->id == id ? &*found : nullptr;
}

CommandRecord* CommandLog::FindMutable(std::int32_t id) {
  return const_cast<CommandRecord*>(std::as_const(*this).Find(id));
}

}  // namespace fireswarm::server
