// The serial link (OpenSerialLink) against a real pseudo-terminal pair: the link
// opens the slave like a modem's /dev/ttyUSB0; the test plays the modem on the
// master side with poll(2) deadlines, so nothing sleeps and nothing hangs.
#include <gtest/gtest.h>
#include <poll.h>
#include <pty.h>
#include <termios.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "fireswarm/radio/link.hpp"
#include "radio/io_link_testing.hpp"

namespace fireswarm::radio {
namespace {

using std::chrono::milliseconds;
using Clock = std::chrono::steady_clock;

constexpr unsigned kModemBaud = 57'600;
using io_link_testing::kDeadline;
using io_link_testing::ReceiveFrom;

// Every byte value, including XON/XOFF, CR and NL, which a cooked tty would eat.
std::vector<std::uint8_t> EveryByteValue(std::size_t size) {
  std::vector<std::uint8_t> bytes(size);
  for (std::size_t i = 0; i < size; ++i)
    bytes[i] = static_cast<std::uint8_t>((i * 7 + i / 256) & 0xFF);
  return bytes;
}

int MillisecondsLeft(Clock::time_point deadline) {
  const auto left = std::chrono::duration_cast<milliseconds>(deadline - Clock::now()).count();
  return left > 0 ? static_cast<int>(left) : 0;
}

// A pseudo-terminal pair; the test plays the modem on the master side.
class PseudoTerminal {
 public:
  PseudoTerminal() {
    std::vector<char> name(256);
    if (::openpty(&master_, &slave_, name.data(), nullptr, nullptr) != 0) {
      throw std::runtime_error("openpty failed");
    }
    slave_name_ = name.data();
    termios raw{};
    ::tcgetattr(master_, &raw);
    ::cfmakeraw(&raw);
    ::tcsetattr(master_, TCSANOW, &raw);
  }
  ~PseudoTerminal() {
    CloseMaster();
    ::close(slave_);
  }
  PseudoTerminal(const PseudoTerminal&) = delete;
  PseudoTerminal& operator=(const PseudoTerminal&) = delete;

  const std::string& slave_name() const { return slave_name_; }
  int slave_fd() const { return slave_; }
  void CloseMaster() {
    if (master_ >= 0) ::close(master_);
    master_ = -1;
  }

  // Reads `size` bytes from the master, or what arrived before the deadline.
  std::vector<std::uint8_t> Read(std::size_t size) const {
    std::vector<std::uint8_t> bytes;
    const auto deadline = Clock::now() + kDeadline;
    while (bytes.size() < size) {
      pollfd readable{master_, POLLIN, 0};
      if (::poll(&readable, 1, MillisecondsLeft(deadline)) <= 0) break;
      std::uint8_t chunk[512];
      const ssize_t got = ::read(master_, chunk, sizeof chunk);
      if (got <= 0) break;
      bytes.insert(bytes.end(), chunk, chunk + got);
    }
    return bytes;
  }

  void Write(const std::vector<std::uint8_t>& bytes) const {
    const auto deadline = Clock::now() + kDeadline;
    std::size_t written = 0;
    while (written < bytes.size()) {
      pollfd writable{master_, POLLOUT, 0};
      ASSERT_GT(::poll(&writable, 1, MillisecondsLeft(deadline)), 0) << "master not writable";
      const ssize_t put = ::write(master_, bytes.data() + written, bytes.size() - written);
      ASSERT_GT(put, 0);
      written += static_cast<std::size_t>(put);
    }
  }

 private:
  int master_ = -1;
  int slave_ = -1;
  std::string slave_name_;
};

TEST(SerialLink, ExchangesBytesBothWays) {
  PseudoTerminal modem;
  const auto link = OpenSerialLink(modem.slave_name(), kModemBaud);
  const std::vector<std::uint8_t> to_modem{0x70, 0x96, 0xAC, 0x01, 0x10, 0x00, 0x11};
  link->Transmit(Nanos{0}, Nanos{0}, to_modem);
  EXPECT_EQ(modem.Read(to_modem.size()), to_modem);

  const std::vector<std::uint8_t> from_modem{0x0D, 0x0A, 0x11, 0x13, 0x03, 0x00, 0xFF};
  modem.Write(from_modem);
  EXPECT_EQ(ReceiveFrom(*link, from_modem.size()), from_modem);
}

TEST(SerialLink, CarriesALongBurstIntactBothWays) {
  PseudoTerminal modem;
  const auto link = OpenSerialLink(modem.slave_name(), kModemBaud);
  const std::vector<std::uint8_t> burst = EveryByteValue(1'500);
  link->Transmit(Nanos{0}, Nanos{0}, burst);
  EXPECT_EQ(modem.Read(burst.size()), burst);
  modem.Write(burst);
  EXPECT_EQ(ReceiveFrom(*link, burst.size()), burst);
}

TEST(SerialLink, ReceiveNeverBlocksAndWaitReadableKeepsItsDeadline) {
  PseudoTerminal modem;
  const auto link = OpenSerialLink(modem.slave_name(), kModemBaud);
  std::vector<std::uint8_t> out;
  link->Receive(Nanos{0}, out);
  EXPECT_TRUE(out.empty());
  const auto before = Clock::now();
  EXPECT_FALSE(link->WaitReadable(milliseconds(30)));
  const auto waited = Clock::now() - before;
  EXPECT_GE(waited, milliseconds(30));
  EXPECT_LT(waited, kDeadline);
}

TEST(SerialLink, ConfiguresRaw8N1AtTheBaud) {
  PseudoTerminal modem;
  const auto link = OpenSerialLink(modem.slave_name(), kModemBaud);
  termios settings{};
  ASSERT_EQ(::tcgetattr(modem.slave_fd(), &settings), 0);
  EXPECT_EQ(::cfgetospeed(&settings), B57600);
  EXPECT_EQ(settings.c_cflag & CSIZE, static_cast<tcflag_t>(CS8));
  EXPECT_EQ(settings.c_cflag & (PARENB | CSTOPB | CRTSCTS), 0U);
  EXPECT_EQ(settings.c_iflag & (IXON | IXOFF | ICRNL), 0U);
  EXPECT_EQ(settings.c_lflag & (ICANON | ECHO), 0U);
}

TEST(SerialLink, HangUpIsAnErrorNamingTheDevice) {
  PseudoTerminal modem;
  const auto link = OpenSerialLink(modem.slave_name(), kModemBaud);
  modem.CloseMaster();
  try {
    link->WaitReadable(kDeadline);
    ADD_FAILURE() << "no error after the master closed";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find(modem.slave_name()), std::string::npos)
        << error.what();
  }
}

TEST(SerialLink, UnsupportedBaudIsRejectedByName) {
  PseudoTerminal modem;
  try {
    OpenSerialLink(modem.slave_name(), 12'345);
    ADD_FAILURE() << "accepted 12345 baud";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("12345"), std::string::npos) << error.what();
  }
}

// Expects OpenSerialLink(device) to fail with a message naming the device.
void ExpectFailsNaming(const std::string& device) {
  try {
    OpenSerialLink(device, kModemBaud);
    ADD_FAILURE() << "opened " << device;
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find(device), std::string::npos) << error.what();
  }
}

TEST(SerialLink, BadDevicePathIsNamed) {
  ExpectFailsNaming("/nonexistent/ttyFIRESWARM0");
}

TEST(SerialLink, DeviceThatIsNotATerminalIsNamed) {
  ExpectFailsNaming("/dev/null");
}

}  // namespace
}  // namespace fireswarm::radio
