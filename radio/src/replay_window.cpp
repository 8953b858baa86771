#include "fireswarm/radio/replay_window.hpp"

#include <cassert>

namespace fireswarm::radio {

bool ReplayWindow::IsFresh(std::uint32_t counter) const {
  if (counter < floor_) return false;
  if (!any_ || counter > highest_) return true;
  const std::uint32_t age = highest_ - counter;
  if (age >= kSize) return false;
  return ((seen_ >> age) & 1U) == 0;
}

void ReplayWindow::Mark(std::uint32_t counter) {
  assert(IsFresh(counter));
  if (!any_) {
    any_ = true;
    highest_ = counter;
    seen_ = 1;
    return;
  }
  if (counter > highest_) {
    const std::uint32_t shift = counter - highest_;
    seen_ = shift >= kSize ? 0 : seen_ << shift;
    seen_ |= 1;
    highest_ = counter;
    return;
  }
  seen_ |= std::uint64_t{1} << (highest_ - counter);
}

}  // namespace fireswarm::radio
