// The web server's connections: an HTTP session per accepted socket (plain or
// TLS, web_http.cpp), upgraded to a WebSocket session on GET /ws (web_socket.cpp),
// and the TLS context they share (web_tls.cpp). Everything here runs on the
// server's one io thread, so sessions need no strands.
#pragma once

#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/ssl/context.hpp>
#include <boost/beast/core/tcp_stream.hpp>
#include <boost/beast/ssl/ssl_stream.hpp>
#include <filesystem>
#include <memory>
#include <string>

#include "web_hub.hpp"
#include "web_routes.hpp"

namespace fireswarm::server::web {

namespace asio = boost::asio;
namespace beast = boost::beast;
using tcp = asio::ip::tcp;
using PlainStream = beast::tcp_stream;
using TlsStream = beast::ssl_stream<beast::tcp_stream>;

/// Serves HTTP on an accepted socket until the peer closes it or it idles.
void StartPlainSession(std::shared_ptr<Hub> hub, tcp::socket socket);
/// The same over TLS (handshake first).
void StartTlsSession(std::shared_ptr<Hub> hub, tcp::socket socket, asio::ssl::context& tls);

/// Accepts the WebSocket upgrade `request` on `stream` and serves the stream
/// (docs/command_center.md): a snapshot first, then broadcasts; client messages to
/// the hub. Instantiated for PlainStream and TlsStream.
template <class Stream>
void StartWebSocket(std::shared_ptr<Hub> hub, Stream stream, Request request, std::string peer);

/// A TLS server context with the PEM certificate chain and key. Throws
/// std::invalid_argument naming --tls-cert or --tls-key and the file.
std::unique_ptr<asio::ssl::context> MakeTlsContext(const std::filesystem::path& cert,
                                                   const std::filesystem::path& key);

}  // namespace fireswarm::server::web
