#include "fireswarm/radio/secure_frame.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "fireswarm/radio/parser.hpp"

namespace fireswarm::radio {
namespace {

using Bytes = std::vector<std::uint8_t>;

common::SecretKey KeyOf(std::uint8_t fill) {
  common::SecretKey key{};
  key.fill(fill);
  return key;
}

// The frames a secure-mode parser finds in `bytes`, with their views copied out.
struct Parsed {
  std::uint8_t receiver;
  std::uint8_t message_id;
  Bytes sealed;
  std::size_t data_size;
};

std::vector<Parsed> Parse(const Bytes& bytes) {
  std::vector<Parsed> out;
  FrameParser parser(ChecksumMode::kSecure);
  parser.Feed(bytes, [&](const FrameView& f) {
    out.push_back(
        {f.receiver, f.message_id, Bytes(f.sealed.begin(), f.sealed.end()), f.data.size()});
  });
  return out;
}

bool Open(const Parsed& p, const common::SecretKey& key, Bytes& plaintext) {
  const FrameView view{.receiver = p.receiver,
                       .message_id = p.message_id,
                       .data = std::span(p.sealed).subspan(8, p.data_size),
                       .sealed = p.sealed};
  return OpenSecureFrame(view, key, plaintext);
}

TEST(SecureFrame, LayoutKeepsReceiverMessageIdLengthKeyIdAndCounterReadable) {
  Bytes out;
  const Bytes data{1, 2, 3};
  AppendSecureFrame(out, 7, 0x30, data, SecureHeader{7, 0x01020304}, KeyOf(1));
  ASSERT_EQ(out.size(), FrameSize(data.size(), ChecksumMode::kSecure));
  EXPECT_EQ((Bytes(out.begin(), out.begin() + 11)),
            (Bytes{0x70, 0x96, 0xAC, 7, 0x30, 3, 7, 0x04, 0x03, 0x02, 0x01}));
  EXPECT_NE((Bytes(out.begin() + 11, out.begin() + 14)), data) << "data must be encrypted";
  const std::uint16_t crc = Crc16(std::span(out).subspan(3, out.size() - 5));
  EXPECT_EQ(out[out.size() - 2], crc & 0xFF);
  EXPECT_EQ(out[out.size() - 1], crc >> 8);
}

TEST(SecureFrame, RoundTripsEverySizeUnderTheRightKeyOnly) {
  for (const std::size_t size : {0U, 1U, 16U, 17U, 255U}) {
    Bytes data(size);
    for (std::size_t i = 0; i < size; ++i) data[i] = static_cast<std::uint8_t>(i * 7);
    Bytes out;
    AppendSecureFrame(out, kServerId, 0x10, data, SecureHeader{3, 9}, KeyOf(3));
    const std::vector<Parsed> frames = Parse(out);
    ASSERT_EQ(frames.size(), 1U);
    Bytes plaintext;
    ASSERT_TRUE(Open(frames[0], KeyOf(3), plaintext)) << size;
    EXPECT_EQ(plaintext, data);
    EXPECT_FALSE(Open(frames[0], KeyOf(4), plaintext)) << "wrong key, size " << size;
    EXPECT_TRUE(plaintext.empty());
  }
}

TEST(SecureFrame, AnyChangedHeaderOrDataByteFailsAuthentication) {
  Bytes out;
  AppendSecureFrame(out, 5, 0x41, Bytes{10, 20, 30, 40}, SecureHeader{5, 77}, KeyOf(9));
  const Parsed good = Parse(out).at(0);
  Bytes plaintext;
  ASSERT_TRUE(Open(good, KeyOf(9), plaintext));
  for (std::size_t i = 0; i < good.sealed.size(); ++i) {
    if (i == 2) continue;  // the length byte changes the frame's size: the parser's business
    Parsed changed = good;
    changed.sealed[i] ^= 0x01;
    if (i == 0) changed.receiver ^= 0x01;
    if (i == 1) changed.message_id ^= 0x01;
    EXPECT_FALSE(Open(changed, KeyOf(9), plaintext)) << "byte " << i;
  }
}

// Each key's cipher is keyed once per thread and takes only a nonce per frame:
// a frame that failed, or a frame under another key, leaves nothing behind.
TEST(SecureFrame, AFailedOpenOrAnotherKeyLeavesTheNextFrameUnchanged) {
  Bytes out;
  AppendSecureFrame(out, 5, 0x41, Bytes{1, 2, 3}, SecureHeader{5, 1}, KeyOf(9));
  AppendSecureFrame(out, 6, 0x41, Bytes{4, 5, 6}, SecureHeader{6, 1}, KeyOf(8));
  AppendSecureFrame(out, 5, 0x42, Bytes{7, 8}, SecureHeader{5, 2}, KeyOf(9));
  const std::vector<Parsed> frames = Parse(out);
  ASSERT_EQ(frames.size(), 3U);
  Parsed forged = frames[0];
  forged.sealed.back() ^= 0x80;  // the tag's last byte
  Bytes plaintext;
  for (int round = 0; round < 2; ++round) {
    EXPECT_FALSE(Open(forged, KeyOf(9), plaintext));
    ASSERT_TRUE(Open(frames[2], KeyOf(9), plaintext));
    EXPECT_EQ(plaintext, (Bytes{7, 8}));
    EXPECT_FALSE(Open(frames[1], KeyOf(9), plaintext)) << "frame 2 is under key 8";
    ASSERT_TRUE(Open(frames[1], KeyOf(8), plaintext));
    EXPECT_EQ(plaintext, (Bytes{4, 5, 6}));
    ASSERT_TRUE(Open(frames[0], KeyOf(9), plaintext));
    EXPECT_EQ(plaintext, (Bytes{1, 2, 3}));
  }
  // Sealing again after all that gives the same bytes as before.
  Bytes again;
  AppendSecureFrame(again, 5, 0x41, Bytes{1, 2, 3}, SecureHeader{5, 1}, KeyOf(9));
  EXPECT_EQ(again, Bytes(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(again.size())));
}

TEST(SecureFrame, NonceSeparatesDirectionsAndKeys) {
  const SecureHeader header{3, 42};
  EXPECT_NE(SecureNonce(kServerId, header), SecureNonce(3, header));
  EXPECT_NE(SecureNonce(kServerId, header), SecureNonce(kServerId, SecureHeader{4, 42}));
  EXPECT_NE(SecureNonce(kServerId, header), SecureNonce(kServerId, SecureHeader{3, 43}));
}

}  // namespace
}  // namespace fireswarm::radio
