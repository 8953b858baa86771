// Streaming APOne frame parser (seed 5.3.4): preamble search, length, checksum.
//
// Every decision is taken only when the bytes it depends on are buffered (or the
// stream has ended), so any chunking of the same stream gives the same frames and
// the same statistics as parsing the whole stream at once.
#include "fireswarm/radio/parser.hpp"

#include <algorithm>
#include <cstring>

#include "range_checksum.hpp"

namespace fireswarm::radio {
namespace {

// Whether a preamble starts at a position, as far as the buffered bytes tell.
enum class PreambleMatch : std::uint8_t { kNo, kYes, kMaybe };

// Compares the bytes in [at, end) with the preamble: kMaybe when every buffered
// byte matches but the preamble runs past `end`.
PreambleMatch PreambleAt(const std::uint8_t* at, const std::uint8_t* end) {
  for (std::size_t i = 0; i < kPreamble.size(); ++i) {
    if (at + i == end) return PreambleMatch::kMaybe;
    if (at[i] != kPreamble[i]) return PreambleMatch::kNo;
  }
  return PreambleMatch::kYes;
}

// Where the search for another preamble inside a failed candidate stopped.
struct InnerPreamble {
  PreambleMatch match = PreambleMatch::kNo;
  const std::uint8_t* at = nullptr;  // the preamble (kYes) or the first partial one (kMaybe)
};

// Whether another preamble starts in [first, last) of a candidate; bytes up to
// `end` are buffered (a preamble starting near `last` may run past it). The search
// stops at the first preamble, which is the next candidate, so over a stream the
// searches cover each byte about once; `examined_bytes` counts what was searched.
InnerPreamble PreambleStartsIn(const std::uint8_t* first, const std::uint8_t* last,
                               const std::uint8_t* end, std::uint64_t& examined_bytes) {
  InnerPreamble result;
  const std::uint8_t* at = first;
  while (at < last) {
    const void* hit = std::memchr(at, kPreamble[0], static_cast<std::size_t>(last - at));
    if (hit == nullptr) {
      at = last;
      break;
    }
    at = static_cast<const std::uint8_t*>(hit);
    const PreambleMatch match = PreambleAt(at, end);
    if (match == PreambleMatch::kYes) {
      result = {match, at};
      break;
    }
    if (match == PreambleMatch::kMaybe && result.match == PreambleMatch::kNo) result = {match, at};
    ++at;
  }
  examined_bytes += static_cast<std::uint64_t>(at - first);
  return result;
}

// The checksum a fully buffered frame carries after its covered bytes.
std::uint16_t ReceivedChecksum(const std::uint8_t* checksum, ChecksumMode mode) {
  if (mode == ChecksumMode::kXor) return checksum[0];
  return static_cast<std::uint16_t>(checksum[0] | (checksum[1] << 8));
}

}  // namespace

FrameParser::FrameParser(ChecksumMode mode) : mode_(mode) {
  // After Next() returns nullopt at most a maximal candidate plus two look-ahead
  // bytes stay buffered, so Push() always finds room after moving them to the front.
  static_assert(kBufferSize >= 2 * (kMaxFrameSize + 2));
}

std::size_t FrameParser::Push(std::span<const std::uint8_t> bytes) {
  if (begin_ == end_) {
    begin_ = end_ = 0;
    ForgetStates();
  } else if (kBufferSize - end_ < bytes.size() && begin_ > 0) {
    std::memmove(buffer_.data(), buffer_.data() + begin_, end_ - begin_);
    // The running states of the kept bytes move with them: a state depends only on
    // the bytes before it since states_first_, not on where they sit.
    if (states_first_ != kNoStates && states_last_ >= begin_) {
      const std::size_t first = std::max(states_first_, begin_);
      std::memmove(states_.data() + first - begin_, states_.data() + first,
                   (states_last_ - first + 1) * sizeof(std::uint16_t));
      states_first_ = first - begin_;
      states_last_ -= begin_;
    } else {
      ForgetStates();
    }
    end_ -= begin_;
    begin_ = 0;
  }
  const std::size_t taken = std::min(bytes.size(), kBufferSize - end_);
  if (taken > 0) std::memcpy(buffer_.data() + end_, bytes.data(), taken);
  end_ += taken;
  stats_.bytes += taken;
  return taken;
}

std::uint16_t FrameParser::RangeChecksum(std::size_t first, std::size_t last) {
  // Candidates come in stream order, so the states usually cover `first` already;
  // otherwise they restart there, leaving out the bytes in no candidate.
  if (states_first_ == kNoStates || first < states_first_ || first > states_last_) {
    states_first_ = states_last_ = first;
    states_[first] = detail::InitialChecksumState(mode_);
  }
  if (last > states_last_) {
    detail::ExtendChecksumStates(mode_, buffer_.data(), states_.data(), states_last_, last);
    stats_.examined_bytes += last - states_last_;
    states_last_ = last;
  }
  return detail::ChecksumBetween(mode_, states_[first], states_[last], last - first);
}

std::optional<FrameView> FrameParser::Next() {
  return Scan(/*end_of_stream=*/false);
}

std::optional<FrameView> FrameParser::Scan(bool end_of_stream) {
  const std::uint8_t* const buffer = buffer_.data();
  const std::uint8_t* const end = buffer + end_;
  const auto skip_to = [&](std::size_t position) {
    stats_.skipped_bytes += position - begin_;
    begin_ = position;
  };
  while (begin_ < end_) {
    // Hostile streams put a candidate right where the last one's search stopped.
    const void* hit = buffer[begin_] == kPreamble[0]
                          ? buffer + begin_
                          : std::memchr(buffer + begin_, kPreamble[0], end_ - begin_);
    if (hit == nullptr) {
      skip_to(end_);
      break;
    }
    const auto start = static_cast<std::size_t>(static_cast<const std::uint8_t*>(hit) - buffer);
    skip_to(start);
    const std::uint8_t* const frame = buffer + start;
    const std::size_t available = end_ - start;

    const PreambleMatch preamble = PreambleAt(frame, end);
    if (preamble == PreambleMatch::kNo) {
      skip_to(start + 1);
      continue;
    }
    if (preamble == PreambleMatch::kMaybe) {
      // At most two trailing bytes that may begin a preamble wait for more bytes.
      if (!end_of_stream) return std::nullopt;
      skip_to(end_);
      break;
    }

    const std::size_t data_size = available >= kHeaderSize ? frame[kHeaderSize - 1] : 0;
    const std::size_t frame_size = FrameSize(data_size, mode_);
    if (available < kHeaderSize || available < frame_size) {
      if (!end_of_stream) return std::nullopt;  // wait for the rest of the candidate
      ++stats_.truncated_frames;
      skip_to(start + 1);
      continue;
    }

    // The checksum covers receiver ID, message ID, length and the body after them.
    const std::size_t checksum_at = start + frame_size - ChecksumSize(mode_);
    if (RangeChecksum(start + kPreamble.size(), checksum_at) ==
        ReceivedChecksum(buffer + checksum_at, mode_)) {
      ++stats_.frames;
      begin_ = start + frame_size;
      // Secure mode: the encrypted data sits behind key ID and counter.
      const std::size_t data_at = mode_ == ChecksumMode::kSecure ? kSecureHeaderSize : 0;
      return FrameView{.receiver = frame[3],
                       .message_id = frame[4],
                       .data = {frame + kHeaderSize + data_at, data_size},
                       .sealed = mode_ == ChecksumMode::kSecure
                                     ? std::span<const std::uint8_t>(
                                           frame + kPreamble.size(),
                                           frame_size - kPreamble.size() - ChecksumSize(mode_))
                                     : std::span<const std::uint8_t>{},
                       .offset = stats_.bytes - available};
    }

    // A failed candidate: truncated when another preamble starts inside it (its
    // sender was cut off and a new frame began), else corrupted. The scan goes on
    // at the first preamble after its first byte, so a frame inside it is not lost.
    // A search that stopped at a partial preamble at the end of the buffer resumes
    // there when the same candidate is tried again with more bytes.
    const std::uint64_t candidate_offset = stats_.bytes - available;
    const std::size_t searched = candidate_offset == resume_.candidate_offset ? resume_.searched : 0;
    const InnerPreamble inner =
        PreambleStartsIn(frame + 1 + searched, frame + frame_size, end, stats_.examined_bytes);
    if (inner.match == PreambleMatch::kMaybe && !end_of_stream) {
      resume_ = {.candidate_offset = candidate_offset,
                 .searched = static_cast<std::size_t>(inner.at - (frame + 1))};
      return std::nullopt;
    }
    if (inner.match == PreambleMatch::kYes) {
      ++stats_.truncated_frames;
    } else {
      ++stats_.checksum_errors;
    }
    // The search has shown that no preamble starts before the one it found (or, when
    // it found none, inside the candidate), so the rescan resumes there directly.
    if (inner.match == PreambleMatch::kYes) {
      skip_to(static_cast<std::size_t>(inner.at - buffer));
    } else if (inner.match == PreambleMatch::kNo) {
      skip_to(start + frame_size);
    } else {
      skip_to(start + 1);
    }
  }
  return std::nullopt;
}

void FrameParser::Reset() {
  stats_ = {};
  begin_ = end_ = 0;
  ForgetStates();
  resume_ = {};
}

}  // namespace fireswarm::radio
