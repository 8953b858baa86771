// One HTTP exchange with a `fireswarm ... --http` process under test, on a new
// connection to 127.0.0.1 (the app tests' one client; the server's own tests use
// tests/server/web_test_support.hpp).
#pragma once

#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <cstdint>
#include <string>

namespace fireswarm::app {

/// `verb target` with `body` (POST) and, unless `token` is empty, the operator's
/// `Authorization: Bearer token`; the reply.
inline boost::beast::http::response<boost::beast::http::string_body> HttpFetch(
    std::uint16_t port, boost::beast::http::verb verb, const std::string& target,
    const std::string& body = "", const std::string& token = "") {
  namespace beast = boost::beast;
  namespace http = beast::http;
  boost::asio::io_context io;
  beast::tcp_stream stream(io);
  stream.connect({boost::asio::ip::make_address("127.0.0.1"), port});
  http::request<http::string_body> request{verb, target, 11};
  request.set(http::field::host, "127.0.0.1");
  if (!token.empty()) request.set(http::field::authorization, "Bearer " + token);
  if (verb == http::verb::post) {
    request.body() = body;
    request.prepare_payload();
  }
  http::write(stream, request);
  beast::flat_buffer buffer;
  http::response<http::string_body> response;
  http::read(stream, buffer, response);
  return response;
}

}  // namespace fireswarm::app
