#include "base64.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

namespace fireswarm::server::internal {
namespace {

std::string Encode(const std::string& text) {
  const std::vector<std::uint8_t> bytes(text.begin(), text.end());
  return Base64Encode(bytes);
}

TEST(Base64Encode, Rfc4648TestVectors) {
  EXPECT_EQ(Encode(""), "");
  EXPECT_EQ(Encode("f"), "Zg==");
  EXPECT_EQ(Encode("fo"), "Zm8=");
  EXPECT_EQ(Encode("foo"), "Zm9v");
  EXPECT_EQ(Encode("foob"), "Zm9vYg==");
  EXPECT_EQ(Encode("fooba"), "Zm9vYmE=");
  EXPECT_EQ(Encode("foobar"), "Zm9vYmFy");
}

TEST(Base64Encode, EveryByteValue) {
  const std::vector<std::uint8_t> bytes = {0x00, 0xFF, 0xFE, 0x03};
  EXPECT_EQ(Base64Encode(bytes), "AP/+Aw==");
}

// Longer than one call of OpenSSL's encoder (3 MiB): the chunks join seamlessly.
TEST(Base64Encode, BeyondOneChunk) {
  const std::vector<std::uint8_t> zeros((std::size_t{3} << 20) + 1, 0);
  const std::string text = Base64Encode(zeros);
  ASSERT_EQ(text.size(), (std::size_t{4} << 20) + 4);
  EXPECT_EQ(text.find_first_not_of('A'), text.size() - 2);
  EXPECT_EQ(text.substr(text.size() - 4), "AA==");
}

}  // namespace
}  // namespace fireswarm::server::internal
