#include "serve_loop.hpp"

#include <algorithm>
#include <chrono>
#include <iostream>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <variant>
#include <vector>

#include "fireswarm/common/time.hpp"
#include "fireswarm/radio/messages.hpp"
#include "fireswarm/server/vehicle_task.hpp"
#include "stop_signals.hpp"

namespace fireswarm::app {
namespace {

using common::Nanos;
using Clock = std::chrono::steady_clock;

// The loop wakes at least this often: to see a stop signal, and operator
// commands arriving on LCM (the wait is on the radio link only).
constexpr Nanos kMaxWait = std::chrono::milliseconds(50);
// Several links: how long the loop waits on one before it looks at the next.
constexpr Nanos kLinkSlice = std::chrono::milliseconds(1);

std::int64_t UnixMicros() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

}  // namespace

const char* ToString(ServeStop stop) {
  switch (stop) {
    case ServeStop::kSignal:
      return "signal";
    case ServeStop::kDuration:
      return "duration";
    case ServeStop::kComplete:
      return "complete";
    case ServeStop::kAborted:
      return "aborted";
  }
  return "unknown";
}

nlohmann::ordered_json EventLine(const server::JournalEntry& entry) {
  nlohmann::ordered_json line;
  const std::string kind = server::JournalKindOf(entry);
  const nlohmann::json data = server::JournalDataOf(entry);
  line["event"] = kind;
  line["t_s"] = entry.t_s;
  if (kind == "phase") {
    line["vehicle"] = data.at("vehicle");
    line["phase"] = server::ToString(static_cast<server::DronePhase>(data.at("phase").get<int>()));
  } else if (kind == "state") {
    line["state"] =
        server::ToString(static_cast<server::MissionState>(data.at("state").get<int>()));
  } else if (kind == "mission") {
    nlohmann::ordered_json drones = nlohmann::ordered_json::array();
    for (const nlohmann::json& drone : data.at("drones")) {
      drones.push_back(
          {{"vehicle", drone.at("vehicle")}, {"waypoints", drone.at("waypoints").size()}});
    }
    line["drones"] = std::move(drones);
  } else if (kind == "report") {
    line["vehicle"] = data.at("vehicle");
    line["report_id"] = data.at("report_id");
  } else if (data.is_object()) {
    for (const auto& [key, value] : data.items()) line[key] = value;
  }
  return line;
}

ServeLoop::ServeLoop(server::Server& server, std::vector<radio::IoLink*> links,
                     server::Journal* journal, server::LcmBridge* bridge)
    : server_(server),
      links_(std::move(links)),
      failed_(links_.size(), false),
      journal_(journal),
      bridge_(bridge),
      sent_parser_(server.scheduler().config().checksum) {}

void ServeLoop::FlushJournal() {
  for (const server::JournalEntry& entry : server_.TakeJournalEntries()) {
    if (journal_ != nullptr) {
      server::AppendEntry(*journal_, entry);
      ++journal_appended_;
    }
    std::cout << EventLine(entry).dump() << std::endl;
  }
}

void ServeLoop::CountFrames(const radio::Burst& burst) {
  sent_parser_.Feed(burst.bytes, [&](const radio::FrameView& frame) {
    const auto name = radio::MessageName(frame.message_id);
    ++frames_sent_[name ? std::string(*name) : std::to_string(frame.message_id)];
  });
}

void ServeLoop::HandleOperatorCommands(Nanos now) {
  if (bridge_ == nullptr) return;
  for (server::IncomingCommand& incoming : bridge_->TakeCommands()) {
    nlohmann::ordered_json line;
    line["event"] = "operator_command";
    line["t_s"] = common::ToSeconds(now);
    if (auto* refused = std::get_if<server::CommandRefused>(&incoming)) {
      line["command"] = refused->command;
      line["operator"] = refused->operator_id;
      line["accepted"] = false;
      line["why"] = refused->why;
      server_.Refuse(std::move(*refused), now);
    } else {
      const auto& command = std::get<server::SignedCommand>(incoming);
      std::string why;
      // The window is on the LCM clock: the Unix-epoch wall clock (docs/lcm.md).
      const bool accepted = server_.HandleSigned(command, now, UnixMicros(), &why);
      line["command"] = static_cast<int>(command.command.kind);
      line["operator"] = command.credentials.operator_id.substr(0, server::kMaxOperatorIdBytes);
      line["accepted"] = accepted;
      if (!accepted) line["why"] = why;
    }
    std::cout << line.dump() << std::endl;
  }
}

void ServeLoop::WatchAuthentication(Nanos now) {
  const radio::FrameSecurity* security = server_.scheduler().config().security.get();
  if (security == nullptr) return;
  for (const auto& [key_id, stats] : security->stats()) {
    if (key_id == radio::kBroadcastKeyId) continue;
    const radio::KeyLinkState state = radio::LinkStateOf(stats);
    const auto [it, first] = auth_states_.try_emplace(key_id, radio::KeyLinkState::kUnheard);
    if (!first && it->second == state) continue;
    if (first && state == radio::KeyLinkState::kUnheard) continue;
    it->second = state;
    nlohmann::ordered_json line;
    line["event"] = "radio_auth";
    line["t_s"] = common::ToSeconds(now);
    line["vehicle"] = key_id;
    line["state"] = std::string(radio::ToString(state));
    line["auth_failures"] = stats.auth_failures;
    line["replays"] = stats.replays;
    line["no_key"] = stats.no_key;
    std::cerr << line.dump() << std::endl;
  }
}

void ServeLoop::StepChannel(std::size_t channel, Nanos now, std::vector<std::uint8_t>& received) {
  received.clear();
  radio::IoLink& link = *links_[channel];
  try {
    if (!failed_[channel]) link.Receive(now, received);
  } catch (const std::runtime_error& e) {
    // A dead modem: its channel goes silent (its vehicles lost), the others fly on.
    failed_[channel] = true;
    nlohmann::ordered_json line;
    line["event"] = "link_failed";
    line["t_s"] = common::ToSeconds(now);
    line["channel"] = channel;
    line["why"] = e.what();
    std::cout << line.dump() << std::endl;
  }
  for (const radio::Burst& burst : server_.Step(now, channel, received)) {
    if (!failed_[channel]) link.Transmit(now, burst.start, burst.bytes);
    CountFrames(burst);
  }
}

void ServeLoop::WaitReadable(Nanos timeout) {
  std::vector<radio::IoLink*> live;
  for (std::size_t k = 0; k < links_.size(); ++k) {
    if (!failed_[k]) live.push_back(links_[k]);
  }
  if (live.size() == 1) {
    live.front()->WaitReadable(timeout);
    return;
  }
  // Several links: wait on each in turn in short slices (a link can wait only
  // on itself), so bytes on any are taken within a slice.
  const auto deadline = Clock::now() + timeout;
  while (!live.empty()) {
    for (radio::IoLink* link : live) {
      const Nanos left = std::chrono::duration_cast<Nanos>(deadline - Clock::now());
      if (left <= Nanos{0}) return;
      try {
        if (link->WaitReadable(std::min(left, kLinkSlice))) return;
      } catch (const std::runtime_error&) {
        return;  // StepChannel reports it
      }
    }
  }
  std::this_thread::sleep_for(timeout);  // every link failed: the loop still keeps time
}

ServeStop ServeLoop::Run(const ServeOptions& options) {
  const Clock::time_point start = Clock::now();
  const auto now = [&] { return options.clock_offset + (Clock::now() - start); };
  // Wall time since the start; Nanos::max(): no limit.
  const Nanos end = options.duration_s ? common::FromSeconds(*options.duration_s) : Nanos::max();
  // LCM utime: the Unix-epoch wall clock; mission time 0 is this far back.
  const std::int64_t utime_at_zero =
      UnixMicros() -
      std::chrono::duration_cast<std::chrono::microseconds>(options.clock_offset).count();
  std::vector<std::uint8_t> received;
  ServeStop stop = ServeStop::kSignal;
  while (true) {
    if (StopRequested()) {
      stop = ServeStop::kSignal;
      break;
    }
    const Nanos t = now();
    HandleOperatorCommands(t);
    for (std::size_t k = 0; k < links_.size(); ++k) StepChannel(k, t, received);
    FlushJournal();  // durable before anything else happens
    WatchAuthentication(t);
    if (bridge_ != nullptr)
      bridge_->Publish(server_, common::ToSeconds(t), UnixMicros(), utime_at_zero);
    if (options.on_step) {
      options.on_step(t, UnixMicros(), utime_at_zero);
      FlushJournal();  // what commands from the page made the server journal
    }
    clock_s_ = common::ToSeconds(t);

    const server::MissionState state = server_.state();
    if (options.until_complete && state == server::MissionState::kComplete) {
      stop = ServeStop::kComplete;
      break;
    }
    if (options.until_complete && state == server::MissionState::kAborted) {
      stop = ServeStop::kAborted;
      break;
    }
    const Nanos elapsed = Clock::now() - start;
    if (elapsed >= end) {
      stop = ServeStop::kDuration;
      break;
    }
    Nanos next = std::min(server_.NextWakeup(),
                          now() + std::min(kMaxWait, common::FromSeconds(options.max_wait_s)));
    if (bridge_ != nullptr) {
      next = std::min(next, common::FromSeconds(std::min(bridge_->NextPublishS(), 1e9)));
    }
    if (end != Nanos::max()) next = std::min(next, options.clock_offset + end);
    WaitReadable(std::max(Nanos{0}, next - now()));
  }
  wall_seconds_ = common::ToSeconds(Clock::now() - start);
  return stop;
}

nlohmann::ordered_json ServeLoop::Summary() const {
  nlohmann::ordered_json j;
  j["event"] = "summary";
  j["state"] = server::ToString(server_.state());
  j["wall_seconds"] = wall_seconds_;
  j["mission_clock_s"] = clock_s_;
  j["mission_seconds"] =
      server_.state() == server::MissionState::kIdle ? 0.0 : clock_s_ - server_.mission_started_s();
  nlohmann::ordered_json vehicles = nlohmann::ordered_json::array();
  for (const std::uint8_t id : server_.registry().ids()) {
    nlohmann::ordered_json v;
    v["id"] = id;
    v["link"] = std::string(server::ToString(server_.registry().LinkAt(id, clock_s_)));
    v["channel"] = server_.scheduler().ChannelOf(id);
    if (const radio::FrameSecurity* security = server_.scheduler().config().security.get()) {
      const auto found = security->stats().find(id);
      v["radio_auth"] = std::string(radio::ToString(found == security->stats().end()
                                                        ? radio::KeyLinkState::kUnheard
                                                        : radio::LinkStateOf(found->second)));
    }
    if (const server::MissionManager* mission = server_.mission()) {
      const auto ids = mission->vehicles();
      if (std::find(ids.begin(), ids.end(), id) != ids.end()) {
        const server::DroneProgress& progress = mission->progress(id);
        v["phase"] = server::ToString(progress.phase);
        v["waypoint_index"] = progress.waypoint_index;
        v["waypoints"] = progress.waypoint_count;
        // Sorties as the task view counts them (from 1; 0 on the ground between).
        const server::TaskView task = server::TaskOf(server_, id, clock_s_);
        v["sortie"] = task.sortie;
        v["sorties_flown"] = task.sorties_flown;
        v["sorties"] = task.sortie_count;
        if (!progress.failure.empty()) v["failure"] = progress.failure;
      }
    }
    vehicles.push_back(std::move(v));
  }
  j["vehicles"] = std::move(vehicles);
  nlohmann::ordered_json tracks = nlohmann::ordered_json::array();
  for (const server::FireTrack& track : server_.fusion().tracks()) {
    const common::LatLon at =
        server_.frame().ToGeodetic({track.position_en_m.x(), track.position_en_m.y()});
    tracks.push_back({{"id", track.track_id},
                      {"status", std::string(server::ToString(track.status))},
                      {"lat_deg", at.lat_deg},
                      {"lon_deg", at.lon_deg},
                      {"reports", track.report_count},
                      {"vehicles", track.vehicle_ids},
                      {"first_seen_s", track.first_seen_s}});
  }
  j["tracks"] = std::move(tracks);
  j["frames_sent"] = frames_sent_;
  const radio::SchedulerStats stats = server_.scheduler().stats();
  j["radio"] = {{"channels", server_.scheduler().channel_count()},
                {"bytes_sent", server_.bytes_sent()},
                {"bytes_received", server_.bytes_received()},
                {"requests_sent", stats.requests_sent},
                {"retries", stats.retries},
                {"requests_failed", stats.requests_failed},
                {"replies", stats.replies},
                {"missed_replies", stats.missed_replies},
                {"telemetry", stats.telemetry},
                {"fire_reports", stats.fire_reports},
                {"secured", server_.scheduler().config().security != nullptr},
                {"refused_frames", stats.refused_frames},
                {"out_of_turn", stats.out_of_turn},
                {"seal_failures", stats.seal_failures}};
  j["journal_records_appended"] = journal_appended_;
  return j;
}

}  // namespace fireswarm::app
