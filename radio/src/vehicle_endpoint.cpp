// The vehicle side of the discipline. Replies are built when the turn is received,
// from the state held at that moment, and handed back with their exact start time.
#include "fireswarm/radio/vehicle_endpoint.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <utility>

namespace fireswarm::radio {
namespace {

constexpr std::size_t kMaxPendingCount = 255;  // Telemetry.pending_reports saturates here

void SetHeader(Message& message, MessageHeader header) {
  std::visit([&](auto& payload) { payload.header = header; }, message);
}

}  // namespace

void VehicleEndpointConfig::Validate() const {
  if (id < kFirstVehicleId || id > kLastVehicleId) {
    throw std::invalid_argument("VehicleEndpointConfig.id must be in 1..254, got " +
                                std::to_string(id));
  }
  if (timing.baud <= 0) {
    throw std::invalid_argument("VehicleEndpointConfig.timing.baud must be > 0, got " +
                                std::to_string(timing.baud));
  }
  if (timing.bits_per_byte <= 0) {
    throw std::invalid_argument("VehicleEndpointConfig.timing.bits_per_byte must be > 0");
  }
  if (timing.turnaround < Nanos::zero()) {
    throw std::invalid_argument("VehicleEndpointConfig.timing.turnaround must be >= 0");
  }
  if (max_queued_reports == 0) {
    throw std::invalid_argument("VehicleEndpointConfig.max_queued_reports must be > 0");
  }
  if (checksum == ChecksumMode::kSecure && !security) {
    throw std::invalid_argument("VehicleEndpointConfig.security must be set in secure mode");
  }
}

VehicleEndpoint::VehicleEndpoint(const VehicleEndpointConfig& config,
                                 VehicleRequestHandler& handler)
    : config_(config), handler_(handler), parser_(config.checksum) {
  config_.Validate();
}

void VehicleEndpoint::SetTelemetry(const Telemetry& telemetry) {
  telemetry_ = telemetry;
}

std::uint16_t VehicleEndpoint::QueueFireReport(const FireReport& report) {
  if (reports_.size() >= config_.max_queued_reports) {
    reports_.pop_front();
    ++stats_.reports_dropped;
  }
  reports_.push_back(report);
  reports_.back().report_id = next_report_id_;
  ++stats_.reports_queued;
  ++state_changes_;
  return next_report_id_++;
}

VehicleEndpointState VehicleEndpoint::state() const {
  return VehicleEndpointState{next_report_id_, next_sequence_,
                              std::vector<FireReport>(reports_.begin(), reports_.end()),
                              last_request_};
}

void VehicleEndpoint::Restore(const VehicleEndpointState& state) {
  next_report_id_ = state.next_report_id;
  next_sequence_ = state.next_sequence;
  reports_.assign(state.reports.begin(), state.reports.end());
  while (reports_.size() > config_.max_queued_reports) {
    reports_.pop_front();
    ++stats_.reports_dropped;
  }
  last_request_ = state.last_request;
  ++state_changes_;
}

std::vector<Burst> VehicleEndpoint::OnReceive(Nanos now, std::span<const std::uint8_t> bytes) {
  std::vector<Burst> out;
  // Frames are handled in stream order, so an ack that precedes a turn in the same
  // burst already removed its report when the turn is answered.
  for (const Received& frame : Parse(now, bytes)) Handle(frame, now, out);
  return out;
}

std::vector<VehicleEndpoint::Received> VehicleEndpoint::Parse(Nanos now,
                                                              std::span<const std::uint8_t> bytes) {
  std::vector<Received> frames;
  // The last byte fed arrived at `now`; a frame followed by k more bytes ended
  // Airtime(k) earlier. A slot schedule counts its slots from its own end.
  const std::uint64_t stream_begin = parser_.stats().bytes;
  const std::uint64_t stream_end = stream_begin + bytes.size();
  parser_.Feed(bytes, [&](const FrameView& frame) {
    const bool for_me = frame.receiver == config_.id;
    if (!for_me && frame.receiver != kBroadcastId) return;
    if (for_me) {
      ++stats_.frames_for_me;
      stats_.payload_bytes_for_me += frame.data.size();
    } else {
      ++stats_.broadcast_frames;
    }
    // Secure mode: nothing unauthenticated, replayed or keyed for another vehicle
    // gets past here (the security object counts why).
    const OpenedData opened =
        OpenFrameData(frame, config_.checksum, config_.security.get(), opened_);
    if (opened.status != OpenStatus::kOk) {
      if (opened.status != OpenStatus::kNotForMe) ++stats_.refused_frames;
      return;
    }
    DecodeResult decoded = DecodePayload(frame.message_id, opened.data);
    if (!decoded.message) {
      ++stats_.decode_errors;
      return;
    }
    const std::uint64_t frame_end = frame.offset + FrameSize(frame.data.size(), config_.checksum);
    // A frame can surface only now although its bytes came earlier: a corrupted
    // length before it made the parser wait. Its turn has passed.
    const bool fresh = frame_end > stream_begin;
    const Nanos after = config_.timing.AirtimeOf(static_cast<std::size_t>(stream_end - frame_end));
    frames.push_back(Received{std::move(*decoded.message), now - after, for_me, fresh});
  });
  return frames;
}

void VehicleEndpoint::Handle(const Received& frame, Nanos now, std::vector<Burst>& out) {
  const Nanos reply_start = now + config_.timing.turnaround;
  const Message& message = frame.message;
  if (const auto* schedule = std::get_if<SlotSchedule>(&message)) {
    if (frame.fresh) {
      HandleSchedule(*schedule, frame.frame_end, now, out);
    } else {
      ++stats_.turns_skipped;
    }
    return;
  }
  if (const auto* ack = std::get_if<FireReportAck>(&message)) {
    if (ack->vehicle != config_.id) return;
    const auto acked = std::find_if(reports_.begin(), reports_.end(), [&](const FireReport& r) {
      return r.report_id == ack->report_id;
    });
    if (acked != reports_.end()) {
      reports_.erase(acked);
      ++stats_.reports_acked;
      ++state_changes_;
    }
    return;
  }
  // Everything else is a turn or a request meant for one vehicle: a broadcast one
  // would make every vehicle answer at once.
  if (!frame.for_me) return;
  if (const auto* poll = std::get_if<Poll>(&message)) {
    if (!frame.fresh) {
      ++stats_.turns_skipped;
    } else if (std::optional<Message> reply = ReplyFor(poll->reply, 0)) {
      Send(std::move(*reply), reply_start, kMaxFrameSize, now, out);
    }
    return;
  }
  if (!AckIdFor(IdOf(message))) return;
  // A stale request is still executed (or recognised as a retry); only its turn has passed.
  HandleRequest(message);
  if (!frame.fresh) {
    ++stats_.turns_skipped;
  } else if (config_.mode == LinkMode::kPoll) {
    Send(last_request_->ack, reply_start, kMaxFrameSize, now, out);
  }
}

void VehicleEndpoint::HandleRequest(const Message& request) {
  const MessageId id = IdOf(request);
  const std::uint16_t sequence = HeaderOf(request).sequence;
  // A retry carries the sequence of the original: executing it again could, say,
  // restart a mission; the cached ack is what the server missed.
  if (last_request_ && last_request_->id == id && last_request_->sequence == sequence) {
    ++stats_.duplicate_requests;
    return;
  }
  last_request_ = HandledRequest{id, sequence, AckFor(request)};
  ++stats_.requests_handled;
  ++state_changes_;
}

Message VehicleEndpoint::AckFor(const Message& request) {
  if (const auto* command = std::get_if<Command>(&request)) {
    return CommandAck{{}, command->header.sequence, command->type, handler_.OnCommand(*command)};
  }
  if (const auto* chunk = std::get_if<MissionChunk>(&request)) {
    return MissionAck{{}, chunk->mission_id, chunk->chunk_index, handler_.OnMissionChunk(*chunk)};
  }
  ParamValue value;
  if (const auto* read = std::get_if<ParamRead>(&request)) {
    value = handler_.OnParamRead(*read);
    value.param_id = read->param_id;
  } else {
    const auto& write = std::get<ParamWrite>(request);
    value = handler_.OnParamWrite(write);
    value.param_id = write.param_id;
  }
  return value;
}

void VehicleEndpoint::HandleSchedule(const SlotSchedule& schedule, Nanos schedule_end, Nanos now,
                                     std::vector<Burst>& out) {
  // The k-th report slot of one schedule carries the k-th oldest report, so
  // several slots drain the queue instead of repeating the oldest.
  std::size_t report_index = 0;
  const std::span<const Slot> slots = schedule.active();
  for (std::size_t k = 0; k < slots.size(); ++k) {
    const Slot& slot = slots[k];
    if (slot.receiver != config_.id) continue;
    const std::size_t index = slot.reply == ReplyKind::kFireReport ? report_index++ : 0;
    std::optional<Message> reply = ReplyFor(slot.reply, index);
    if (!reply) continue;
    Send(std::move(*reply), SlotStart(schedule, k, schedule_end, config_.timing), slot.slot_bytes,
         now, out);
  }
}

std::optional<Message> VehicleEndpoint::ReplyFor(ReplyKind kind, std::size_t report_index) const {
  if (kind == ReplyKind::kAck) {
    if (!last_request_) return std::nullopt;
    return last_request_->ack;
  }
  if (kind == ReplyKind::kFireReport && report_index < reports_.size()) {
    return reports_[report_index];
  }
  // A telemetry turn, or a report turn with nothing (left) to report: telemetry
  // tells the server how many reports are still pending.
  Telemetry telemetry = telemetry_;
  telemetry.flags = static_cast<std::uint8_t>(telemetry.flags & ~telemetry_flags::kReportPending);
  if (!reports_.empty()) telemetry.flags |= telemetry_flags::kReportPending;
  telemetry.pending_reports =
      static_cast<std::uint8_t>(std::min(reports_.size(), kMaxPendingCount));
  handler_.CompleteTelemetry(telemetry);
  return telemetry;
}

void VehicleEndpoint::Send(Message reply, Nanos start, std::size_t max_bytes, Nanos now,
                           std::vector<Burst>& out) {
  SetHeader(reply, MessageHeader{config_.id, next_sequence_});
  std::vector<std::uint8_t> frame;
  if (AppendFrameFor(frame, kServerId, reply, config_.checksum, config_.security.get()) !=
      SealStatus::kOk) {
    ++stats_.seal_failures;
    return;
  }
  // Half duplex, as the channel enforces it: a radio that is receiving needs the
  // turnaround; one still transmitting may only continue after its last byte.
  const bool transmitting = now < transmitting_until_;
  const bool too_early =
      transmitting ? start < transmitting_until_ : start < now + config_.timing.turnaround;
  const bool back_to_back =
      transmitting && !out.empty() && start < transmitting_until_ &&
      out.back().start + config_.timing.AirtimeOf(out.back().bytes.size()) == transmitting_until_;
  if (frame.size() > max_bytes || (too_early && !back_to_back)) {
    ++stats_.turns_skipped;
    return;
  }
  ++next_sequence_;
  ++stats_.replies_sent;
  ++state_changes_;
  if (back_to_back) {
    // Two turns at the same instant (a request and a Poll in one burst): one burst.
    out.back().bytes.insert(out.back().bytes.end(), frame.begin(), frame.end());
  } else {
    out.push_back(Burst{start, std::move(frame)});
  }
  transmitting_until_ = out.back().start + config_.timing.AirtimeOf(out.back().bytes.size());
}

}  // namespace fireswarm::radio
