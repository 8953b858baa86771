// Every payload decoder (radio/messages.hpp) on any bytes. Input: the message ID
// byte, then the payload. Properties: a decoded payload re-encodes to exactly the
// input bytes and carries the ID it was decoded as; a refused one has a reason.
#include <span>
#include <vector>

#include "fireswarm/radio/messages.hpp"
#include "fuzz_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace radio = fireswarm::radio;
  using fireswarm::fuzz::Check;
  if (size < 1) return 0;
  const std::uint8_t message_id = data[0];
  const std::span<const std::uint8_t> payload(data + 1, size - 1);
  const radio::DecodeResult result = radio::DecodePayload(message_id, payload);
  if (!result.message) {
    Check(result.error != radio::DecodeError::kNone, "a refused payload without a reason");
    return 0;
  }
  Check(result.error == radio::DecodeError::kNone, "a decoded payload with an error");
  Check(static_cast<std::uint8_t>(radio::IdOf(*result.message)) == message_id,
        "decoded as another message ID");
  std::vector<std::uint8_t> encoded;
  radio::EncodePayload(*result.message, encoded);
  Check(encoded.size() == payload.size() &&
            std::equal(encoded.begin(), encoded.end(), payload.begin()),
        "re-encoding a decoded payload does not give its bytes");
  return 0;
}
