#include "fireswarm/radio/frame.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <stdexcept>
#include <string_view>
#include <utility>
#include <vector>

#include "fireswarm/radio/time.hpp"

namespace fireswarm::radio {
namespace {

using Bytes = std::vector<std::uint8_t>;

TEST(Airtime, HundredBytesAt57600BaudTake17_36ms) {
  // 57,600 baud 8N1 carries 5,760 bytes/s, not 7,200: 100 bytes = 17.3611 ms.
  EXPECT_EQ(Airtime(100, 57'600).count(), 17'361'112);
  EXPECT_EQ(Airtime(5'760, 57'600), std::chrono::seconds(1));
}

TEST(ChecksumMode, NamesRoundTripAndUnknownNamesAreRejected) {
  for (const ChecksumMode mode :
       {ChecksumMode::kXor, ChecksumMode::kCrc16, ChecksumMode::kSecure}) {
    EXPECT_EQ(ParseChecksumMode(ToString(mode)), mode);
  }
  EXPECT_EQ(ToString(ChecksumMode::kSecure), "secure");
  EXPECT_EQ(ToString(ChecksumMode::kXor), "xor");
  EXPECT_EQ(ToString(ChecksumMode::kCrc16), "crc16");
  EXPECT_FALSE(ParseChecksumMode("CRC16").has_value());
  EXPECT_FALSE(ParseChecksumMode("").has_value());
}

TEST(FrameSize, HeaderDataAndChecksum) {
  EXPECT_EQ(FrameSize(0, ChecksumMode::kXor), 7U);
  EXPECT_EQ(FrameSize(0, ChecksumMode::kCrc16), 8U);
  EXPECT_EQ(FrameSize(kMaxDataSize, ChecksumMode::kCrc16), 263U);
  EXPECT_EQ(FrameSize(0, ChecksumMode::kSecure), 21U);  // + key ID, counter (4), tag (8)
  EXPECT_EQ(kMaxFrameSize, 276U);
}

TEST(Crc16, CcittFalseCheckValue) {
  constexpr std::string_view kCheckInput = "123456789";
  const Bytes input(kCheckInput.begin(), kCheckInput.end());
  EXPECT_EQ(Crc16(input), 0x29B1);
  EXPECT_EQ(Crc16({}), 0xFFFF);  // the initial value, untouched
}

TEST(Xor8, XorsEveryByte) {
  EXPECT_EQ(Xor8({}), 0);
  EXPECT_EQ(Xor8(Bytes{0x0F, 0xF0, 0x01}), 0xFE);
}

// Seed Table 5.3 frame carrying the seed's Table 5.5 sample data (10..15) with the
// seed's example attitude message ID 0x1D, to receiver 3 (seed 5.3.4.2).
const Bytes kSeedData{10, 11, 12, 13, 14, 15};

TEST(AppendFrame, SeedTable5_3ExampleInXorMode) {
  Bytes out;
  AppendFrame(out, 3, 0x1D, kSeedData, ChecksumMode::kXor);
  // 03 ^ 1D ^ 06 ^ 0A ^ 0B ^ 0C ^ 0D ^ 0E ^ 0F = 0x19.
  const Bytes expected{0x70, 0x96, 0xAC, 0x03, 0x1D, 0x06, 0x0A,
                       0x0B, 0x0C, 0x0D, 0x0E, 0x0F, 0x19};
  EXPECT_EQ(out, expected);
}

TEST(AppendFrame, SeedTable5_3ExampleInCrc16ModeLowByteFirst) {
  Bytes out;
  AppendFrame(out, 3, 0x1D, kSeedData, ChecksumMode::kCrc16);
  // CRC-16/CCITT-FALSE of 03 1D 06 0A 0B 0C 0D 0E 0F is 0x4ABD.
  const Bytes expected{0x70, 0x96, 0xAC, 0x03, 0x1D, 0x06, 0x0A,
                       0x0B, 0x0C, 0x0D, 0x0E, 0x0F, 0xBD, 0x4A};
  EXPECT_EQ(out, expected);
}

TEST(AppendFrame, AppendsAfterExistingBytesAndChecksumSkipsPreamble) {
  Bytes out{0xEE};
  AppendFrame(out, kBroadcastId, 0x50, {}, ChecksumMode::kXor);
  const Bytes expected{0xEE, 0x70, 0x96, 0xAC, 0xFF, 0x50, 0x00, 0xFF ^ 0x50};
  EXPECT_EQ(out, expected);
}

// Regression: an exact reserve() per frame reallocated the buffer on every append,
// so building a long capture or burst was quadratic.
TEST(AppendFrame, ManyAppendsGrowTheBufferGeometrically) {
  constexpr int kFrames = 20'000;
  const Bytes data(41, 0x5A);
  Bytes out;
  int reallocations = 0;
  for (int i = 0; i < kFrames; ++i) {
    const std::size_t capacity = out.capacity();
    AppendFrame(out, 1, 0x10, data, ChecksumMode::kCrc16);
    if (out.capacity() != capacity) ++reallocations;
  }
  EXPECT_EQ(out.size(), kFrames * FrameSize(data.size(), ChecksumMode::kCrc16));
  EXPECT_LT(reallocations, 40) << "one reallocation per append is quadratic";
}

TEST(AppendFrame, AcceptsMaximalDataAndRejectsLonger) {
  Bytes out;
  AppendFrame(out, 1, 2, Bytes(kMaxDataSize, 0xAB), ChecksumMode::kCrc16);
  EXPECT_EQ(out.size(), FrameSize(kMaxDataSize, ChecksumMode::kCrc16));
  EXPECT_EQ(out[5], 255);
  out.clear();
  EXPECT_THROW(AppendFrame(out, 1, 2, Bytes(kMaxDataSize + 1), ChecksumMode::kCrc16),
               std::invalid_argument);
  EXPECT_TRUE(out.empty());
}

// XOR's blind spots (docs/protocol.md): errors that cancel in a column of bits.
TEST(Xor8, MissesTwoFlipsInTheSameBitPositionThatCrc16Catches) {
  const Bytes intact{0x01, 0x10, 0x07, 0x20, 0x30, 0x40, 0x50};
  Bytes corrupted = intact;
  corrupted[3] ^= 0x04;  // the same bit flipped in two bytes cancels in the XOR
  corrupted[5] ^= 0x04;
  EXPECT_EQ(Xor8(corrupted), Xor8(intact));
  EXPECT_NE(Crc16(corrupted), Crc16(intact));
}

TEST(Xor8, MissesSwappedBytesThatCrc16Catches) {
  const Bytes intact{0x01, 0x10, 0x07, 0x20, 0x30, 0x40, 0x50};
  Bytes swapped = intact;
  std::swap(swapped[3], swapped[6]);  // XOR does not see the order of bytes
  EXPECT_EQ(Xor8(swapped), Xor8(intact));
  EXPECT_NE(Crc16(swapped), Crc16(intact));
}

}  // namespace
}  // namespace fireswarm::radio
