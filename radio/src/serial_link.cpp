// The serial transport: an RF modem (or a pseudo-terminal standing in for one) on
// a Boost.Asio serial_port, raw 8N1 without flow control (seed 5.3.1: the telemetry
// link runs at 57,600 baud). Reads stay outstanding asynchronously; writes are
// synchronous, because a burst is small and the modem's buffer takes it at once.
#include <termios.h>

#include <array>
#include <cerrno>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>

#include "asio.hpp"
#include "async_receiver.hpp"
#include "fireswarm/radio/link.hpp"

namespace fireswarm::radio {
namespace {

constexpr std::size_t kReadChunkBytes = 4096;

struct BaudSpeed {
  unsigned baud;
  speed_t speed;
};

// The standard speeds termios can set on Linux; anything else would need the
// non-portable BOTHER/termios2 route, which no RF modem we target needs.
constexpr std::array<BaudSpeed, 30> kBaudSpeeds{{
    {50, B50},           {75, B75},           {110, B110},         {134, B134},
    {150, B150},         {200, B200},         {300, B300},         {600, B600},
    {1200, B1200},       {1800, B1800},       {2400, B2400},       {4800, B4800},
    {9600, B9600},       {19200, B19200},     {38400, B38400},     {57600, B57600},
    {115200, B115200},   {230400, B230400},   {460800, B460800},   {500000, B500000},
    {576000, B576000},   {921600, B921600},   {1000000, B1000000}, {1152000, B1152000},
    {1500000, B1500000}, {2000000, B2000000}, {2500000, B2500000}, {3000000, B3000000},
    {3500000, B3500000}, {4000000, B4000000},
}};

speed_t SpeedOf(unsigned baud) {
  for (const BaudSpeed& entry : kBaudSpeeds) {
    if (entry.baud == baud) return entry.speed;
  }
  std::string supported;
  for (const BaudSpeed& entry : kBaudSpeeds) {
    supported += (supported.empty() ? "" : ", ") + std::to_string(entry.baud);
  }
  throw std::invalid_argument("serial baud " + std::to_string(baud) +
                              " is not a supported termios speed (supported: " + supported + ")");
}

// Raw 8N1, no parity, no hardware or software flow control, no modem control lines.
// termios directly (not Asio's options) so every flag is set in one place.
void ConfigureRaw8N1(int fd, speed_t speed, const std::string& name) {
  termios settings{};
  if (::tcgetattr(fd, &settings) != 0) {
    throw std::runtime_error(name + ": not a serial port: " + std::strerror(errno));
  }
  ::cfmakeraw(&settings);
  settings.c_cflag &= ~static_cast<tcflag_t>(PARENB | CSTOPB | CSIZE | CRTSCTS);
  settings.c_cflag |= CS8 | CREAD | CLOCAL;
  settings.c_iflag &= ~static_cast<tcflag_t>(IXON | IXOFF | IXANY);
  if (::cfsetispeed(&settings, speed) != 0 || ::cfsetospeed(&settings, speed) != 0 ||
      ::tcsetattr(fd, TCSANOW, &settings) != 0) {
    throw std::runtime_error(name + ": cannot set raw 8N1: " + std::strerror(errno));
  }
}

class SerialLink final : public IoLink {
 public:
  SerialLink(const std::string& device, unsigned baud)
      : name_("serial device " + device), port_(io_) {
    const speed_t speed = SpeedOf(baud);  // a bad baud fails before the device is touched
    boost::system::error_code error;
    port_.open(device, error);
    if (error) throw std::runtime_error(name_ + ": cannot open: " + error.message());
    ConfigureRaw8N1(port_.native_handle(), speed, name_);
    receiver_ = std::make_unique<detail::AsyncReceiver>(
        io_, name_, kReadChunkBytes,
        [this](boost::asio::mutable_buffer buffer, detail::AsyncReceiver::Completion done) {
          port_.async_read_some(buffer, std::move(done));
        });
  }

  void Transmit(Nanos /*now*/, Nanos /*start*/, std::span<const std::uint8_t> bytes) override {
    boost::system::error_code error;
    boost::asio::write(port_, boost::asio::buffer(bytes.data(), bytes.size()), error);
    if (error) throw std::runtime_error(name_ + ": write failed: " + error.message());
  }

  void Receive(Nanos /*now*/, std::vector<std::uint8_t>& out) override { receiver_->MoveTo(out); }

  bool WaitReadable(Nanos timeout) override { return receiver_->WaitReadable(timeout); }

 private:
  // Declaration order is destruction order in reverse: the receiver goes first,
  // then the port (aborting its read), then the io_context that owns the handler.
  std::string name_;
  boost::asio::io_context io_;
  boost::asio::serial_port port_;
  std::unique_ptr<detail::AsyncReceiver> receiver_;
};

}  // namespace

std::unique_ptr<IoLink> OpenSerialLink(const std::string& device, unsigned baud) {
  return std::make_unique<SerialLink>(device, baud);
}

}  // namespace fireswarm::radio
