#include "fireswarm/common/secret_key.hpp"

#include <openssl/rand.h>
#include <sys/stat.h>

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "fireswarm/common/atomic_file.hpp"

namespace fireswarm::common {
namespace {

constexpr mode_t kOwnerOnlyMode = 0600;
constexpr char kHexDigits[] = "0123456789abcdef";

int HexValue(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

}  // namespace

SecretKey GenerateSecretKey() {
  SecretKey key{};
  if (RAND_bytes(key.data(), static_cast<int>(key.size())) != 1) {
    throw std::runtime_error("cannot draw a key: OpenSSL's random generator failed");
  }
  return key;
}

void WriteSecretKeyFile(const std::filesystem::path& path, const SecretKey& key) {
  std::string text;
  text.reserve(2 * key.size() + 1);
  for (const std::uint8_t byte : key) {
    text += kHexDigits[byte >> 4];
    text += kHexDigits[byte & 0x0f];
  }
  text += '\n';
  WriteFileAtomically(path, text, kOwnerOnlyMode);
}

SecretKey ReadSecretKeyFile(const std::filesystem::path& path) {
  struct stat status {};
  if (::stat(path.c_str(), &status) != 0) {
    throw std::runtime_error(path.string() + ": cannot read the key file: " + std::strerror(errno));
  }
  if (!S_ISREG(status.st_mode)) {
    throw std::runtime_error(path.string() + ": a key file must be a regular file");
  }
  if ((status.st_mode & 077) != 0) {
    char mode[8];
    std::snprintf(mode, sizeof mode, "%04o", static_cast<unsigned>(status.st_mode & 07777));
    throw std::runtime_error(path.string() + ": key file has mode " + mode +
                             ", open to group or others; refused (chmod 600 it, and "
                             "make a new key if others may have read it)");
  }
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  std::string text = buffer.str();
  if (!in) throw std::runtime_error(path.string() + ": cannot read the key file");
  if (!text.empty() && text.back() == '\n') text.pop_back();
  if (!text.empty() && text.back() == '\r') text.pop_back();
  SecretKey key{};
  if (text.size() != 2 * key.size()) {
    throw std::runtime_error(path.string() + ": a key file holds 64 hex digits, this one " +
                             std::to_string(text.size()) + " characters");
  }
  for (std::size_t c = 0; c < text.size(); ++c) {
    if (HexValue(text[c]) < 0) {
      throw std::runtime_error(path.string() + ": character " + std::to_string(c + 1) +
                               " of the key is not a hex digit");
    }
  }
  for (std::size_t i = 0; i < key.size(); ++i) {
    key[i] = static_cast<std::uint8_t>((HexValue(text[2 * i]) << 4) | HexValue(text[2 * i + 1]));
  }
  return key;
}

}  // namespace fireswarm::common
