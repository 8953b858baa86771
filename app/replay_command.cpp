// `fireswarm replay LOG.lcmlog --http HOST:PORT`: a recorded mission (an LCM log
// written by `serve|run --log`) on the command-center page, read-only, with a
// timeline to play, pause and scrub (replay_feed.hpp). It starts paused at the
// log's start, so the operator picks where to look and how fast before anything
// moves; it pauses at the log's end and serves on until --duration-s of wall time
// passed or SIGINT/SIGTERM.
#include <algorithm>
#include <chrono>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli.hpp"
#include "commands.hpp"
#include "fireswarm/server/replay.hpp"
#include "replay_feed.hpp"
#include "stop_signals.hpp"
#include "web_flags.hpp"

namespace fireswarm::app {
namespace {

namespace po = boost::program_options;
using Clock = ReplayFeed::Clock;

constexpr const char* kName = "replay";
// The longest the loop waits for a page message: how soon it notices SIGINT/SIGTERM
// (the signal handler only sets a flag, which cannot wake the wait).
constexpr auto kMaxWait = std::chrono::milliseconds(250);

struct Flags {
  std::string log;
  double speed = 1.0;
  std::optional<double> duration_s;
  WebFlags web;
};

void CheckFlags(const Flags& f) {
  if (!(f.speed > 0.0 && f.speed <= ReplayFeed::kMaxSpeed)) {
    ThrowBadFlag(kName, "speed", "in (0, 1000]", FlagText(f.speed));
  }
  if (f.duration_s) {
    CheckFlagRange(kName, "duration-s", *f.duration_s, {0.0, kMaxCommandDurationS, true});
  }
  CheckWebFlags(kName, f.web);
  if (f.web.http.empty()) {
    throw UsageError(
        "fireswarm replay: --http HOST:PORT is required (the replay is shown on the "
        "command-center page)");
  }
}

server::ReplayLog LoadLog(const std::string& path) {
  server::ReplayLog log;
  try {
    log = server::ReplayLog::Load(path);
  } catch (const std::exception& e) {
    throw UsageError(std::string("fireswarm replay: ") + e.what());
  }
  if (log.events().empty()) {
    throw UsageError("fireswarm replay: " + path +
                     ": no command-center message (FIRESWARM_VEHICLE_STATE, ...) in it");
  }
  if (!log.warning().empty()) std::cerr << "replay: warning: " << log.warning() << std::endl;
  std::cout << "replay: " << path << ": " << log.events().size() << " messages from "
            << log.start_s() << " s to " << log.end_s() << " s (" << log.skipped()
            << " on other channels skipped)" << std::endl;
  return log;
}

// Serves the replay until the wall-time limit or a signal.
void Serve(ReplayFeed& feed, server::WebServer& web, const Flags& f) {
  const Clock::time_point start = Clock::now();
  const Clock::time_point end = f.duration_s
                                    ? start + std::chrono::duration_cast<Clock::duration>(
                                                  std::chrono::duration<double>(*f.duration_s))
                                    : Clock::time_point::max();
  while (!StopRequested()) {
    const Clock::time_point now = Clock::now();
    if (now >= end) break;
    const Clock::time_point wake = std::min({feed.NextDue(), end, now + kMaxWait});
    const auto wait = std::max(std::chrono::milliseconds(0),
                               std::chrono::ceil<std::chrono::milliseconds>(wake - now));
    for (const server::ClientMessage& message : web.TakeClientMessages(wait)) {
      feed.Handle(message, Clock::now());
    }
    feed.Advance(Clock::now());
  }
}

}  // namespace

int RunReplay(const std::vector<std::string>& args) {
  Flags f;
  po::options_description options("replay options");
  auto add = options.add_options();
  add("speed", po::value(&f.speed)->value_name("K"),
      "play at K times the wall clock (default 1; the page can change it)");
  add("duration-s",
      po::value<double>()->notifier([&f](double v) { f.duration_s = v; })->value_name("S"),
      "stop after S seconds of wall time (default: at SIGINT/SIGTERM)");
  AddWebOptions(options, f.web);
  add("log", po::value(&f.log)->required(), "the LCM log (written by serve|run --log)");
  po::positional_options_description positional;
  positional.add("log", 1);
  po::variables_map values;
  if (!ParseCommandLine(kName, "LOG.lcmlog --http HOST:PORT [--speed K] [--duration-s S]", options,
                        positional, args, values)) {
    return kExitOk;
  }
  CheckFlags(f);
  const server::ReplayLog log = LoadLog(f.log);
  const StopOnSignals stop;
  std::optional<ReplayFeed> feed;
  // The feed serves the log's start before the URL is printed.
  const std::unique_ptr<server::WebServer> web = StartWebServer(
      kName, f.web, true,
      [&](server::WebServer& started) { feed.emplace(log, started, f.speed, Clock::now()); });
  Serve(*feed, *web, f);
  return kExitOk;
}

}  // namespace fireswarm::app
