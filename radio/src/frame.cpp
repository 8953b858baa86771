// APOne frame encoding and checksums (seed Table 5.3, seed 5.3.4.5).
#include "fireswarm/radio/frame.hpp"

#include <stdexcept>
#include <string>

#include "byte_io.hpp"
#include "range_checksum.hpp"

namespace fireswarm::radio {

std::string_view ToString(ChecksumMode mode) {
  switch (mode) {
    case ChecksumMode::kXor:
      return "xor";
    case ChecksumMode::kCrc16:
      return "crc16";
    case ChecksumMode::kSecure:
      return "secure";
  }
  return "unknown";
}

std::optional<ChecksumMode> ParseChecksumMode(std::string_view text) {
  if (text == "xor") return ChecksumMode::kXor;
  if (text == "crc16") return ChecksumMode::kCrc16;
  if (text == "secure") return ChecksumMode::kSecure;
  return std::nullopt;
}

std::uint8_t Xor8(std::span<const std::uint8_t> bytes) {
  std::uint8_t sum = 0;
  for (const std::uint8_t byte : bytes) sum ^= byte;
  return sum;
}

std::uint16_t Crc16(std::span<const std::uint8_t> bytes) {
  std::uint16_t crc = detail::kCrc16Initial;
  for (const std::uint8_t byte : bytes) crc = detail::Crc16Step(crc, byte);
  return crc;
}

void AppendFrame(std::vector<std::uint8_t>& out, std::uint8_t receiver, std::uint8_t message_id,
                 std::span<const std::uint8_t> data, ChecksumMode mode) {
  if (data.size() > kMaxDataSize) {
    throw std::invalid_argument("AppendFrame: data of " + std::to_string(data.size()) +
                                " bytes exceeds the frame's maximum of 255");
  }
  if (mode == ChecksumMode::kSecure) {
    throw std::invalid_argument("AppendFrame: a secure frame needs a key (AppendSecureFrame)");
  }
  const std::size_t start = out.size();
  // No exact reserve(start + frame size) here: it would defeat the vector's geometric
  // growth and make appending many frames to one buffer quadratic.
  out.insert(out.end(), kPreamble.begin(), kPreamble.end());
  out.push_back(receiver);
  out.push_back(message_id);
  out.push_back(static_cast<std::uint8_t>(data.size()));
  out.insert(out.end(), data.begin(), data.end());
  // The checksum covers receiver ID, message ID, length and data, not the preamble.
  const std::span<const std::uint8_t> covered(out.data() + start + kPreamble.size(),
                                              out.size() - start - kPreamble.size());
  if (mode == ChecksumMode::kXor) {
    out.push_back(Xor8(covered));
  } else {
    detail::AppendLittleEndian(out, Crc16(covered));
  }
}

}  // namespace fireswarm::radio
