#include "web_routes.hpp"

#include <openssl/crypto.h>
#include <openssl/evp.h>

#include <array>
#include <charconv>
#include <fstream>
#include <iterator>
#include <sstream>

namespace fireswarm::server::web {
namespace {

constexpr std::string_view kJson = "application/json";
constexpr std::string_view kBearer = "Bearer ";

std::optional<int> HexDigit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return std::nullopt;
}

std::optional<std::string> ReadFile(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return std::nullopt;
  return std::string(std::istreambuf_iterator<char>(in), {});
}

std::array<unsigned char, EVP_MAX_MD_SIZE> Sha256(std::string_view text) {
  std::array<unsigned char, EVP_MAX_MD_SIZE> digest{};
  unsigned int size = 0;
  EVP_Digest(text.data(), text.size(), digest.data(), &size, EVP_sha256(), nullptr);
  return digest;
}

// "/tiles/Z/X/Y.ext" -> z, x, y.
std::optional<std::array<int, 3>> TileAddress(std::string_view path) {
  path.remove_prefix(std::string_view("/tiles/").size());
  std::array<int, 3> zxy{};
  for (std::size_t i = 0; i < zxy.size(); ++i) {
    const char* end = path.data() + path.size();
    const auto [next, error] = std::from_chars(path.data(), end, zxy[i]);
    if (error != std::errc() || next == path.data()) return std::nullopt;
    const char expected = i + 1 < zxy.size() ? '/' : '.';
    if (next == end || *next != expected) return std::nullopt;
    path.remove_prefix(static_cast<std::size_t>(next - path.data()) + 1);
  }
  return zxy;
}

Response Tiles(const Hub& hub, const Request& request, std::string_view path) {
  const MbTiles* tiles = hub.tiles();
  if (tiles == nullptr) return ErrorReply(request, http::status::not_found, "no --tiles given");
  if (path == "/tiles/metadata.json") {
    return Reply(request, http::status::ok, tiles->MetadataJson().dump(), kJson);
  }
  const auto zxy = TileAddress(path);
  if (!zxy) return ErrorReply(request, http::status::not_found, "tiles are /tiles/Z/X/Y.png");
  std::optional<std::string> tile;
  try {
    tile = tiles->Tile((*zxy)[0], (*zxy)[1], (*zxy)[2]);
  } catch (const std::runtime_error& e) {
    return ErrorReply(request, http::status::internal_server_error, e.what());
  }
  if (!tile) return ErrorReply(request, http::status::not_found, "no such tile");
  return Reply(request, http::status::ok, std::move(*tile), tiles->ContentType());
}

Response StaticFile(const Hub& hub, const Request& request, const std::string& path) {
  const auto file = FileUnder(hub.config().web_root, path);
  if (!file) return ErrorReply(request, http::status::not_found, "no such file");
  std::error_code error;
  std::filesystem::path target = *file;
  if (std::filesystem::is_directory(target, error)) target /= "index.html";
  if (!std::filesystem::is_regular_file(target, error)) {
    return ErrorReply(request, http::status::not_found, "no such file");
  }
  std::optional<std::string> content = ReadFile(target);
  if (!content) return ErrorReply(request, http::status::not_found, "cannot read the file");
  return Reply(request, http::status::ok, std::move(*content), MimeType(target));
}

}  // namespace

Response Reply(const Request& request, http::status status, std::string body,
               std::string_view content_type) {
  Response response{status, request.version()};
  response.set(http::field::server, "fireswarm");
  response.set(http::field::content_type,
               boost::beast::string_view(content_type.data(), content_type.size()));
  response.set(http::field::cache_control, "no-store");
  response.keep_alive(request.keep_alive());
  const std::size_t size = body.size();
  if (request.method() != http::verb::head) response.body() = std::move(body);
  response.content_length(size);
  return response;
}

Response ErrorReply(const Request& request, http::status status, const std::string& text) {
  return Reply(request, status, nlohmann::json{{"error", text}}.dump(), kJson);
}

std::optional<std::string> DecodePath(std::string_view target) {
  target = target.substr(0, target.find_first_of("?#"));
  std::string path;
  for (std::size_t i = 0; i < target.size(); ++i) {
    if (target[i] != '%') {
      path.push_back(target[i]);
      continue;
    }
    if (i + 2 >= target.size()) return std::nullopt;
    const auto high = HexDigit(target[i + 1]);
    const auto low = HexDigit(target[i + 2]);
    if (!high || !low) return std::nullopt;
    path.push_back(static_cast<char>(*high * 16 + *low));
    i += 2;
  }
  if (path.empty() || path.front() != '/' || path.find('\0') != std::string::npos) {
    return std::nullopt;
  }
  return path;
}

std::optional<std::filesystem::path> FileUnder(const std::filesystem::path& root,
                                               const std::string& path) {
  if (path.find('\\') != std::string::npos) return std::nullopt;
  std::filesystem::path file = root;
  std::stringstream segments(path);
  std::string segment;
  while (std::getline(segments, segment, '/')) {
    if (segment == "..") return std::nullopt;
    if (segment.empty() || segment == ".") continue;
    file /= segment;
  }
  return file;
}

std::string_view MimeType(const std::filesystem::path& file) {
  const std::string extension = file.extension().string();
  if (extension == ".html" || extension == ".htm") return "text/html; charset=utf-8";
  if (extension == ".js" || extension == ".mjs") return "text/javascript; charset=utf-8";
  if (extension == ".css") return "text/css; charset=utf-8";
  if (extension == ".png") return "image/png";
  if (extension == ".svg") return "image/svg+xml";
  if (extension == ".json" || extension == ".map" || extension == ".geojson") return kJson;
  if (extension == ".ico") return "image/x-icon";
  if (extension == ".txt") return "text/plain; charset=utf-8";
  return "application/octet-stream";
}

std::string_view View(boost::beast::string_view text) {
  return {text.data(), text.size()};
}

Response Route(const Hub& hub, const Request& request) {
  const std::optional<std::string> path = DecodePath(View(request.target()));
  if (!path) return ErrorReply(request, http::status::bad_request, "malformed path");
  if (*path == "/api/command") {
    return ErrorReply(request, http::status::method_not_allowed, "commands are POSTed");
  }
  if (request.method() != http::verb::get && request.method() != http::verb::head) {
    return ErrorReply(request, http::status::method_not_allowed, "only GET and HEAD here");
  }
  if (path->starts_with("/api/")) {
    const Documents documents = hub.documents();
    // GET /api/state is the session's (it may wait for a fresh state).
    const Text* document = *path == "/api/plan"       ? &documents.plan
                           : *path == "/api/coverage" ? &documents.coverage
                                                      : nullptr;
    if (document == nullptr) return ErrorReply(request, http::status::not_found, "no such API");
    return Reply(request, http::status::ok, **document, kJson);
  }
  if (path->starts_with("/tiles/")) return Tiles(hub, request, *path);
  return StaticFile(hub, request, *path);
}

bool BearerMatches(std::string_view authorization, const std::string& token) {
  if (!authorization.starts_with(kBearer)) return false;
  authorization.remove_prefix(kBearer.size());
  // Equal-length digests, so the comparison's time tells nothing of the token
  // (not even its length).
  const auto given = Sha256(authorization);
  const auto expected = Sha256(token);
  return CRYPTO_memcmp(given.data(), expected.data(), given.size()) == 0;
}

std::optional<Response> AdmitCommand(Hub& hub, const Request& request, const std::string& peer,
                                     Responder responder, std::uint64_t* id) {
  const WebServerConfig& config = hub.config();
  const auto refuse = [&](http::status status, const std::string& reason) {
    hub.Refuse(peer, reason);
    return ErrorReply(request, status, reason);
  };
  if (request.method() != http::verb::post) {
    return ErrorReply(request, http::status::method_not_allowed, "commands are POSTed");
  }
  if (config.read_only) return refuse(http::status::forbidden, "read-only: commands are refused");
  if (!config.operator_token) {
    return refuse(http::status::forbidden,
                  "no operator token configured (--operator-token-file): commands are refused");
  }
  const auto authorization = request.find(http::field::authorization);
  if (authorization == request.end()) {
    return refuse(http::status::unauthorized, "no Authorization: Bearer token");
  }
  if (!BearerMatches(View(authorization->value()), *config.operator_token)) {
    return refuse(http::status::unauthorized, "wrong operator token");
  }
  nlohmann::json body = nlohmann::json::parse(request.body(), nullptr, false);
  if (body.is_discarded()) return refuse(http::status::bad_request, "the body is not JSON");
  if (!body.is_object()) return refuse(http::status::bad_request, "the body is not a JSON object");
  *id = hub.QueueCommand(std::move(body), peer, std::move(responder));
  return std::nullopt;
}

}  // namespace fireswarm::server::web
