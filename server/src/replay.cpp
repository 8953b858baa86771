// The replay adapter: the one place the command center meets lcm::LogFile.
#include "fireswarm/server/replay.hpp"

#include <algorithm>
#include <cstdio>
#include <lcm/lcm-cpp.hpp>
#include <stdexcept>
#include <string_view>
#include <system_error>

#include "fireswarm/server/lcm_bridge.hpp"

namespace fireswarm::server {

namespace {

[[noreturn]] void Fail(const std::filesystem::path& path, const std::string& problem) {
  throw std::runtime_error(path.string() + ": " + problem);
}

template <typename Message>
ReplayEvent Decode(const lcm::LogEvent& event, const std::filesystem::path& path) {
  Message message;
  if (message.decode(event.data, 0, event.datalen) != event.datalen) {
    Fail(path, "event " + std::to_string(event.eventnum) + " on " + event.channel +
                   " does not decode as " + Message::getTypeName() +
                   " (a log of another version of lcmtypes/, or a corrupt event)");
  }
  return ReplayEvent{static_cast<double>(message.utime) * 1e-6, std::move(message)};
}

// The event decoded by its channel; nullopt for a channel the command center does not read.
std::optional<ReplayEvent> DecodeEvent(const lcm::LogEvent& event,
                                       const std::filesystem::path& path) {
  const std::string_view channel = event.channel;
  if (channel == kVehicleStateChannel) return Decode<vehicle_state_t>(event, path);
  if (channel == kFireTracksChannel) return Decode<fire_track_list_t>(event, path);
  if (channel == kMissionStatusChannel) return Decode<mission_status_t>(event, path);
  if (channel == kRadioStatsChannel) return Decode<radio_stats_t>(event, path);
  if (channel == kPlanChannel) {
    const std::span<const std::uint8_t> bytes(static_cast<const std::uint8_t*>(event.data),
                                              static_cast<std::size_t>(event.datalen));
    if (!LcmStringsFit(bytes, kPlanStringsAt, 1)) {
      Fail(path, "event " + std::to_string(event.eventnum) + " on " + event.channel +
                     ": the geojson string's length does not fit the event (a corrupt event)");
    }
    return Decode<plan_t>(event, path);
  }
  if (channel == kCommandStatusChannel) return Decode<command_status_t>(event, path);
  if (channel == kConflictChannel) return Decode<conflict_t>(event, path);
  return std::nullopt;
}

}  // namespace

ReplayLog ReplayLog::Load(const std::filesystem::path& path) {
  std::error_code error;
  const std::uintmax_t size_bytes = std::filesystem::file_size(path, error);
  if (error) Fail(path, "cannot read the LCM log: " + error.message());
  lcm::LogFile file(path.string(), "r");
  if (!file.good()) Fail(path, "cannot open the LCM log");
  ReplayLog log;
  std::size_t read = 0;
  long end_of_last_event = 0;
  while (const lcm::LogEvent* event = file.readNextEvent()) {
    ++read;
    end_of_last_event = std::ftell(file.getFilePtr());
    if (std::optional<ReplayEvent> decoded = DecodeEvent(*event, path)) {
      log.events_.push_back(std::move(*decoded));
    } else {
      ++log.skipped_;
    }
  }
  if (read == 0 && size_bytes > 0) Fail(path, "not an LCM log: no event in it");
  if (read > 0 && static_cast<std::uintmax_t>(end_of_last_event) < size_bytes) {
    log.warning_ = path.string() + ": " +
                   std::to_string(size_bytes - static_cast<std::uintmax_t>(end_of_last_event)) +
                   " bytes after event " + std::to_string(read) +
                   " hold no event (cut short while written?); replaying the events before";
  }
  std::stable_sort(log.events_.begin(), log.events_.end(),
                   [](const ReplayEvent& a, const ReplayEvent& b) { return a.time_s < b.time_s; });
  return log;
}

double ReplayLog::start_s() const {
  return events_.empty() ? 0.0 : events_.front().time_s;
}

double ReplayLog::end_s() const {
  return events_.empty() ? 0.0 : events_.back().time_s;
}

std::size_t ReplayLog::Feed(CommandCenter& center, std::size_t next, double until_s) const {
  for (; next < events_.size() && events_[next].time_s <= until_s; ++next) {
    Apply(center, events_[next].message);
  }
  return next;
}

void Apply(CommandCenter& center, const ReplayMessage& message) {
  struct Visitor {
    CommandCenter& center;
    void operator()(const plan_t& m) const { center.OnPlan(m); }
    void operator()(const vehicle_state_t& m) const { center.OnVehicleState(m); }
    void operator()(const fire_track_list_t& m) const { center.OnFireTracks(m); }
    void operator()(const mission_status_t& m) const { center.OnMissionStatus(m); }
    void operator()(const radio_stats_t& m) const { center.OnRadioStats(m); }
    void operator()(const command_status_t& m) const { center.OnCommandStatus(m); }
    void operator()(const conflict_t& m) const { center.OnConflict(m); }
  };
  std::visit(Visitor{center}, message);
}

}  // namespace fireswarm::server
