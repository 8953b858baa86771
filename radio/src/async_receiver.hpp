// Private to the radio module. Keeps one asynchronous read outstanding on an Asio
// I/O object (serial port, UDP socket) and buffers what it returns, so a link's
// Receive() never blocks and WaitReadable() waits on a deadline instead of sleeping.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "asio.hpp"
#include "fireswarm/radio/time.hpp"

namespace fireswarm::radio::detail {

class AsyncReceiver {
 public:
  using Completion = std::function<void(const boost::system::error_code&, std::size_t)>;
  /// Starts one asynchronous read into `buffer` that calls `done` on completion.
  using StartRead = std::function<void(boost::asio::mutable_buffer buffer, Completion done)>;

  /// `name` (e.g. "serial device /dev/ttyUSB0") prefixes error messages;
  /// `chunk_bytes` bounds one read (a whole datagram for UDP). Starts reading at once.
  AsyncReceiver(boost::asio::io_context& io, std::string name, std::size_t chunk_bytes,
                StartRead start_read)
      : io_(io), name_(std::move(name)), chunk_(chunk_bytes), start_read_(std::move(start_read)) {
    StartNextRead();
  }
  AsyncReceiver(const AsyncReceiver&) = delete;
  AsyncReceiver& operator=(const AsyncReceiver&) = delete;

  /// Appends every byte read so far to `out` without blocking.
  /// Throws std::runtime_error naming the link when the read failed and nothing is left.
  void MoveTo(std::vector<std::uint8_t>& out) {
    RunReadyHandlers();
    ThrowIfFailedAndEmpty();
    out.insert(out.end(), received_.begin(), received_.end());
    received_.clear();
  }

  /// True as soon as bytes wait, false once `timeout` passed without any.
  /// Throws std::runtime_error naming the link when the read failed.
  bool WaitReadable(Nanos timeout) {
    RunReadyHandlers();
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (received_.empty() && reading_) {
      if (io_.stopped()) io_.restart();
      if (io_.run_one_until(deadline) == 0) break;  // deadline passed
    }
    ThrowIfFailedAndEmpty();
    return !received_.empty();
  }

 private:
  void StartNextRead() {
    reading_ = true;
    start_read_(boost::asio::buffer(chunk_), [this](const boost::system::error_code& error,
                                                    std::size_t bytes) { OnRead(error, bytes); });
  }

  void OnRead(const boost::system::error_code& error, std::size_t bytes) {
    reading_ = false;
    if (error) {
      // Aborted reads come from closing the I/O object: not a failure of the link.
      if (error != boost::asio::error::operation_aborted) error_ = error;
      return;
    }
    const auto first = chunk_.begin();
    received_.insert(received_.end(), first, first + static_cast<std::ptrdiff_t>(bytes));
    StartNextRead();
  }

  void RunReadyHandlers() {
    if (io_.stopped()) io_.restart();
    io_.poll();
  }

  void ThrowIfFailedAndEmpty() const {
    if (error_ && received_.empty()) {
      throw std::runtime_error(name_ + ": read failed: " + error_.message());
    }
  }

  boost::asio::io_context& io_;
  std::string name_;
  std::vector<std::uint8_t> chunk_;
  StartRead start_read_;
  std::vector<std::uint8_t> received_;
  boost::system::error_code error_;
  bool reading_ = false;
};

}  // namespace fireswarm::radio::detail
