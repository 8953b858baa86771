// The command center's POST /api/command body on any bytes: JSON parsing, then
// ParseWebCommand and ParseWebCredentials, the web adapter's pure parsers.
// Properties: nothing throws (both are documented never to); credentials read
// from a body come back the same through WebCredentialsJson.
#include <nlohmann/json.hpp>
#include <string>

#include "fireswarm/server/web_command.hpp"
#include "fuzz_check.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  namespace server = fireswarm::server;
  using fireswarm::fuzz::Check;
  const nlohmann::json body =
      nlohmann::json::parse(data, data + size, /*cb=*/nullptr, /*allow_exceptions=*/false);
  if (body.is_discarded()) return 0;
  std::string why;
  const std::optional<server::OperatorCommand> command = server::ParseWebCommand(body, &why);
  Check(command.has_value() || !why.empty(), "a command refused without a reason");
  const std::optional<server::CommandCredentials> credentials =
      server::ParseWebCredentials(body, &why);
  if (!credentials) return 0;
  const nlohmann::json again_body = {{"auth", server::WebCredentialsJson(*credentials)}};
  const std::optional<server::CommandCredentials> again =
      server::ParseWebCredentials(again_body, &why);
  Check(again && again->operator_id == credentials->operator_id &&
            again->utime == credentials->utime && again->nonce == credentials->nonce &&
            again->mac == credentials->mac,
        "credentials change through WebCredentialsJson");
  return 0;
}
