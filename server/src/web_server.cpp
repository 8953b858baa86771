// WebServer: checks its configuration, binds, accepts connections on its own io
// thread and hands each to a session (web_http.cpp); the calls from the caller's
// thread go to the hub they share (web_hub.cpp).
#include "fireswarm/server/web_server.hpp"

#include <pthread.h>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ssl.hpp>
#include <ctime>
#include <iostream>
#include <optional>
#include <stdexcept>
#include <thread>

#include "web_sessions.hpp"

namespace fireswarm::server {

using web::asio::ip::tcp;
namespace asio = web::asio;

namespace {

// "localhost" is the loopback address; anything else must be an IP literal.
asio::ip::address AddressOf(const std::string& host) {
  if (host == "localhost") return asio::ip::address_v4::loopback();
  boost::system::error_code error;
  const asio::ip::address address = asio::ip::make_address(host, error);
  if (error) {
    throw std::invalid_argument("--http " + host + ": the host must be an IP address or localhost");
  }
  return address;
}

std::unique_ptr<MbTiles> OpenTiles(const std::filesystem::path& file) {
  if (file.empty()) return nullptr;
  try {
    return std::make_unique<MbTiles>(file);
  } catch (const std::runtime_error& e) {
    throw std::invalid_argument(std::string("--tiles ") + e.what());
  }
}

// The checks that need no socket, in the order a user would fix them.
void Check(const WebServerConfig& config, const asio::ip::address& address) {
  const bool tls = !config.tls_cert.empty() || !config.tls_key.empty();
  if (config.tls_cert.empty() != config.tls_key.empty()) {
    throw std::invalid_argument(config.tls_cert.empty() ? "--tls-key needs --tls-cert"
                                                        : "--tls-cert needs --tls-key");
  }
  if (!address.is_loopback() && !tls) {
    throw std::invalid_argument("--http " + config.host +
                                ": not a loopback address; serving beyond this machine needs "
                                "--tls-cert and --tls-key");
  }
  std::error_code error;
  if (!std::filesystem::is_directory(config.web_root, error)) {
    throw std::invalid_argument("--web-root " + config.web_root.string() +
                                ": not a directory (the page's files)");
  }
  if (config.operator_token && config.operator_token->empty()) {
    throw std::invalid_argument("--operator-token-file: the token is empty");
  }
}

}  // namespace

struct WebServer::Impl {
  std::shared_ptr<web::Hub> hub;
  std::unique_ptr<asio::ssl::context> tls;  // null: plain HTTP
  asio::io_context io{1};
  tcp::acceptor acceptor{io};
  std::thread thread;
  std::optional<clockid_t> thread_clock;  // the io thread's CPU clock (pthread_getcpuclockid)
  std::string url;
  std::uint16_t port = 0;  // bound, read without touching the acceptor (io thread's)

  void Accept() {
    acceptor.async_accept([this](boost::system::error_code error, tcp::socket socket) {
      if (error == asio::error::operation_aborted) return;
      if (!error) {
        if (tls) {
          web::StartTlsSession(hub, std::move(socket), *tls);
        } else {
          web::StartPlainSession(hub, std::move(socket));
        }
      }
      Accept();
    });
  }
};

WebServer::WebServer(WebServerConfig config) : impl_(std::make_unique<Impl>()) {
  const asio::ip::address address = AddressOf(config.host);
  Check(config, address);
  if (!config.tls_cert.empty()) impl_->tls = web::MakeTlsContext(config.tls_cert, config.tls_key);
  std::unique_ptr<MbTiles> tiles = OpenTiles(config.tiles);
  const bool tls = impl_->tls != nullptr;
  const std::string host = config.host;
  impl_->hub = std::make_shared<web::Hub>(std::move(config), std::move(tiles));

  const tcp::endpoint endpoint(address, impl_->hub->config().port);
  boost::system::error_code error;
  tcp::acceptor& acceptor = impl_->acceptor;
  acceptor.open(endpoint.protocol(), error);
  if (!error) acceptor.set_option(asio::socket_base::reuse_address(true), error);
  if (!error) acceptor.bind(endpoint, error);
  if (!error) acceptor.listen(asio::socket_base::max_listen_connections, error);
  if (error) {
    throw std::runtime_error("--http " + host + ":" + std::to_string(endpoint.port()) +
                             ": cannot listen: " + error.message());
  }
  impl_->port = acceptor.local_endpoint().port();
  const std::string shown = address.is_v6() ? "[" + address.to_string() + "]" : host;
  impl_->url =
      std::string(tls ? "https" : "http") + "://" + shown + ":" + std::to_string(port()) + "/";
  impl_->Accept();
  impl_->thread = std::thread([this] { impl_->io.run(); });
  clockid_t clock{};
  if (pthread_getcpuclockid(impl_->thread.native_handle(), &clock) == 0) {
    impl_->thread_clock = clock;
  }
}

WebServer::~WebServer() {
  asio::post(impl_->io, [this] {
    boost::system::error_code ignored;
    impl_->acceptor.close(ignored);
  });
  impl_->io.stop();
  if (impl_->thread.joinable()) impl_->thread.join();
  // Responders and clients hold sessions, whose sockets belong to the io_context:
  // they go before it does (the sessions in its queue go with it).
  impl_->hub->DropAll();
}

std::uint16_t WebServer::port() const {
  return impl_->port;
}

std::string WebServer::url() const {
  return impl_->url;
}

void WebServer::SetDocuments(std::string state_json, std::string plan_json,
                             std::string coverage_json) {
  impl_->hub->SetDocuments(std::make_shared<const std::string>(std::move(state_json)),
                           std::make_shared<const std::string>(std::move(plan_json)),
                           std::make_shared<const std::string>(std::move(coverage_json)));
}

void WebServer::SetPlanDocuments(std::string plan_json, std::string coverage_json) {
  impl_->hub->SetPlanDocuments(std::make_shared<const std::string>(std::move(plan_json)),
                               std::make_shared<const std::string>(std::move(coverage_json)));
}

void WebServer::HoldSnapshots() {
  impl_->hub->HoldSnapshots();
}

bool WebServer::snapshot_wanted() const {
  return impl_->hub->snapshot_wanted();
}

void WebServer::Broadcast(std::string json) {
  impl_->hub->Broadcast(std::make_shared<const std::string>(std::move(json)));
}

bool WebServer::SendTo(std::uint64_t client, std::string json) {
  return impl_->hub->SendTo(client, std::make_shared<const std::string>(std::move(json)));
}

std::vector<PendingCommand> WebServer::TakeCommands(std::chrono::milliseconds wait) {
  return impl_->hub->TakeCommands(wait);
}

bool WebServer::Answer(std::uint64_t id, int http_status, std::string json_body) {
  return impl_->hub->Answer(id, http_status, std::move(json_body));
}

std::vector<ClientMessage> WebServer::TakeClientMessages(std::chrono::milliseconds wait) {
  return impl_->hub->TakeClientMessages(wait);
}

std::uint64_t WebServer::refused() const {
  return impl_->hub->refused();
}

std::size_t WebServer::clients() const {
  return impl_->hub->clients();
}

double WebServer::io_cpu_seconds() const {
  timespec cpu{};
  if (!impl_->thread_clock || clock_gettime(*impl_->thread_clock, &cpu) != 0) return 0.0;
  return static_cast<double>(cpu.tv_sec) + static_cast<double>(cpu.tv_nsec) * 1e-9;
}

}  // namespace fireswarm::server
