// The byte link between the server and vehicles: the same interface over the
// simulated shared channel, a serial RF modem (Boost.Asio serial_port) or UDP.
// The pure cores (scheduler, vehicle endpoint) produce bursts and consume bytes;
// a Link carries them. Asio stays inside the transport .cpp files.
#pragma once

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "fireswarm/radio/channel.hpp"
#include "fireswarm/radio/time.hpp"

namespace fireswarm::radio {

class Link {
 public:
  virtual ~Link() = default;
  /// Sends `bytes` as one burst. A simulated link starts it exactly at `start`;
  /// a real link sends at once (its modem adds the turnaround).
  virtual void Transmit(Nanos now, Nanos start, std::span<const std::uint8_t> bytes) = 0;
  /// Appends every byte received so far to `out`. Never blocks. An IoLink throws
  /// std::runtime_error naming its device or endpoint once its reads have failed.
  virtual void Receive(Nanos now, std::vector<std::uint8_t>& out) = 0;
};

/// A radio on a SharedChannel. The channel must outlive the link.
class SimLink final : public Link {
 public:
  SimLink(SharedChannel& channel, RadioId radio) : channel_(channel), radio_(radio) {}
  void Transmit(Nanos now, Nanos start, std::span<const std::uint8_t> bytes) override {
    channel_.Transmit(radio_, now, start, bytes);
  }
  void Receive(Nanos /*now*/, std::vector<std::uint8_t>& out) override {
    channel_.Drain(radio_, out);
  }
  RadioId radio() const { return radio_; }

 private:
  SharedChannel& channel_;
  RadioId radio_;
};

/// A link over real I/O that can also wait for bytes (for the wall-clock server,
/// `fireswarm serve`, and end-to-end tests).
class IoLink : public Link {
 public:
  /// Blocks until bytes are available or `timeout` (wall-clock) passes, returning
  /// as soon as they arrive; true when bytes wait. Throws as Receive().
  virtual bool WaitReadable(Nanos timeout) = 0;
};

/// Opens a serial device (e.g. /dev/ttyUSB0 or a pseudo-terminal) raw, 8N1, no flow
/// control, at `baud` bits/s. Transmit() writes the burst at once and synchronously.
/// Throws std::invalid_argument naming `baud` when termios has no such speed (50 to
/// 4,000,000: the standard rates), std::runtime_error naming the device when it
/// cannot be opened or is not a serial port.
std::unique_ptr<IoLink> OpenSerialLink(const std::string& device, unsigned baud);

/// Binds a UDP socket to `local` ("host:port", port 0 = any) and sends each burst as
/// one datagram to `remote` ("host:port"). Throws std::invalid_argument naming a
/// malformed endpoint, std::runtime_error naming one that cannot be resolved or
/// bound. UdpLink (udp_link.hpp) is the same link with its bound port exposed.
std::unique_ptr<IoLink> OpenUdpLink(const std::string& local, const std::string& remote);

}  // namespace fireswarm::radio
