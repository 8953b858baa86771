// Helpers for the tests of real links (serial on a pseudo-terminal, UDP on
// loopback): a deadline long enough for a loaded machine, and a read that waits
// on the link itself, never sleeps.
#pragma once

#include <chrono>
#include <cstdint>
#include <vector>

#include "fireswarm/radio/link.hpp"

namespace fireswarm::radio::io_link_testing {

/// How long a test waits for bytes that should come at once.
inline constexpr auto kDeadline = std::chrono::seconds(5);

/// Collects `size` bytes from the link, waiting with WaitReadable deadlines; fewer
/// if kDeadline passes first.
inline std::vector<std::uint8_t> ReceiveFrom(IoLink& link, std::size_t size) {
  using Clock = std::chrono::steady_clock;
  std::vector<std::uint8_t> bytes;
  const auto deadline = Clock::now() + kDeadline;
  while (bytes.size() < size && Clock::now() < deadline) {
    if (link.WaitReadable(deadline - Clock::now())) link.Receive(Nanos{0}, bytes);
  }
  return bytes;
}

}  // namespace fireswarm::radio::io_link_testing
