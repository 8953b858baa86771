// The web server's HTTP routes, apart from the sessions that carry them: static
// files, the API documents, map tiles and command admission (authentication,
// body checks). The WebSocket upgrade is the session's (web_socket.cpp).
#pragma once

#include <boost/beast/http.hpp>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "web_hub.hpp"

namespace fireswarm::server::web {

namespace http = boost::beast::http;
using Request = http::request<http::string_body>;
using Response = http::response<http::string_body>;

/// A reply with a body of `content_type`, matching the request's version and keep-alive.
Response Reply(const Request& request, http::status status, std::string body,
               std::string_view content_type);
/// {"error": text} with `status`.
Response ErrorReply(const Request& request, http::status status, const std::string& text);

/// Beast's string_view (Boost's in 1.74) as std::string_view.
std::string_view View(boost::beast::string_view text);

/// The URL path `target` (query string removed) percent-decoded; nullopt when it
/// is malformed or contains a NUL.
std::optional<std::string> DecodePath(std::string_view target);

/// The file under `root` that the decoded `path` names ("/" -> index.html);
/// nullopt when it would leave `root` (a ".." segment, a backslash).
std::optional<std::filesystem::path> FileUnder(const std::filesystem::path& root,
                                               const std::string& path);

/// The MIME type for a file name's extension (application/octet-stream otherwise).
std::string_view MimeType(const std::filesystem::path& file);

/// Everything but POST /api/command and GET /api/state (the session's: they wait
/// for the caller): files, the plan and coverage documents, tiles, 404/405.
Response Route(const Hub& hub, const Request& request);

/// POST /api/command: refuses it (401, 403, 400) or queues it for the caller,
/// who answers through `responder`; nullopt then, and `*id` is its number.
std::optional<Response> AdmitCommand(Hub& hub, const Request& request, const std::string& peer,
                                     Responder responder, std::uint64_t* id);

/// True when `authorization` is "Bearer TOKEN" with TOKEN equal to `token`,
/// compared in constant time (digests compared with CRYPTO_memcmp).
bool BearerMatches(std::string_view authorization, const std::string& token);

}  // namespace fireswarm::server::web
