// Message payload codec: one table of message specs, built at compile time from
// the Message variant and the per-message layouts in payload_layouts.hpp.
#include "fireswarm/radio/messages.hpp"

#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

#include "payload_io.hpp"
#include "payload_layouts.hpp"

namespace fireswarm::radio {
namespace {

// Message ID and name of each payload struct.
struct WireName {
  MessageId id;
  std::string_view name;
};
constexpr WireName NameOf(std::type_identity<Poll>) {
  return {MessageId::kPoll, "poll"};
}
constexpr WireName NameOf(std::type_identity<SlotSchedule>) {
  return {MessageId::kSlotSchedule, "slot_schedule"};
}
constexpr WireName NameOf(std::type_identity<Telemetry>) {
  return {MessageId::kTelemetry, "telemetry"};
}
constexpr WireName NameOf(std::type_identity<FireReport>) {
  return {MessageId::kFireReport, "fire_report"};
}
constexpr WireName NameOf(std::type_identity<FireReportAck>) {
  return {MessageId::kFireReportAck, "fire_report_ack"};
}
constexpr WireName NameOf(std::type_identity<MissionChunk>) {
  return {MessageId::kMissionChunk, "mission_chunk"};
}
constexpr WireName NameOf(std::type_identity<MissionAck>) {
  return {MessageId::kMissionAck, "mission_ack"};
}
constexpr WireName NameOf(std::type_identity<Command>) {
  return {MessageId::kCommand, "command"};
}
constexpr WireName NameOf(std::type_identity<CommandAck>) {
  return {MessageId::kCommandAck, "command_ack"};
}
constexpr WireName NameOf(std::type_identity<ParamRead>) {
  return {MessageId::kParamRead, "param_read"};
}
constexpr WireName NameOf(std::type_identity<ParamWrite>) {
  return {MessageId::kParamWrite, "param_write"};
}
constexpr WireName NameOf(std::type_identity<ParamValue>) {
  return {MessageId::kParamValue, "param_value"};
}
constexpr WireName NameOf(std::type_identity<Heartbeat>) {
  return {MessageId::kHeartbeat, "heartbeat"};
}

// Variable-length payloads: how many entries the struct holds, and its count field.
template <typename M>
constexpr std::size_t kMaxEntries = 0;
template <>
constexpr std::size_t kMaxEntries<SlotSchedule> = kMaxSlots;
template <>
constexpr std::size_t kMaxEntries<MissionChunk> = kMaxWaypointsPerChunk;

constexpr void SetEntryCount(SlotSchedule& m, std::uint8_t count) {
  m.slot_count = count;
}
constexpr void SetEntryCount(MissionChunk& m, std::uint8_t count) {
  m.waypoint_count = count;
}
constexpr void SetEntryCount(auto& /*fixed_size_message*/, std::uint8_t /*count*/) {}

// Payload bytes of an `M` with `entries` entries, counted from its layout.
template <typename M>
constexpr std::size_t WireSize(std::uint8_t entries) {
  M message{};
  SetEntryCount(message, entries);
  detail::PayloadSizeCounter counter;
  detail::Layout(counter, std::as_const(message));
  return counter.size();
}

template <typename M>
DecodeResult DecodeAs(std::span<const std::uint8_t> data) {
  M message{};
  detail::PayloadReader reader(data);
  detail::Layout(reader, message);
  // The length lies within the layout's bounds (checked by the caller), so a
  // length the layout did not consume exactly means a count that disagrees with it.
  if (reader.bad_value() || reader.length_mismatch()) return {std::nullopt, DecodeError::kBadValue};
  return {Message{std::move(message)}, DecodeError::kNone};
}

struct MessageSpec {
  MessageId id;
  std::string_view name;
  std::size_t fixed_size;   // payload bytes without entries
  std::size_t entry_size;   // bytes per entry; 0 for a fixed-size payload
  std::size_t max_entries;  // entries the struct can hold
  DecodeResult (*decode)(std::span<const std::uint8_t>);

  constexpr std::size_t max_size() const { return fixed_size + entry_size * max_entries; }
};

template <typename M>
constexpr MessageSpec SpecOf() {
  constexpr WireName kName = NameOf(std::type_identity<M>{});
  constexpr std::size_t kFixedSize = WireSize<M>(0);
  constexpr std::size_t kEntrySize = kMaxEntries<M> == 0 ? 0 : WireSize<M>(1) - kFixedSize;
  constexpr MessageSpec spec{kName.id,   kName.name,     kFixedSize,
                             kEntrySize, kMaxEntries<M>, &DecodeAs<M>};
  static_assert(spec.max_size() <= kMaxDataSize, "a payload must fit one frame");
  return spec;
}

template <std::size_t... Index>
constexpr auto MakeSpecs(std::index_sequence<Index...>) {
  return std::array{SpecOf<std::variant_alternative_t<Index, Message>>()...};
}

// In the order of the Message variant's alternatives: kSpecs[message.index()].
constexpr auto kSpecs = MakeSpecs(std::make_index_sequence<std::variant_size_v<Message>>{});

const MessageSpec* FindSpec(std::uint8_t message_id) {
  for (const MessageSpec& spec : kSpecs) {
    if (static_cast<std::uint8_t>(spec.id) == message_id) return &spec;
  }
  return nullptr;
}

}  // namespace

std::optional<std::string_view> MessageName(std::uint8_t message_id) {
  const MessageSpec* spec = FindSpec(message_id);
  if (spec == nullptr) return std::nullopt;
  return spec->name;
}

MessageId IdOf(const Message& message) {
  return kSpecs[message.index()].id;
}

const MessageHeader& HeaderOf(const Message& message) {
  return std::visit([](const auto& m) -> const MessageHeader& { return m.header; }, message);
}

std::string_view ToString(DecodeError error) {
  switch (error) {
    case DecodeError::kNone:
      return "none";
    case DecodeError::kUnknownMessageId:
      return "unknown_message_id";
    case DecodeError::kTooShort:
      return "too_short";
    case DecodeError::kTooLong:
      return "too_long";
    case DecodeError::kBadValue:
      return "bad_value";
  }
  return "unknown";
}

DecodeResult DecodePayload(std::uint8_t message_id, std::span<const std::uint8_t> data) {
  const MessageSpec* spec = FindSpec(message_id);
  if (spec == nullptr) return {std::nullopt, DecodeError::kUnknownMessageId};
  if (data.size() < spec->fixed_size) return {std::nullopt, DecodeError::kTooShort};
  if (data.size() > spec->max_size()) return {std::nullopt, DecodeError::kTooLong};
  return spec->decode(data);
}

void EncodePayload(const Message& message, std::vector<std::uint8_t>& out) {
  const std::size_t start = out.size();
  try {
    std::visit(
        [&out](const auto& m) {
          detail::PayloadWriter writer(out);
          detail::Layout(writer, m);
        },
        message);
  } catch (...) {
    out.resize(start);  // leave `out` as it was
    throw;
  }
  // Unreachable with the capacities checked above (kSpecs' static_assert), kept as
  // the codec's promise: a payload never exceeds a frame.
  if (out.size() - start > kMaxDataSize) {
    out.resize(start);
    throw std::invalid_argument("EncodePayload: payload exceeds 255 bytes");
  }
}

void AppendMessageFrame(std::vector<std::uint8_t>& out, std::uint8_t receiver,
                        const Message& message, ChecksumMode mode) {
  std::vector<std::uint8_t> payload;
  payload.reserve(kMaxDataSize);
  EncodePayload(message, payload);
  AppendFrame(out, receiver, static_cast<std::uint8_t>(IdOf(message)), payload, mode);
}

std::size_t PayloadSize(MessageId id, std::size_t entries) {
  const MessageSpec* spec = FindSpec(static_cast<std::uint8_t>(id));
  if (spec == nullptr) {
    throw std::invalid_argument("PayloadSize: unknown message ID " +
                                std::to_string(static_cast<int>(id)));
  }
  return spec->fixed_size + spec->entry_size * entries;
}

}  // namespace fireswarm::radio
