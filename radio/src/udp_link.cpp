// The UDP transport on a Boost.Asio socket: each burst is one datagram, so a burst
// arrives whole or not at all, as on the radio. The socket is not connected, so an
// absent peer costs no ICMP errors; datagrams from anyone but the configured remote
// are dropped and counted (today's forged fire reports came from another port).
#include "fireswarm/radio/udp_link.hpp"

#include <charconv>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "asio.hpp"
#include "async_receiver.hpp"

namespace fireswarm::radio {
namespace {

using boost::asio::ip::udp;

// One read takes one whole datagram; 65,535 covers the largest one UDP allows.
constexpr std::size_t kDatagramBufferBytes = std::numeric_limits<std::uint16_t>::max();

struct HostPort {
  std::string host;  // without IPv6 brackets; empty = any address
  std::uint16_t port = 0;
};

std::string Describe(const char* role, const std::string& text) {
  return std::string("UDP ") + role + " endpoint \"" + text + "\"";
}

// "host:port", "[v6-host]:port" or ":port".
HostPort ParseEndpoint(const char* role, const std::string& text) {
  const std::size_t colon = text.rfind(':');
  if (colon == std::string::npos) {
    throw std::invalid_argument(Describe(role, text) + ": expected host:port");
  }
  HostPort parsed;
  parsed.host = text.substr(0, colon);
  if (parsed.host.size() >= 2 && parsed.host.front() == '[' && parsed.host.back() == ']') {
    parsed.host = parsed.host.substr(1, parsed.host.size() - 2);
  } else if (parsed.host.find(':') != std::string::npos) {
    throw std::invalid_argument(Describe(role, text) + ": put an IPv6 host in brackets");
  }
  const char* first = text.data() + colon + 1;
  const char* last = text.data() + text.size();
  const auto [end, error] = std::from_chars(first, last, parsed.port);
  if (first == last || error != std::errc() || end != last) {
    throw std::invalid_argument(Describe(role, text) + ": port must be a number in 0-65535");
  }
  return parsed;
}

// The first address of `where` in `family` (any family when it is null).
udp::endpoint Resolve(boost::asio::io_context& io, const char* role, const std::string& text,
                      const HostPort& where, const udp* family) {
  if (where.host.empty()) return {family ? *family : udp::v4(), where.port};
  udp::resolver resolver(io);
  boost::system::error_code error;
  const auto results = resolver.resolve(where.host, std::to_string(where.port),
                                        udp::resolver::numeric_service, error);
  if (error)
    throw std::runtime_error(Describe(role, text) + ": cannot resolve: " + error.message());
  for (const auto& result : results) {
    if (family == nullptr || result.endpoint().protocol() == *family) return result.endpoint();
  }
  throw std::runtime_error(Describe(role, text) + ": no address in the local socket's family");
}

}  // namespace

struct UdpLink::Impl {
  // Destroyed bottom-up: the receiver, then the socket (aborting its read), then
  // the io_context that owns the aborted handler.
  boost::asio::io_context io;
  udp::socket socket{io};
  std::string remote_text;
  udp::endpoint remote;
  udp::endpoint sender;  // of the datagram being received
  std::uint64_t foreign_datagrams = 0;
  std::unique_ptr<detail::AsyncReceiver> receiver;
};

UdpLink::UdpLink(const std::string& local, const std::string& remote)
    : impl_(std::make_unique<Impl>()) {
  // Both strings are checked before any socket exists, so a typo fails cleanly.
  const HostPort local_where = ParseEndpoint("local", local);
  ParseEndpoint("remote", remote);
  const udp::endpoint bind_to = Resolve(impl_->io, "local", local, local_where, nullptr);
  boost::system::error_code error;
  impl_->socket.open(bind_to.protocol(), error);
  if (!error) impl_->socket.bind(bind_to, error);
  if (error)
    throw std::runtime_error(Describe("local", local) + ": cannot bind: " + error.message());
  SetRemote(remote);
  impl_->receiver = std::make_unique<detail::AsyncReceiver>(
      impl_->io, Describe("local", local), kDatagramBufferBytes,
      [impl = impl_.get()](boost::asio::mutable_buffer buffer,
                           detail::AsyncReceiver::Completion done) {
        impl->socket.async_receive_from(
            buffer, impl->sender,
            [impl, done = std::move(done)](const boost::system::error_code& read_error,
                                           std::size_t bytes) {
              // Only the configured peer speaks on this link: anything else keeps
              // nothing of its datagram.
              if (!read_error && impl->sender != impl->remote) {
                ++impl->foreign_datagrams;
                bytes = 0;
              }
              done(read_error, bytes);
            });
      });
}

UdpLink::~UdpLink() = default;

void UdpLink::SetRemote(const std::string& remote) {
  const HostPort where = ParseEndpoint("remote", remote);
  if (where.port == 0) {
    throw std::invalid_argument(Describe("remote", remote) + ": port 0 cannot be sent to");
  }
  const udp family = impl_->socket.local_endpoint().protocol();
  impl_->remote = Resolve(impl_->io, "remote", remote, where, &family);
  impl_->remote_text = remote;
}

void UdpLink::Transmit(Nanos /*now*/, Nanos /*start*/, std::span<const std::uint8_t> bytes) {
  if (bytes.empty()) return;
  if (bytes.size() > kMaxBurstBytes) {
    throw std::invalid_argument("UDP burst of " + std::to_string(bytes.size()) +
                                " bytes exceeds one datagram (" + std::to_string(kMaxBurstBytes) +
                                " bytes)");
  }
  boost::system::error_code error;
  impl_->socket.send_to(boost::asio::buffer(bytes.data(), bytes.size()), impl_->remote, 0, error);
  if (error) {
    throw std::runtime_error(Describe("remote", impl_->remote_text) +
                             ": send failed: " + error.message());
  }
}

void UdpLink::Receive(Nanos /*now*/, std::vector<std::uint8_t>& out) {
  impl_->receiver->MoveTo(out);
}

bool UdpLink::WaitReadable(Nanos timeout) {
  return impl_->receiver->WaitReadable(timeout);
}

std::uint64_t UdpLink::foreign_datagrams() const {
  return impl_->foreign_datagrams;
}

std::uint16_t UdpLink::local_port() const {
  return impl_->socket.local_endpoint().port();
}

std::unique_ptr<IoLink> OpenUdpLink(const std::string& local, const std::string& remote) {
  return std::make_unique<UdpLink>(local, remote);
}

}  // namespace fireswarm::radio
