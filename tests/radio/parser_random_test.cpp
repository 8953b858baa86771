// Randomized stream tests of FrameParser: seeded streams of intact frames, garbage,
// truncated frames, bit flips and false preambles, fed in random chunks.
//
// A 16-bit check passes a random corrupted candidate with probability 2^-16 (XOR:
// 2^-8), so a random stream can hold a candidate that legitimately verifies and then
// hides intact frames behind it. The tests find those with an independent checksum
// implementation, exclude such streams from the strict check, and bound their count.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <optional>
#include <random>
#include <vector>

#include "fireswarm/radio/parser.hpp"
#include "radio/frame_capture.hpp"

namespace fireswarm::radio {
namespace {

using testing_frames::AsTuple;
using testing_frames::Bytes;
using testing_frames::CapturedFrame;
using testing_frames::ParseResult;
using Rng = std::mt19937_64;

// ---- An independent model of the protocol, written from docs/protocol.md ----

std::uint16_t BitwiseCrc16(const std::uint8_t* bytes, std::size_t size) {
  std::uint16_t crc = 0xFFFF;
  for (std::size_t i = 0; i < size; ++i) {
    crc = static_cast<std::uint16_t>(crc ^ (bytes[i] << 8));
    for (int bit = 0; bit < 8; ++bit) {
      crc = static_cast<std::uint16_t>((crc & 0x8000) != 0 ? (crc << 1) ^ 0x1021 : crc << 1);
    }
  }
  return crc;
}

bool PreambleAt(const Bytes& s, std::size_t at) {
  return at + 3 <= s.size() && s[at] == 0x70 && s[at + 1] == 0x96 && s[at + 2] == 0xAC;
}

// Size of the candidate at `at` (a preamble) when it lies wholly inside `s`.
std::optional<std::size_t> CompleteCandidateSize(const Bytes& s, std::size_t at,
                                                 ChecksumMode mode) {
  if (at + 6 > s.size()) return std::nullopt;
  const std::size_t size = 6 + s[at + 5] + (mode == ChecksumMode::kXor ? 1U : 2U);
  if (at + size > s.size()) return std::nullopt;
  return size;
}

bool CandidateVerifies(const Bytes& s, std::size_t at, std::size_t size, ChecksumMode mode) {
  const std::uint8_t* covered = s.data() + at + 3;
  if (mode == ChecksumMode::kXor) {
    std::uint8_t x = 0;
    for (std::size_t i = 0; i < size - 4; ++i) x = static_cast<std::uint8_t>(x ^ covered[i]);
    return x == s[at + size - 1];
  }
  const std::uint16_t crc = BitwiseCrc16(covered, size - 5);
  return (crc & 0xFF) == s[at + size - 2] && (crc >> 8) == s[at + size - 1];
}

// The parser's contract, parsing the whole buffer in one simple loop.
ParseResult ReferenceParse(const Bytes& s, ChecksumMode mode) {
  ParseResult result;
  result.stats.bytes = s.size();
  std::size_t at = 0;
  while (at < s.size()) {
    const std::optional<std::size_t> size =
        PreambleAt(s, at) ? CompleteCandidateSize(s, at, mode) : std::nullopt;
    if (size && CandidateVerifies(s, at, *size, mode)) {
      result.frames.push_back({at, s[at + 3], s[at + 4],
                               Bytes(s.begin() + static_cast<std::ptrdiff_t>(at + 6),
                                     s.begin() + static_cast<std::ptrdiff_t>(at + 6 + s[at + 5]))});
      ++result.stats.frames;
      at += *size;
      continue;
    }
    if (PreambleAt(s, at)) {
      bool preamble_inside = false;
      for (std::size_t q = at + 1; size && q < at + *size; ++q) preamble_inside |= PreambleAt(s, q);
      ++(!size || preamble_inside ? result.stats.truncated_frames : result.stats.checksum_errors);
    }
    ++result.stats.skipped_bytes;
    ++at;
  }
  return result;
}

// ---- Stream generation ----

struct TruncatedFrame {
  std::size_t offset = 0;
  std::size_t missing_bytes = 0;
};

struct GeneratedStream {
  Bytes bytes;
  std::vector<CapturedFrame> intact;      // every frame written unharmed, in order
  std::vector<TruncatedFrame> truncated;  // frames cut short, in order
};

// Complete candidates at preambles that start no intact frame, how many verify, and
// how many are expected to verify by chance. A random candidate passes a k-byte
// check with probability 256^-k, but a frame cut short by fewer bytes than its
// checksum still carries the first checksum bytes intact: a CRC-16 frame missing
// only its last byte passes with probability 1/256 (when the next byte matches).
struct CandidateCensus {
  std::size_t complete = 0;
  std::size_t verifying = 0;
  double expected_verifying = 0.0;
};

CandidateCensus CountNonIntactCandidates(const GeneratedStream& stream, ChecksumMode mode) {
  const Bytes& s = stream.bytes;
  const std::size_t checksum_size = mode == ChecksumMode::kXor ? 1 : 2;
  CandidateCensus census;
  std::size_t next_intact = 0;
  std::size_t next_truncated = 0;
  for (std::size_t at = 0; at < s.size(); ++at) {
    if (next_intact < stream.intact.size() && stream.intact[next_intact].offset == at) {
      ++next_intact;
      continue;
    }
    std::size_t random_checksum_bytes = checksum_size;
    if (next_truncated < stream.truncated.size() && stream.truncated[next_truncated].offset == at) {
      random_checksum_bytes =
          std::min(checksum_size, stream.truncated[next_truncated++].missing_bytes);
    }
    if (!PreambleAt(s, at)) continue;
    if (const std::optional<std::size_t> size = CompleteCandidateSize(s, at, mode)) {
      ++census.complete;
      census.expected_verifying += std::pow(256.0, -static_cast<double>(random_checksum_bytes));
      if (CandidateVerifies(s, at, *size, mode)) ++census.verifying;
    }
  }
  return census;
}

class StreamGenerator {
 public:
  StreamGenerator(ChecksumMode mode, std::uint64_t seed) : mode_(mode), rng_(seed) {}

  // 1-10 pieces: intact frames, garbage, truncated frames, frames with bit flips.
  GeneratedStream MixedStream() {
    GeneratedStream stream;
    const int pieces = Uniform(1, 10);
    for (int i = 0; i < pieces; ++i) {
      const int kind = Uniform(0, 99);
      if (kind < 40) {
        AppendIntact(stream);
      } else if (kind < 60) {
        AppendGarbage(stream.bytes, static_cast<std::size_t>(Uniform(1, 40)));
      } else if (kind < 80) {
        const Bytes frame = RandomFrame().second;
        const auto kept = static_cast<std::size_t>(Uniform(1, static_cast<int>(frame.size()) - 1));
        stream.truncated.push_back({stream.bytes.size(), frame.size() - kept});
        stream.bytes.insert(stream.bytes.end(), frame.begin(),
                            frame.begin() + static_cast<std::ptrdiff_t>(kept));
      } else {
        AppendWithBitFlips(stream.bytes, RandomFrame().second, Uniform(1, 3));
      }
    }
    return stream;
  }

  // `frames` intact frames with garbage runs between them making up about
  // `garbage_fraction` of the stream.
  GeneratedStream FramesWithGarbage(int frames, double garbage_fraction) {
    GeneratedStream stream;
    for (int i = 0; i < frames; ++i) {
      const std::size_t before = stream.bytes.size();
      AppendIntact(stream);
      const double frame_size = static_cast<double>(stream.bytes.size() - before);
      const double mean_garbage = frame_size * garbage_fraction / (1.0 - garbage_fraction);
      AppendGarbage(stream.bytes, static_cast<std::size_t>(std::uniform_real_distribution(
                                      0.0, 2.0 * mean_garbage)(rng_)));
    }
    return stream;
  }

  // Chunk sizes from 1 byte to several buffers.
  std::size_t ChunkSize() {
    const int kind = Uniform(0, 9);
    if (kind < 5) return static_cast<std::size_t>(Uniform(1, 8));
    if (kind < 9) return static_cast<std::size_t>(Uniform(9, 300));
    return static_cast<std::size_t>(Uniform(301, 9000));
  }

 private:
  int Uniform(int low, int high) { return std::uniform_int_distribution(low, high)(rng_); }
  std::uint8_t RandomByte() { return static_cast<std::uint8_t>(Uniform(0, 255)); }

  void AppendFalsePreamble(Bytes& out) {
    out.insert(out.end(), {0x70, 0x96, 0xAC});
    for (int i = Uniform(0, 3); i > 0; --i) out.push_back(RandomByte());  // header bytes
  }

  // Mostly short payloads, some long, some maximal; a quarter carry a false preamble.
  std::pair<CapturedFrame, Bytes> RandomFrame() {
    const int kind = Uniform(0, 19);
    const int size = kind < 14 ? Uniform(0, 48) : (kind < 19 ? Uniform(49, 255) : 255);
    CapturedFrame frame{0, RandomByte(), RandomByte(), Bytes(static_cast<std::size_t>(size))};
    for (std::uint8_t& byte : frame.data) byte = RandomByte();
    if (size >= 6 && Uniform(0, 3) == 0) {
      Bytes fake;
      AppendFalsePreamble(fake);
      const auto at = static_cast<std::size_t>(Uniform(0, size - static_cast<int>(fake.size())));
      std::copy(fake.begin(), fake.end(), frame.data.begin() + static_cast<std::ptrdiff_t>(at));
    }
    Bytes encoded;
    AppendFrame(encoded, frame.receiver, frame.message_id, frame.data, mode_);
    return {std::move(frame), std::move(encoded)};
  }

  void AppendIntact(GeneratedStream& stream) {
    auto [frame, encoded] = RandomFrame();
    frame.offset = stream.bytes.size();
    stream.bytes.insert(stream.bytes.end(), encoded.begin(), encoded.end());
    stream.intact.push_back(std::move(frame));
  }

  // `frame` with `flips` distinct bits flipped (a bit flipped twice would restore it).
  void AppendWithBitFlips(Bytes& out, Bytes frame, int flips) {
    const int bits = static_cast<int>(frame.size()) * 8;
    std::vector<int> flipped;
    while (static_cast<int>(flipped.size()) < flips) {
      const int bit = Uniform(0, bits - 1);
      if (std::find(flipped.begin(), flipped.end(), bit) != flipped.end()) continue;
      flipped.push_back(bit);
      frame[static_cast<std::size_t>(bit / 8)] ^= static_cast<std::uint8_t>(1U << (bit % 8));
    }
    out.insert(out.end(), frame.begin(), frame.end());
  }

  // Random bytes; some runs hold a false preamble or end in a preamble's first bytes.
  void AppendGarbage(Bytes& out, std::size_t size) {
    const std::size_t end = out.size() + size;
    const int kind = Uniform(0, 9);
    if (kind < 3) AppendFalsePreamble(out);
    while (out.size() < end) out.push_back(RandomByte());
    if (kind == 3) out.push_back(0x70);
    if (kind == 4) out.insert(out.end(), {0x70, 0x96});
  }

  ChecksumMode mode_;
  Rng rng_;
};

ParseResult ParseInRandomChunks(const Bytes& s, ChecksumMode mode, StreamGenerator& chunks) {
  return testing_frames::ParseInChunks(s, mode, [&chunks] { return chunks.ChunkSize(); });
}

std::uint64_t IntactBytes(const std::vector<CapturedFrame>& intact, ChecksumMode mode) {
  std::uint64_t bytes = 0;
  for (const CapturedFrame& frame : intact) bytes += FrameSize(frame.data.size(), mode);
  return bytes;
}

// Poisson upper bound far in the tail: mean + 6 sigma + 6 (false failure < 1e-8).
double CoincidenceBound(double expected) {
  return expected + 6.0 * std::sqrt(expected) + 6.0;
}

// Checks streams from `make` exactly against their intact frames, excluding (and
// bounding) streams where a non-intact candidate legitimately verifies.
template <typename MakeStream>
void ExpectEveryIntactFrameAndNothingElse(ChecksumMode mode, int streams, std::uint64_t seed,
                                          MakeStream make) {
  StreamGenerator generator(mode, seed);
  std::size_t excluded = 0;
  std::size_t mismatches = 0;
  double expected_coincidences = 0.0;
  ParserStats totals;
  for (int i = 0; i < streams; ++i) {
    const GeneratedStream stream = make(generator);
    const CandidateCensus census = CountNonIntactCandidates(stream, mode);
    expected_coincidences += census.expected_verifying;
    const ParseResult parsed = ParseInRandomChunks(stream.bytes, mode, generator);
    totals.checksum_errors += parsed.stats.checksum_errors;
    totals.truncated_frames += parsed.stats.truncated_frames;
    totals.frames += parsed.stats.frames;
    if (census.verifying > 0) {
      ++excluded;
      continue;
    }
    const bool exact =
        parsed.frames == stream.intact &&
        parsed.stats.skipped_bytes == stream.bytes.size() - IntactBytes(stream.intact, mode);
    if (!exact && ++mismatches <= 3) ADD_FAILURE() << "stream " << i << " (seed " << seed << ")";
  }
  EXPECT_EQ(mismatches, 0U);
  std::cout << "[ " << ToString(mode) << " ] " << streams << " streams, " << totals.frames
            << " frames, " << totals.checksum_errors << " checksum errors, "
            << totals.truncated_frames << " truncated; " << excluded
            << " streams excluded for a coincidentally verifying candidate (expected "
            << expected_coincidences << ", bound " << CoincidenceBound(expected_coincidences)
            << ")\n";
  EXPECT_LE(static_cast<double>(excluded), CoincidenceBound(expected_coincidences));
  EXPECT_GT(totals.checksum_errors, 0U);
  EXPECT_GT(totals.truncated_frames, 0U);
}

TEST(FrameParserRandom, FindsEveryIntactFrameAndNothingElseIn100kStreams) {
  ExpectEveryIntactFrameAndNothingElse(ChecksumMode::kCrc16, 100'000, 20240501,
                                       [](StreamGenerator& g) { return g.MixedStream(); });
}

TEST(FrameParserRandom, RandomChunkingEqualsWholeBufferReferenceParse) {
  for (const ChecksumMode mode : {ChecksumMode::kCrc16, ChecksumMode::kXor}) {
    StreamGenerator generator(mode, 77);
    int mismatches = 0;
    for (int i = 0; i < 20'000; ++i) {
      const GeneratedStream stream = generator.MixedStream();
      const ParseResult reference = ReferenceParse(stream.bytes, mode);
      const ParseResult parsed = ParseInRandomChunks(stream.bytes, mode, generator);
      const bool same =
          parsed.frames == reference.frames && AsTuple(parsed.stats) == AsTuple(reference.stats);
      if (!same && ++mismatches <= 3) ADD_FAILURE() << ToString(mode) << " stream " << i;
    }
    EXPECT_EQ(mismatches, 0) << ToString(mode);
  }
}

TEST(FrameParserRandom, LosesNoIntactFrameWithTenPercentGarbageBetweenFrames) {
  for (const ChecksumMode mode : {ChecksumMode::kCrc16, ChecksumMode::kXor}) {
    ExpectEveryIntactFrameAndNothingElse(mode, 2'000, 99, [](StreamGenerator& g) {
      return g.FramesWithGarbage(/*frames=*/40, /*garbage_fraction=*/0.10);
    });
  }
}

}  // namespace
}  // namespace fireswarm::radio
