// The server on several radio channels (issue 21): each channel is stepped on its
// own bytes; the registry, the mission, commands and reports are the fleet's, and
// the ChannelRouter sends every request on its vehicle's channel.
#include <algorithm>
#include <span>
#include <vector>

#include "fireswarm/server/server.hpp"

namespace fireswarm::server {

std::vector<radio::SchedulerConfig> ServerConfig::ChannelConfigs() const {
  if (channels.empty()) return {radio};
  std::vector<radio::SchedulerConfig> out(channels.size(), radio);
  for (std::size_t k = 0; k < channels.size(); ++k) out[k].timing = channels[k];
  return out;
}

std::vector<radio::Burst> Server::Step(common::Nanos now, std::span<const std::uint8_t> received) {
  return Step(now, 0, received);
}

common::Nanos Server::NextWakeup(std::size_t channel) const {
  common::Nanos next = scheduler_->NextWakeup(channel);
  if (mission_) next = std::min(next, mission_->NextWakeup());
  return investigations_.NextVerdict(fusion_, next);
}

common::Nanos Server::NextWakeup() const {
  common::Nanos next = common::Nanos::max();
  for (std::size_t k = 0; k < scheduler_->channel_count(); ++k) {
    next = std::min(next, NextWakeup(k));
  }
  return next;
}

}  // namespace fireswarm::server
