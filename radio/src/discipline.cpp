#include "fireswarm/radio/discipline.hpp"

#include <cassert>

namespace fireswarm::radio {

std::string_view ToString(LinkMode mode) {
  return mode == LinkMode::kPoll ? "poll" : "slots";
}

std::optional<LinkMode> ParseLinkMode(std::string_view text) {
  if (text == "poll") return LinkMode::kPoll;
  if (text == "slots") return LinkMode::kSlots;
  return std::nullopt;
}

std::size_t MessageFrameSize(MessageId id, ChecksumMode mode, std::size_t entries) {
  return FrameSize(PayloadSize(id, entries), mode);
}

std::optional<MessageId> AckIdFor(MessageId request) {
  switch (request) {
    case MessageId::kCommand:
      return MessageId::kCommandAck;
    case MessageId::kMissionChunk:
      return MessageId::kMissionAck;
    case MessageId::kParamRead:
    case MessageId::kParamWrite:
      return MessageId::kParamValue;
    default:
      return std::nullopt;
  }
}

Nanos SlotStart(const SlotSchedule& schedule, std::size_t index, Nanos schedule_end,
                const LinkTiming& timing) {
  assert(index < schedule.slot_count);
  const Nanos guard = std::chrono::microseconds(schedule.guard_us);
  Nanos start = schedule_end + std::chrono::microseconds(schedule.first_slot_delay_us);
  for (std::size_t j = 0; j < index; ++j) {
    start += timing.AirtimeOf(schedule.slots[j].slot_bytes) + guard;
  }
  return start;
}

Nanos SlotEnd(const SlotSchedule& schedule, std::size_t index, Nanos schedule_end,
              const LinkTiming& timing) {
  return SlotStart(schedule, index, schedule_end, timing) +
         timing.AirtimeOf(schedule.slots[index].slot_bytes);
}

}  // namespace fireswarm::radio
