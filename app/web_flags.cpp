#include "web_flags.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <charconv>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>

#include "cli.hpp"

namespace fireswarm::app {

namespace po = boost::program_options;

namespace {

std::string Trimmed(const std::string& text) {
  constexpr const char* kSpace = " \t\r\n\v\f";
  const std::size_t first = text.find_first_not_of(kSpace);
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(kSpace) - first + 1);
}

}  // namespace

void AddWebOptions(po::options_description& options, WebFlags& f) {
  auto add = options.add_options();
  add("http", po::value(&f.http)->value_name("HOST:PORT"),
      "serve the command-center page and its API (docs/command_center.md) on HOST:PORT; "
      "port 0 picks a free one; a non-loopback HOST needs --tls-cert and --tls-key");
  add("operator-token-file", po::value(&f.operator_token_file)->value_name("FILE"),
      "the operator's token (a file only its owner may read): commands over HTTP need it as "
      "'Authorization: Bearer TOKEN'; without it every command is refused");
  add("tls-cert", po::value(&f.tls_cert)->value_name("FILE"),
      "serve HTTPS/WSS with this PEM certificate (chain)");
  add("tls-key", po::value(&f.tls_key)->value_name("FILE"), "the certificate's PEM private key");
  add("tiles", po::value(&f.tiles)->value_name("FILE.mbtiles"),
      "offline map tiles (MBTiles) served under /tiles/");
  add("web-root", po::value(&f.web_root)->value_name("DIR"),
      ("the page's files (default: " + DefaultWebRoot() + ")").c_str());
}

std::optional<HostPort> ParseHostPort(const std::string& text) {
  const std::size_t colon = text.rfind(':');
  if (colon == std::string::npos || colon == 0) return std::nullopt;
  std::string host = text.substr(0, colon);
  if (host.front() == '[') {
    if (host.size() < 3 || host.back() != ']') return std::nullopt;
    host = host.substr(1, host.size() - 2);
  } else if (host.find(':') != std::string::npos) {
    return std::nullopt;  // an IPv6 address goes in brackets
  }
  const std::string port = text.substr(colon + 1);
  unsigned value = 0;
  const auto [end, error] = std::from_chars(port.data(), port.data() + port.size(), value);
  if (port.empty() || error != std::errc() || end != port.data() + port.size() || value > 65535) {
    return std::nullopt;
  }
  return HostPort{host, static_cast<std::uint16_t>(value)};
}

void CheckWebFlags(const std::string& command, const WebFlags& f) {
  const std::string prefix = "fireswarm " + command + ": ";
  if (f.http.empty()) {
    for (const auto& [flag, value] :
         {std::pair{"operator-token-file", &f.operator_token_file},
          std::pair{"tls-cert", &f.tls_cert}, std::pair{"tls-key", &f.tls_key},
          std::pair{"tiles", &f.tiles}, std::pair{"web-root", &f.web_root}}) {
      if (!value->empty()) throw UsageError(prefix + "--" + flag + " goes with --http");
    }
    return;
  }
  if (!ParseHostPort(f.http)) {
    ThrowBadFlag(command, "http", "HOST:PORT (e.g. 127.0.0.1:8080, [::1]:0)", f.http);
  }
}

std::string ReadOperatorToken(const std::string& command, const std::string& file) {
  const std::string prefix = "fireswarm " + command + ": --operator-token-file " + file + ": ";
  struct stat status {};
  if (::stat(file.c_str(), &status) != 0) throw UsageError(prefix + std::strerror(errno));
  if ((status.st_mode & (S_IRWXG | S_IRWXO)) != 0) {
    throw UsageError(prefix +
                     "its group or others may read it; make it the owner's only (chmod 600 " +
                     file + ")");
  }
  std::ifstream in(file, std::ios::binary);
  if (!in) throw UsageError(prefix + "cannot be read: " + std::strerror(errno));
  const std::string token = Trimmed(std::string(std::istreambuf_iterator<char>(in), {}));
  if (token.empty()) throw UsageError(prefix + "holds no token");
  return token;
}

std::string DefaultWebRoot() {
  std::error_code error;
  if (std::filesystem::is_directory(FIRESWARM_SOURCE_WEB_DIR, error)) {
    return FIRESWARM_SOURCE_WEB_DIR;
  }
  return FIRESWARM_INSTALLED_WEB_DIR;
}

std::unique_ptr<server::WebServer> StartWebServer(
    const std::string& command, const WebFlags& f, bool read_only,
    const std::function<void(server::WebServer&)>& ready) {
  if (f.http.empty()) return nullptr;
  const HostPort address = *ParseHostPort(f.http);
  server::WebServerConfig config;
  config.host = address.host;
  config.port = address.port;
  config.web_root = f.web_root.empty() ? DefaultWebRoot() : f.web_root;
  if (!f.operator_token_file.empty()) {
    config.operator_token = ReadOperatorToken(command, f.operator_token_file);
  }
  config.tls_cert = f.tls_cert;
  config.tls_key = f.tls_key;
  config.tiles = f.tiles;
  config.read_only = read_only;
  // The page's first snapshot is the feed's state, not an empty document: the
  // server listens before the feed (WebFeed, ReplayFeed) is made.
  config.wait_for_first_state = true;
  std::unique_ptr<server::WebServer> web;
  try {
    web = std::make_unique<server::WebServer>(config);
  } catch (const std::exception& e) {
    throw UsageError("fireswarm " + command + ": " + e.what());
  }
  if (ready) ready(*web);
  std::cout << "http: listening on " << web->url() << std::endl;
  return web;
}

}  // namespace fireswarm::app
