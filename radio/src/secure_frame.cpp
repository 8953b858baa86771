// AES-256-GCM sealing of APOne frames through OpenSSL's EVP interface. EVP checks
// the tag itself (EVP_DecryptFinal_ex fails on a mismatch), so no tag comparison
// is written here.
#include "fireswarm/radio/secure_frame.hpp"

#include <openssl/evp.h>

#include <algorithm>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>

#include "byte_io.hpp"

namespace fireswarm::radio {
namespace {

constexpr std::size_t kAssociatedSize = kHeaderSize - kPreamble.size() + kSecureHeaderSize;
constexpr std::uint8_t kToServer = 1;
constexpr std::uint8_t kFromServer = 0;

struct CipherContextDeleter {
  void operator()(EVP_CIPHER_CTX* context) const { EVP_CIPHER_CTX_free(context); }
};
using CipherContext = std::unique_ptr<EVP_CIPHER_CTX, CipherContextDeleter>;

// Contexts keyed once, per thread, key and direction. OpenSSL 3 fetches the
// cipher and expands the key on every full initialisation, which costs more than
// sealing or opening a short frame; a context keyed once takes each frame's nonce
// alone (EVP_CipherInit_ex with no cipher and no key keeps both). 250 drones open
// every broadcast frame, and the server seals and opens under 250 keys.
struct KeyedContexts {
  CipherContext seal;
  CipherContext open;
};

// More keys than a fleet has (254 vehicles, broadcast, a previous key each): past
// it the cache starts over rather than grow with every rotation.
constexpr std::size_t kMaxCachedKeys = 1024;

// The context for `key` in one direction, keyed, or nullptr when OpenSSL fails.
EVP_CIPHER_CTX* ContextFor(const common::SecretKey& key, bool seal) {
  thread_local std::map<common::SecretKey, KeyedContexts> contexts;
  auto found = contexts.find(key);
  if (found == contexts.end()) {
    if (contexts.size() >= kMaxCachedKeys) contexts.clear();
    found = contexts.emplace(key, KeyedContexts{}).first;
  }
  CipherContext& context = seal ? found->second.seal : found->second.open;
  if (!context) {
    CipherContext fresh(EVP_CIPHER_CTX_new());
    if (!fresh || EVP_CipherInit_ex(fresh.get(), EVP_aes_256_gcm(), nullptr, key.data(), nullptr,
                                    seal ? 1 : 0) != 1) {
      return nullptr;
    }
    context = std::move(fresh);
  }
  return context.get();
}

int SizeAsInt(std::size_t size) {
  return static_cast<int>(size);  // every size here is <= 276
}

}  // namespace

std::array<std::uint8_t, 12> SecureNonce(std::uint8_t receiver, const SecureHeader& header) {
  std::array<std::uint8_t, 12> nonce{};
  nonce[0] = header.key_id;
  nonce[1] = receiver == kServerId ? kToServer : kFromServer;
  for (std::size_t i = 0; i < 4; ++i) {
    nonce[4 + i] = static_cast<std::uint8_t>(header.counter >> (8 * i));
  }
  return nonce;
}

void AppendSecureFrame(std::vector<std::uint8_t>& out, std::uint8_t receiver,
                       std::uint8_t message_id, std::span<const std::uint8_t> plaintext,
                       const SecureHeader& header, const common::SecretKey& key) {
  if (plaintext.size() > kMaxDataSize) {
    throw std::invalid_argument("AppendSecureFrame: data of " + std::to_string(plaintext.size()) +
                                " bytes exceeds the frame's maximum of 255");
  }
  const std::size_t start = out.size();
  out.insert(out.end(), kPreamble.begin(), kPreamble.end());
  out.push_back(receiver);
  out.push_back(message_id);
  out.push_back(static_cast<std::uint8_t>(plaintext.size()));
  out.push_back(header.key_id);
  detail::AppendLittleEndian(out, header.counter);
  const std::size_t data_at = out.size();
  out.resize(data_at + plaintext.size() + kSecureTagSize);

  const std::array<std::uint8_t, 12> nonce = SecureNonce(receiver, header);
  EVP_CIPHER_CTX* context = ContextFor(key, /*seal=*/true);
  int written = 0;
  const std::uint8_t* associated = out.data() + start + kPreamble.size();
  const bool ok =
      context != nullptr &&
      EVP_EncryptInit_ex(context, nullptr, nullptr, nullptr, nonce.data()) == 1 &&
      EVP_EncryptUpdate(context, nullptr, &written, associated, SizeAsInt(kAssociatedSize)) == 1 &&
      EVP_EncryptUpdate(context, out.data() + data_at, &written, plaintext.data(),
                        SizeAsInt(plaintext.size())) == 1 &&
      EVP_EncryptFinal_ex(context, out.data() + data_at + plaintext.size(), &written) == 1 &&
      EVP_CIPHER_CTX_ctrl(context, EVP_CTRL_GCM_GET_TAG, SizeAsInt(kSecureTagSize),
                          out.data() + data_at + plaintext.size()) == 1;
  if (!ok) {
    out.resize(start);
    throw std::runtime_error("AppendSecureFrame: OpenSSL AES-256-GCM encryption failed");
  }
  const std::span<const std::uint8_t> covered(out.data() + start + kPreamble.size(),
                                              out.size() - start - kPreamble.size());
  detail::AppendLittleEndian(out, Crc16(covered));
}

SecureHeader ReadSecureHeader(const FrameView& frame) {
  SecureHeader header;
  if (frame.sealed.size() < kAssociatedSize) return header;
  const std::uint8_t* at = frame.sealed.data() + (kHeaderSize - kPreamble.size());
  header.key_id = at[0];
  for (std::size_t i = 0; i < 4; ++i) {
    header.counter |= static_cast<std::uint32_t>(at[1 + i]) << (8 * i);
  }
  return header;
}

bool OpenSecureFrame(const FrameView& frame, const common::SecretKey& key,
                     std::vector<std::uint8_t>& plaintext) {
  plaintext.clear();
  if (frame.sealed.size() != kAssociatedSize + frame.data.size() + kSecureTagSize) return false;
  const SecureHeader header = ReadSecureHeader(frame);
  const std::array<std::uint8_t, 12> nonce = SecureNonce(frame.receiver, header);
  // EVP_CTRL_GCM_SET_TAG takes a non-const pointer; it only reads the tag.
  std::array<std::uint8_t, kSecureTagSize> tag{};
  std::copy_n(frame.sealed.end() - kSecureTagSize, kSecureTagSize, tag.begin());
  plaintext.resize(frame.data.size());
  EVP_CIPHER_CTX* context = ContextFor(key, /*seal=*/false);
  int written = 0;
  const bool ok = context != nullptr &&
                  EVP_DecryptInit_ex(context, nullptr, nullptr, nullptr, nonce.data()) == 1 &&
                  EVP_DecryptUpdate(context, nullptr, &written, frame.sealed.data(),
                                    SizeAsInt(kAssociatedSize)) == 1 &&
                  EVP_DecryptUpdate(context, plaintext.data(), &written, frame.data.data(),
                                    SizeAsInt(frame.data.size())) == 1 &&
                  EVP_CIPHER_CTX_ctrl(context, EVP_CTRL_GCM_SET_TAG, SizeAsInt(kSecureTagSize),
                                      tag.data()) == 1 &&
                  EVP_DecryptFinal_ex(context, plaintext.data() + plaintext.size(), &written) == 1;
  if (!ok) plaintext.clear();
  return ok;
}

}  // namespace fireswarm::radio
