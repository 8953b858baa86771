#include <boost/asio/ssl.hpp>
#include <fstream>
#include <stdexcept>

#include "web_sessions.hpp"

namespace fireswarm::server::web {

std::unique_ptr<asio::ssl::context> MakeTlsContext(const std::filesystem::path& cert,
                                                   const std::filesystem::path& key) {
  for (const auto& [flag, file] : {std::pair{"--tls-cert", &cert}, std::pair{"--tls-key", &key}}) {
    if (!std::ifstream(*file)) {
      throw std::invalid_argument(std::string(flag) + " " + file->string() + ": cannot be read");
    }
  }
  // TLS 1.2 or later only.
  auto tls = std::make_unique<asio::ssl::context>(asio::ssl::context::tls_server);
  tls->set_options(asio::ssl::context::default_workarounds | asio::ssl::context::no_sslv2 |
                   asio::ssl::context::no_sslv3 | asio::ssl::context::no_tlsv1 |
                   asio::ssl::context::no_tlsv1_1 | asio::ssl::context::single_dh_use);
  boost::system::error_code error;
  tls->use_certificate_chain_file(cert.string(), error);
  if (error) {
    throw std::invalid_argument("--tls-cert " + cert.string() +
                                ": not a PEM certificate: " + error.message());
  }
  tls->use_private_key_file(key.string(), asio::ssl::context::pem, error);
  if (error) {
    throw std::invalid_argument(
        "--tls-key " + key.string() +
        ": not a PEM private key (or not the certificate's): " + error.message());
  }
  return tls;
}

}  // namespace fireswarm::server::web
