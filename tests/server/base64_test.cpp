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

}  // namespace
}  // namespace fireswarm::server::internal
