// The command center's flags, shared by the commands that serve the page
// (`serve`, `run`): --http HOST:PORT, --operator-token-file, --tls-cert,
// --tls-key, --tiles, --web-root; their checks and the web server they start.
#pragma once

#include <boost/program_options.hpp>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "fireswarm/server/web_server.hpp"

namespace fireswarm::app {

struct WebFlags {
  std::string http;  ///< HOST:PORT, empty: no web server
  std::string operator_token_file;
  std::string tls_cert;
  std::string tls_key;
  std::string tiles;
  std::string web_root;  ///< empty: DefaultWebRoot()
};

/// Adds the web options to `options`, writing into `flags` (which must outlive them).
void AddWebOptions(boost::program_options::options_description& options, WebFlags& flags);

/// Throws UsageError naming the flag ("fireswarm <command>: --http ...") for a
/// malformed --http, or another web flag without --http.
void CheckWebFlags(const std::string& command, const WebFlags& flags);

/// "HOST:PORT" ("[::1]:8080" for IPv6) split; nullopt when malformed.
struct HostPort {
  std::string host;
  std::uint16_t port = 0;
};
std::optional<HostPort> ParseHostPort(const std::string& text);

/// The operator token in `file`, surrounding whitespace stripped. Throws
/// UsageError naming the file when it cannot be read, is readable by its group or
/// others (a secret: chmod 600), or holds no token.
std::string ReadOperatorToken(const std::string& command, const std::string& file);

/// The page's files: the source tree's web/ when it exists (a build), else the
/// installed share/fireswarm/web.
std::string DefaultWebRoot();

/// The web server the flags ask for, listening (its URL printed on stdout as
/// "http: listening on URL"); null without --http. `ready`, when given, is called
/// with the server before its URL is printed (e.g. to serve the first documents,
/// so no client that read the URL gets an empty state). Throws UsageError naming
/// the flag when the server refuses its configuration or cannot listen.
/// Precondition: CheckWebFlags passed.
std::unique_ptr<server::WebServer> StartWebServer(
    const std::string& command, const WebFlags& flags, bool read_only,
    const std::function<void(server::WebServer&)>& ready = {});

}  // namespace fireswarm::app
