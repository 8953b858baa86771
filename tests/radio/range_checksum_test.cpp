// The parser's running checksum states (radio/src/range_checksum.hpp): four bytes at
// a time give every state the byte-by-byte CRC-16 gives, and any range's checksum
// comes from the states at its ends.
#include "range_checksum.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <random>
#include <vector>

#include "fireswarm/radio/frame.hpp"

namespace fireswarm::radio {
namespace {

std::vector<std::uint8_t> RandomBytes(std::size_t size, std::uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> byte(0, 255);
  std::vector<std::uint8_t> bytes(size);
  for (std::uint8_t& b : bytes) b = static_cast<std::uint8_t>(byte(rng));
  return bytes;
}

TEST(RangeChecksum, StatesExtendedFourBytesAtATimeAreTheByteByByteOnes) {
  const std::vector<std::uint8_t> bytes = RandomBytes(1'000, 7);
  // Every start and length of an extension, so every remainder of four is met.
  for (std::size_t from = 0; from < 8; ++from) {
    for (std::size_t to = from; to < from + 40; ++to) {
      std::vector<std::uint16_t> states(bytes.size() + 1, 0);
      states[from] = detail::kCrc16Initial;
      detail::ExtendChecksumStates(ChecksumMode::kCrc16, bytes.data(), states.data(), from, to);
      std::uint16_t crc = detail::kCrc16Initial;
      for (std::size_t i = from; i < to; ++i) {
        crc = detail::Crc16Step(crc, bytes[i]);
        ASSERT_EQ(states[i + 1], crc) << "from " << from << " to " << to << " at " << i;
      }
    }
  }
}

TEST(RangeChecksum, AnyRangesChecksumIsTheCrc16OfItsBytes) {
  const std::vector<std::uint8_t> bytes = RandomBytes(600, 11);
  std::vector<std::uint16_t> states(bytes.size() + 1, 0);
  states[0] = detail::kCrc16Initial;
  detail::ExtendChecksumStates(ChecksumMode::kCrc16, bytes.data(), states.data(), 0, bytes.size());
  for (std::size_t first = 0; first < 40; first += 3) {
    for (std::size_t last = first; last <= first + kMaxFrameSize && last <= bytes.size();
         last += 17) {
      const std::span<const std::uint8_t> range(bytes.data() + first, last - first);
      EXPECT_EQ(
          detail::ChecksumBetween(ChecksumMode::kCrc16, states[first], states[last], last - first),
          Crc16(range))
          << first << ".." << last;
    }
  }
}

}  // namespace
}  // namespace fireswarm::radio
