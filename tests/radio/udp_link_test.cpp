// UdpLink: two real links on 127.0.0.1 with ephemeral ports; waits use
// WaitReadable deadlines, never sleeps.
#include "fireswarm/radio/udp_link.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "radio/io_link_testing.hpp"

namespace fireswarm::radio {
namespace {

using std::chrono::milliseconds;
using Clock = std::chrono::steady_clock;

using io_link_testing::kDeadline;
using io_link_testing::ReceiveFrom;

std::string Loopback(std::uint16_t port) {
  return "127.0.0.1:" + std::to_string(port);
}

std::vector<std::uint8_t> SeededBytes(std::size_t size, std::uint8_t seed) {
  std::vector<std::uint8_t> bytes(size);
  for (std::size_t i = 0; i < size; ++i)
    bytes[i] = static_cast<std::uint8_t>((i * 13 + seed) & 0xFF);
  return bytes;
}

// Two links that send to each other. The first starts with a placeholder remote
// because the second's ephemeral port is known only once it is bound.
struct LinkPair {
  LinkPair() : a("127.0.0.1:0", Loopback(9)), b("127.0.0.1:0", Loopback(a.local_port())) {
    a.SetRemote(Loopback(b.local_port()));
  }
  UdpLink a;
  UdpLink b;
};

TEST(UdpLink, BindsToEphemeralPorts) {
  LinkPair links;
  EXPECT_NE(links.a.local_port(), 0);
  EXPECT_NE(links.b.local_port(), 0);
  EXPECT_NE(links.a.local_port(), links.b.local_port());
}

TEST(UdpLink, ExchangesBurstsBothWays) {
  LinkPair links;
  std::vector<std::uint8_t> sent;
  for (std::uint8_t i = 0; i < 3; ++i) {
    const std::vector<std::uint8_t> burst = SeededBytes(20 + i, i);
    links.a.Transmit(Nanos{0}, Nanos{0}, burst);
    sent.insert(sent.end(), burst.begin(), burst.end());
  }
  EXPECT_EQ(ReceiveFrom(links.b, sent.size()), sent);

  const std::vector<std::uint8_t> reply = SeededBytes(7, 99);
  links.b.Transmit(Nanos{0}, Nanos{0}, reply);
  EXPECT_EQ(ReceiveFrom(links.a, reply.size()), reply);
}

TEST(UdpLink, CarriesALongBurstInOneDatagram) {
  LinkPair links;
  const std::vector<std::uint8_t> burst = SeededBytes(4'000, 1);
  links.b.Transmit(Nanos{0}, Nanos{0}, burst);
  ASSERT_TRUE(links.a.WaitReadable(kDeadline));
  std::vector<std::uint8_t> received;
  links.a.Receive(Nanos{0}, received);
  EXPECT_EQ(received, burst);  // whole after one wait: it was one datagram
}

TEST(UdpLink, ReceiveNeverBlocksAndWaitReadableKeepsItsDeadline) {
  LinkPair links;
  std::vector<std::uint8_t> out;
  links.a.Receive(Nanos{0}, out);
  EXPECT_TRUE(out.empty());
  const auto before = Clock::now();
  EXPECT_FALSE(links.a.WaitReadable(milliseconds(30)));
  const auto waited = Clock::now() - before;
  EXPECT_GE(waited, milliseconds(30));
  EXPECT_LT(waited, kDeadline);
}

TEST(UdpLink, OpenUdpLinkGivesAWorkingIoLink) {
  UdpLink peer("127.0.0.1:0", Loopback(9));
  const std::unique_ptr<IoLink> link = OpenUdpLink("127.0.0.1:0", Loopback(peer.local_port()));
  peer.SetRemote(Loopback(dynamic_cast<UdpLink&>(*link).local_port()));
  link->Transmit(Nanos{0}, Nanos{0}, SeededBytes(5, 0));
  EXPECT_EQ(ReceiveFrom(peer, 5), SeededBytes(5, 0));
}

TEST(UdpLink, DatagramsFromAnyOtherPortAreDroppedAndCounted) {
  LinkPair links;
  UdpLink intruder("127.0.0.1:0", Loopback(links.b.local_port()));
  for (int i = 0; i < 80; ++i) intruder.Transmit(Nanos{0}, Nanos{0}, SeededBytes(30, 7));
  // The genuine peer's datagram, sent after the forgeries, is all that arrives.
  const std::vector<std::uint8_t> genuine = SeededBytes(9, 1);
  links.a.Transmit(Nanos{0}, Nanos{0}, genuine);
  EXPECT_EQ(ReceiveFrom(links.b, genuine.size()), genuine);
  std::vector<std::uint8_t> rest;
  links.b.Receive(Nanos{0}, rest);
  EXPECT_TRUE(rest.empty());
  EXPECT_EQ(links.b.foreign_datagrams(), 80U);
}

TEST(UdpLink, OversizedBurstIsRejected) {
  LinkPair links;
  EXPECT_THROW(links.a.Transmit(Nanos{0}, Nanos{0}, SeededBytes(UdpLink::kMaxBurstBytes + 1, 0)),
               std::invalid_argument);
}

// Expects opening with these endpoints to throw `Error` naming `named`.
template <typename Error>
void ExpectAddressesRejected(const std::string& local, const std::string& remote,
                             const std::string& named) {
  try {
    UdpLink link(local, remote);
    ADD_FAILURE() << "opened " << local << " -> " << remote;
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find(named), std::string::npos) << error.what();
  }
}

TEST(UdpLink, MalformedEndpointsAreNamed) {
  const std::string good = "127.0.0.1:0";
  for (const std::string bad : {"127.0.0.1", "127.0.0.1:", "127.0.0.1:abc", "127.0.0.1:70000",
                                "127.0.0.1:-1", "::1:5000"}) {
    ExpectAddressesRejected<std::invalid_argument>(bad, Loopback(9), bad);
    ExpectAddressesRejected<std::invalid_argument>(good, bad, bad);
  }
  ExpectAddressesRejected<std::invalid_argument>(good, "127.0.0.1:0",
                                                 "127.0.0.1:0");  // cannot send to 0
  UdpLink link(good, Loopback(9));
  EXPECT_THROW(link.SetRemote("nowhere"), std::invalid_argument);
}

TEST(UdpLink, PortInUseIsNamed) {
  UdpLink first("127.0.0.1:0", Loopback(9));
  const std::string taken = Loopback(first.local_port());
  ExpectAddressesRejected<std::runtime_error>(taken, Loopback(9), taken);
}

}  // namespace
}  // namespace fireswarm::radio
