// The UDP transport: one datagram per burst, for radio bridges on a LAN and for
// end-to-end tests on 127.0.0.1. Asio stays in udp_link.cpp (pimpl).
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "fireswarm/radio/link.hpp"
#include "fireswarm/radio/time.hpp"

namespace fireswarm::radio {

class UdpLink final : public IoLink {
 public:
  /// Largest burst one datagram carries over IPv4, in bytes.
  static constexpr std::size_t kMaxBurstBytes = 65'507;

  /// Binds to `local` ("host:port"; port 0 = an ephemeral port; empty host = any
  /// IPv4 address) and sends to `remote` ("host:port", port 1-65535). IPv6 hosts
  /// go in brackets: "[::1]:5000". Throws std::invalid_argument naming a malformed
  /// endpoint, std::runtime_error naming one that cannot be resolved or bound.
  UdpLink(const std::string& local, const std::string& remote);
  ~UdpLink() override;
  UdpLink(const UdpLink&) = delete;
  UdpLink& operator=(const UdpLink&) = delete;

  /// Sends `bytes` as one datagram to the remote at once (`now`, `start` unused).
  /// Throws std::invalid_argument above kMaxBurstBytes, std::runtime_error naming
  /// the remote when the send fails.
  void Transmit(Nanos now, Nanos start, std::span<const std::uint8_t> bytes) override;
  /// Appends the bytes of every datagram received so far from the remote, in arrival
  /// order; datagrams from any other address or port are dropped (foreign_datagrams()).
  void Receive(Nanos now, std::vector<std::uint8_t>& out) override;
  bool WaitReadable(Nanos timeout) override;

  /// Datagrams dropped because they did not come from the remote.
  std::uint64_t foreign_datagrams() const;
  /// The port the socket is bound to (the ephemeral one when `local` asked for 0).
  std::uint16_t local_port() const;
  /// Sends further bursts to `remote` ("host:port"); throws as the constructor.
  void SetRemote(const std::string& remote);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fireswarm::radio
