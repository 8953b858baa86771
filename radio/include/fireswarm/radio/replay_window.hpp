// Sliding replay window over 32-bit frame counters (RFC 4303 3.4.3 style): the
// highest counter accepted and a 64-bit bitmap of the 64 counters up to it. A
// counter is accepted once; one older than the window is refused. Pure; the caller
// checks a counter before it authenticates the frame and marks it only after.
#pragma once

#include <cstdint>

namespace fireswarm::radio {

class ReplayWindow {
 public:
  static constexpr std::uint32_t kSize = 64;  ///< counters remembered below the highest

  /// A window that refuses every counter below `floor` (persisted across restarts).
  explicit ReplayWindow(std::uint32_t floor = 0) : floor_(floor) {}

  /// Whether `counter` is new: at or above the floor, not seen, not too old.
  bool IsFresh(std::uint32_t counter) const;
  /// Records `counter` as seen. Precondition: IsFresh(counter).
  void Mark(std::uint32_t counter);
  /// The lowest counter a restarted receiver may accept: one past the highest seen.
  std::uint32_t NextFloor() const { return any_ ? highest_ + 1 : floor_; }

 private:
  std::uint32_t floor_;
  bool any_ = false;
  std::uint32_t highest_ = 0;
  std::uint64_t seen_ = 0;  // bit k: highest_ - k was accepted
};

}  // namespace fireswarm::radio
