#include "base64.hpp"

#include <openssl/evp.h>

#include <algorithm>

namespace fireswarm::server::internal {

std::string Base64Encode(std::span<const std::uint8_t> bytes) {
  // OpenSSL's encoder takes an int length: whole 3-byte groups at a time.
  constexpr std::size_t kChunk = std::size_t{3} << 20;
  std::string text((bytes.size() + 2) / 3 * 4 + 1, '\0');  // + EVP_EncodeBlock's NUL
  std::size_t written = 0;
  for (std::size_t i = 0; i < bytes.size(); i += kChunk) {
    const std::size_t n = std::min(kChunk, bytes.size() - i);
    written += static_cast<std::size_t>(
        EVP_EncodeBlock(reinterpret_cast<unsigned char*>(text.data() + written), bytes.data() + i,
                        static_cast<int>(n)));
  }
  text.resize(written);
  return text;
}

}  // namespace fireswarm::server::internal
