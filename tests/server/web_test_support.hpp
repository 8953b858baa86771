// Test support for the web server and MBTiles tests: a scratch directory, a
// small MBTiles file, a self-signed certificate (OpenSSL API), and Beast
// clients (HTTP, HTTPS, WebSocket, WSS) on 127.0.0.1.
#pragma once

#include <gtest/gtest.h>
#include <openssl/evp.h>
#include <openssl/pem.h>
#include <openssl/x509.h>
#include <sqlite3.h>
#include <unistd.h>

#include <boost/asio/connect.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/ssl.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/ssl.hpp>
#include <boost/beast/websocket.hpp>
#include <boost/beast/websocket/ssl.hpp>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace fireswarm::server::testing {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
using tcp = asio::ip::tcp;
using Response = http::response<http::string_body>;

/// A directory of its own per test, removed afterwards.
class ScratchTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* test = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = std::filesystem::temp_directory_path() /
           ("fireswarm_" + std::string(test->test_suite_name()) + "_" + std::to_string(getpid()) +
            "_" + test->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::filesystem::path Write(const std::string& name, const std::string& content) const {
    const std::filesystem::path file = dir_ / name;
    std::filesystem::create_directories(file.parent_path());
    std::ofstream(file, std::ios::binary) << content;
    return file;
  }

  std::filesystem::path dir_;
};

/// Runs SQL on a new or existing SQLite file; fails the test on an error.
inline void Sql(const std::filesystem::path& file, const std::string& sql) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(file.string().c_str(), &db), SQLITE_OK);
  char* error = nullptr;
  const int result = sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &error);
  const std::string message = error != nullptr ? error : "";
  sqlite3_free(error);
  sqlite3_close(db);
  ASSERT_EQ(result, SQLITE_OK) << message;
}

/// An MBTiles file with one tile at z 1, column 0, TMS row 0 (the south-west
/// quarter: XYZ y 1) holding `tile`, and a metadata table.
inline void WriteMbTiles(const std::filesystem::path& file, const std::string& tile) {
  std::string hex;
  for (const char signed_c : tile) {
    const auto c = static_cast<unsigned char>(signed_c);
    static constexpr char kDigits[] = "0123456789abcdef";
    hex += kDigits[c >> 4];
    hex += kDigits[c & 15];
  }
  Sql(file,
      "CREATE TABLE metadata (name TEXT, value TEXT);"
      "CREATE TABLE tiles (zoom_level INTEGER, tile_column INTEGER, tile_row INTEGER, "
      "tile_data BLOB);"
      "INSERT INTO metadata VALUES ('name', 'test'), ('format', 'png'), ('minzoom', '0'), "
      "('maxzoom', '1'), ('bounds', '-180,-85,0,0');"
      "INSERT INTO tiles VALUES (1, 0, 0, x'" +
          hex + "');");
}

/// A self-signed certificate for CN 127.0.0.1 and its key (EC P-256), as PEM files.
inline void WriteSelfSignedCertificate(const std::filesystem::path& cert,
                                       const std::filesystem::path& key) {
  EVP_PKEY* pkey = EVP_EC_gen("P-256");
  ASSERT_NE(pkey, nullptr);
  X509* x509 = X509_new();
  X509_set_version(x509, 2);
  ASN1_INTEGER_set(X509_get_serialNumber(x509), 1);
  X509_gmtime_adj(X509_getm_notBefore(x509), -60);
  X509_gmtime_adj(X509_getm_notAfter(x509), 3600);
  X509_set_pubkey(x509, pkey);
  X509_NAME* name = X509_get_subject_name(x509);
  X509_NAME_add_entry_by_txt(name, "CN", MBSTRING_ASC,
                             reinterpret_cast<const unsigned char*>("127.0.0.1"), -1, -1, 0);
  X509_set_issuer_name(x509, name);
  ASSERT_GT(X509_sign(x509, pkey, EVP_sha256()), 0);
  std::FILE* out = std::fopen(cert.string().c_str(), "w");
  ASSERT_NE(out, nullptr);
  PEM_write_X509(out, x509);
  std::fclose(out);
  out = std::fopen(key.string().c_str(), "w");
  ASSERT_NE(out, nullptr);
  PEM_write_PrivateKey(out, pkey, nullptr, nullptr, 0, nullptr, nullptr);
  std::fclose(out);
  X509_free(x509);
  EVP_PKEY_free(pkey);
}

/// A request to 127.0.0.1:port.
inline http::request<http::string_body> MakeRequest(
    http::verb verb, const std::string& target, const std::string& body = "",
    const std::vector<std::pair<http::field, std::string>>& headers = {}) {
  http::request<http::string_body> request{verb, target, 11};
  request.set(http::field::host, "127.0.0.1");
  for (const auto& [field, value] : headers) request.set(field, value);
  if (!body.empty() || verb == http::verb::post) {
    request.set(http::field::content_type, "application/json");
    request.body() = body;
    request.prepare_payload();
  }
  return request;
}

template <class Stream>
Response Exchange(Stream& stream, const http::request<http::string_body>& request) {
  http::write(stream, request);
  beast::flat_buffer buffer;
  Response response;
  if (request.method() == http::verb::head) {
    http::response_parser<http::string_body> parser;
    parser.skip(true);
    http::read(stream, buffer, parser);
    return parser.release();
  }
  http::read(stream, buffer, response);
  return response;
}

/// One plain HTTP exchange on a new connection.
inline Response Fetch(std::uint16_t port, const http::request<http::string_body>& request) {
  asio::io_context io;
  beast::tcp_stream stream(io);
  stream.connect(tcp::endpoint(asio::ip::make_address("127.0.0.1"), port));
  return Exchange(stream, request);
}
inline Response Get(std::uint16_t port, const std::string& target) {
  return Fetch(port, MakeRequest(http::verb::get, target));
}

/// A TLS client context that trusts only `ca` (the self-signed certificate).
inline asio::ssl::context ClientTls(const std::filesystem::path& ca) {
  asio::ssl::context tls(asio::ssl::context::tls_client);
  tls.load_verify_file(ca.string());
  tls.set_verify_mode(asio::ssl::verify_peer);
  return tls;
}

/// One HTTPS exchange on a new connection, verifying the server against `ca`.
inline Response FetchTls(std::uint16_t port, const std::filesystem::path& ca,
                         const http::request<http::string_body>& request) {
  asio::io_context io;
  asio::ssl::context tls = ClientTls(ca);
  beast::ssl_stream<beast::tcp_stream> stream(io, tls);
  beast::get_lowest_layer(stream).connect(tcp::endpoint(asio::ip::make_address("127.0.0.1"), port));
  stream.handshake(asio::ssl::stream_base::client);
  return Exchange(stream, request);
}

/// A blocking WebSocket client (plain or TLS) on 127.0.0.1:port/ws.
class WsTestClient {
 public:
  explicit WsTestClient(std::uint16_t port) : plain_(std::make_unique<Plain>(io_)) {
    beast::get_lowest_layer(*plain_).connect(Endpoint(port));
    plain_->handshake("127.0.0.1", "/ws");
  }
  WsTestClient(std::uint16_t port, const std::filesystem::path& ca)
      : tls_context_(std::make_unique<asio::ssl::context>(ClientTls(ca))),
        tls_(std::make_unique<Tls>(io_, *tls_context_)) {
    beast::get_lowest_layer(*tls_).connect(Endpoint(port));
    tls_->next_layer().handshake(asio::ssl::stream_base::client);
    tls_->handshake("127.0.0.1", "/ws");
  }

  std::string Read() {
    beast::flat_buffer buffer;
    if (plain_) {
      plain_->read(buffer);
    } else {
      tls_->read(buffer);
    }
    return beast::buffers_to_string(buffer.data());
  }
  void Write(const std::string& text) {
    if (plain_) {
      plain_->write(asio::buffer(text));
    } else {
      tls_->write(asio::buffer(text));
    }
  }

 private:
  using Plain = websocket::stream<beast::tcp_stream>;
  using Tls = websocket::stream<beast::ssl_stream<beast::tcp_stream>>;
  static tcp::endpoint Endpoint(std::uint16_t port) {
    return {asio::ip::make_address("127.0.0.1"), port};
  }

  asio::io_context io_;
  std::unique_ptr<asio::ssl::context> tls_context_;
  std::unique_ptr<Plain> plain_;
  std::unique_ptr<Tls> tls_;
};

}  // namespace fireswarm::server::testing
