// What both ends of the poll-and-answer discipline (seed 5.3.1.1) share: the burst
// a pure core asks its link to send, the link mode, and the timing rules of a turn.
// The master scheduler and the vehicle endpoint compute slot times and reply sizes
// here, so the two sides cannot disagree on them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "fireswarm/radio/frame.hpp"
#include "fireswarm/radio/messages.hpp"
#include "fireswarm/radio/time.hpp"

namespace fireswarm::radio {

/// Bytes a core wants on the air, starting exactly at `start` (a simulated link) or
/// as soon as possible (a real link, whose modem adds the turnaround).
struct Burst {
  Nanos start{0};
  std::vector<std::uint8_t> bytes;
};

/// How the server hands out turns.
enum class LinkMode : std::uint8_t {
  /// One exchange at a time: a Poll, or a request, gives one vehicle the turn.
  kPoll,
  /// One broadcast SlotSchedule grants several vehicles consecutive reply slots;
  /// requests are answered in a kAck slot, never right after the request.
  kSlots,
};

/// "poll" or "slots".
std::string_view ToString(LinkMode mode);
/// Parses "poll" or "slots"; nullopt for anything else.
std::optional<LinkMode> ParseLinkMode(std::string_view text);

/// Serial timing of one link: airtime per byte and the radios' turnaround.
struct LinkTiming {
  int baud = 57'600;                               ///< bits/s
  int bits_per_byte = kBitsPerByte8N1;             ///< 10 for 8N1
  Nanos turnaround{std::chrono::milliseconds(5)};  ///< receive-to-transmit switch time
  /// Time `bytes` bytes occupy on the air.
  Nanos AirtimeOf(std::size_t bytes) const { return Airtime(bytes, baud, bits_per_byte); }
};

/// Bytes on the air of a frame carrying message `id` (with `entries` slots or
/// waypoints for the variable-length messages).
std::size_t MessageFrameSize(MessageId id, ChecksumMode mode, std::size_t entries = 0);

/// The answer a vehicle sends to a request: kCommand -> kCommandAck, kMissionChunk ->
/// kMissionAck, kParamRead and kParamWrite -> kParamValue; nullopt for other IDs.
std::optional<MessageId> AckIdFor(MessageId request);

/// Start of slot `index` of `schedule` whose frame ended at `schedule_end`:
/// end + first_slot_delay + sum over j < index of (Airtime(slot_bytes_j) + guard).
/// Precondition: index < schedule.slot_count.
Nanos SlotStart(const SlotSchedule& schedule, std::size_t index, Nanos schedule_end,
                const LinkTiming& timing);

/// End of slot `index`: its start plus Airtime(slot_bytes). Precondition as SlotStart.
Nanos SlotEnd(const SlotSchedule& schedule, std::size_t index, Nanos schedule_end,
              const LinkTiming& timing);

}  // namespace fireswarm::radio
