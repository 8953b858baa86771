// End-to-end tests of `fireswarm serve` and `fireswarm sim`: the real server and
// a simulated fleet as two processes on the two ends of a serial line made of
// pseudo-terminals. Each process opens a pty's slave as its serial device; a
// relay thread in the test copies bytes between the two masters, as a null-modem
// cable (or `socat pty pty`) would. Every wait has a deadline (poll() on a
// pipe); none sleeps.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <pty.h>
#include <sys/stat.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <lcm/lcm-cpp.hpp>
#include <nlohmann/json.hpp>
#include <optional>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "app/fireswarm_process.hpp"
#include "app/http_fetch.hpp"
#include "app/run_fireswarm.hpp"
#include "fireswarm/common/angles.hpp"
#include "fireswarm/common/secret_key.hpp"
#include "fireswarm/operator_command_t.hpp"
#include "fireswarm/server/command_auth.hpp"
#include "fireswarm/server/lcm_bridge.hpp"
#include "fireswarm/server/web_command.hpp"

namespace fireswarm::app {
namespace {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
using Clock = std::chrono::steady_clock;
using Json = nlohmann::json;
using std::chrono::seconds;

constexpr double kLaunchLat = 46.5;
constexpr double kLaunchLon = 7.5;
constexpr double kMetresPerDegLat = 111'320.0;
// Faster than real time, slow enough for two cameras on a loaded 2-core machine.
constexpr const char* kSimSpeed = "20";
constexpr auto kMissionDeadline = seconds(90);
constexpr auto kStartDeadline = seconds(30);
constexpr auto kExitDeadline = seconds(10);

// A point `east_m`, `north_m` from the launch site, "lat,lon".
std::string LatLonText(double east_m, double north_m) {
  const double lat = kLaunchLat + north_m / kMetresPerDegLat;
  const double lon =
      kLaunchLon + east_m / (kMetresPerDegLat * std::cos(common::DegToRad(kLaunchLat)));
  return std::to_string(lat) + "," + std::to_string(lon);
}

// A 300 m x 200 m forest just east of the launch site, as GeoJSON.
std::string SmallArea() {
  Json ring = Json::array();
  for (const auto& [e, n] : std::vector<std::pair<double, double>>{
           {20, -100}, {320, -100}, {320, 100}, {20, 100}, {20, -100}}) {
    const double lat = kLaunchLat + n / kMetresPerDegLat;
    const double lon = kLaunchLon + e / (kMetresPerDegLat * std::cos(common::DegToRad(kLaunchLat)));
    ring.push_back({lon, lat});
  }
  return Json{{"type", "Polygon"}, {"coordinates", {ring}}}.dump();
}

// Two pseudo-terminal pairs joined master to master by a relay thread: a serial
// cable between the two slave devices. The test keeps both slaves open too, so
// a process killed on one end leaves the cable intact for its restart.
class PtyCable {
 public:
  PtyCable() {
    termios raw{};
    ::cfmakeraw(&raw);
    std::array<char, 128> name{};
    for (End& end : ends_) {
      if (::openpty(&end.master, &end.slave, name.data(), &raw, nullptr) != 0) {
        ADD_FAILURE() << "openpty failed";
        return;
      }
      end.path = name.data();
      ::fcntl(end.master, F_SETFL, ::fcntl(end.master, F_GETFL) | O_NONBLOCK);
    }
    if (::pipe(stop_) != 0) ADD_FAILURE() << "pipe failed";
    relay_ = std::thread([this] { Relay(); });
  }
  ~PtyCable() {
    if (relay_.joinable()) {
      const char byte = 0;
      [[maybe_unused]] const ssize_t written = ::write(stop_[1], &byte, 1);
      relay_.join();
    }
    for (const End& end : ends_) {
      ::close(end.master);
      ::close(end.slave);
    }
    ::close(stop_[0]);
    ::close(stop_[1]);
  }
  PtyCable(const PtyCable&) = delete;
  PtyCable& operator=(const PtyCable&) = delete;

  const std::string& server_end() const { return ends_[0].path; }
  const std::string& fleet_end() const { return ends_[1].path; }

 private:
  struct End {
    int master = -1;
    int slave = -1;
    std::string path;
  };

  void Relay() {
    std::array<char, 4096> buffer{};
    while (true) {
      std::array<pollfd, 3> fds{pollfd{ends_[0].master, POLLIN, 0},
                                pollfd{ends_[1].master, POLLIN, 0}, pollfd{stop_[0], POLLIN, 0}};
      if (::poll(fds.data(), fds.size(), -1) < 0) continue;
      if (fds[2].revents != 0) return;
      for (std::size_t from = 0; from < 2; ++from) {
        if ((fds[from].revents & POLLIN) == 0) continue;
        const ssize_t got = ::read(ends_[from].master, buffer.data(), buffer.size());
        if (got <= 0) continue;
        WriteAll(ends_[1 - from].master, buffer.data(), static_cast<std::size_t>(got));
      }
    }
  }
  static void WriteAll(int fd, const char* data, std::size_t size) {
    while (size > 0) {
      const ssize_t put = ::write(fd, data, size);
      if (put > 0) {
        data += put;
        size -= static_cast<std::size_t>(put);
      } else {
        pollfd writable{fd, POLLOUT, 0};
        if (::poll(&writable, 1, 100) <= 0) return;  // the far end is not reading: drop
      }
    }
  }

  std::array<End, 2> ends_;
  int stop_[2] = {-1, -1};
  std::thread relay_;
};

class ServeCommand : public CommandTest {
 protected:
  void SetUp() override {
    CommandTest::SetUp();
    area_ = PathOf("area.geojson");
    std::ofstream(area_) << SmallArea();
    // The link runs secured (the default): a key store with both vehicles' keys.
    keys_ = PathOf("fleet_keys");
    ASSERT_EQ(RunFireswarm("keys init " + keys_).exit_code, 0);
    ASSERT_EQ(RunFireswarm("keys add-vehicle " + keys_ + " --id 1 --id 2").exit_code, 0);
  }

  std::vector<std::string> ServeArgs(const std::string& device) const {
    return {"serve",
            "--keys",
            keys_,
            "--radio-state",
            PathOf("server.radio-state"),
            "--area",
            area_,
            "--drones",
            "2",
            "--launch",
            LatLonText(0, 0),
            "--altitude-m",
            "40",
            "--serial",
            device,
            "--telemetry-hz",
            "4",
            "--start",
            "--until-complete",
            "--duration-s",
            "80"};
  }
  std::vector<std::string> SimArgs(const std::string& device) const {
    // A fire in the middle of the area; a long link-lost timeout so the fleet
    // flies on while the server is restarted (vehicle timers run kSimSpeed times
    // faster than the wall clock).
    return {"sim",  "--count", "2",       "--launch", LatLonText(0, 0),   "--serial",
            device, "--speed", kSimSpeed, "--fire",   LatLonText(170, 0), "--link-lost-timeout-s",
            "600",  "--keys",  keys_};
  }

  // Reads `process`'s JSON lines until one has "event" == `event`; nullopt at the
  // deadline or end of output. Every line read is kept in `seen`.
  static std::optional<Json> WaitForEvent(FireswarmProcess& process, const std::string& event,
                                          Clock::time_point deadline, std::vector<Json>& seen) {
    while (const std::optional<std::string> line = process.ReadLine(deadline)) {
      Json j = Json::parse(*line, nullptr, false);
      if (j.is_discarded()) continue;
      seen.push_back(j);
      if (j.value("event", "") == event) return j;
    }
    return std::nullopt;
  }

  static Json SummaryOf(const RunResult& run) {
    for (auto line = run.lines.rbegin(); line != run.lines.rend(); ++line) {
      Json j = Json::parse(*line, nullptr, false);
      if (!j.is_discarded() && j.value("event", "") == "summary") return j;
    }
    ADD_FAILURE() << "no summary line";
    return Json::object();
  }

  static void ExpectAllDone(const Json& summary) {
    EXPECT_EQ(summary.value("state", ""), "complete") << summary.dump();
    ASSERT_EQ(summary.at("vehicles").size(), 2U) << summary.dump();
    for (const Json& vehicle : summary.at("vehicles")) {
      EXPECT_EQ(vehicle.value("phase", ""), "done") << summary.dump();
    }
  }

  std::string area_;
  std::string keys_;
};

// The mission over the pty runs in secure mode (the default): every frame sealed
// under the vehicles' keys from the key store.
TEST_F(ServeCommand, ServerAndSimulatedFleetOnAPtyCompleteAMission) {
  PtyCable cable;
  FireswarmProcess sim(SimArgs(cable.fleet_end()));
  std::vector<std::string> serve_args = ServeArgs(cable.server_end());
  const std::string lcm_log = PathOf("serve.lcmlog");
  serve_args.insert(serve_args.end(), {"--log", lcm_log});
  FireswarmProcess serve(serve_args);
  const auto started = Clock::now();
  const RunResult run = serve.Finish(Clock::now() + kMissionDeadline);
  const double wall_s = std::chrono::duration<double>(Clock::now() - started).count();
  ASSERT_EQ(run.exit_code, 0) << (run.lines.empty() ? "" : run.lines.back());
  const Json summary = SummaryOf(run);
  ExpectAllDone(summary);
  EXPECT_EQ(summary.value("resumed", true), false);
  EXPECT_GT(summary.at("frames_sent").value("mission_chunk", 0), 0);
  EXPECT_EQ(summary.at("radio").value("requests_failed", 1), 0);
  EXPECT_EQ(summary.at("radio").value("secured", false), true);
  EXPECT_EQ(summary.at("radio").value("refused_frames", 1), 0);
  for (const Json& vehicle : summary.at("vehicles")) {
    EXPECT_EQ(vehicle.value("radio_auth", ""), "ok") << summary.dump();
  }
  // What went on LCM is in the log, for lcm-logplayer.
  EXPECT_GT(std::filesystem::file_size(lcm_log), 0U);

  sim.Signal(SIGTERM);
  const RunResult fleet = sim.Finish(Clock::now() + kExitDeadline);
  EXPECT_EQ(fleet.exit_code, 0);
  ASSERT_FALSE(fleet.lines.empty());
  const Json figures = Json::parse(fleet.lines.back());
  ASSERT_EQ(figures.at("vehicles").size(), 2U);
  for (const Json& vehicle : figures.at("vehicles")) EXPECT_EQ(vehicle.at("mode"), "landed");
  std::cout << "[ figures  ] mission " << summary.at("mission_seconds") << " s on the server's "
            << "clock, " << wall_s << " s wall; sim " << figures.at("sim_seconds")
            << " s simulated, real-time factor " << figures.at("real_time_factor") << "; tracks "
            << summary.at("tracks").size() << "\n";
}

// Two radio channels (issue 21): serve drives two modems, one pty cable each, and
// each channel's fleet is its own `sim` process (vehicle 1 on the first link,
// vehicle 2 on the second: serve's contiguous blocks).
TEST_F(ServeCommand, ServerOnTwoChannelsAndTwoFleetsOnTwoPtysCompleteAMission) {
  PtyCable first;
  PtyCable second;
  const auto sim_on = [&](const PtyCable& cable, int id) {
    std::vector<std::string> args = SimArgs(cable.fleet_end());
    args.at(2) = "1";  // --count
    args.insert(args.end(), {"--first-id", std::to_string(id)});
    return args;
  };
  FireswarmProcess sim_one(sim_on(first, 1));
  FireswarmProcess sim_two(sim_on(second, 2));
  std::vector<std::string> serve_args = ServeArgs(first.server_end());
  serve_args.insert(serve_args.end(), {"--serial", second.server_end()});
  FireswarmProcess serve(serve_args);
  const RunResult run = serve.Finish(Clock::now() + kMissionDeadline);
  ASSERT_EQ(run.exit_code, 0) << (run.lines.empty() ? "" : run.lines.back());
  const Json summary = SummaryOf(run);
  ExpectAllDone(summary);
  // Three processes on wall-clock ptys: on a loaded machine a request may see
  // every retry time out (once in a fresh-root run beside a sanitizer build); the
  // mission is still carried through, which is what this test shows.
  EXPECT_LE(summary.at("radio").value("requests_failed", 99), 1);
  EXPECT_EQ(summary.at("radio").value("channels", 0), 2);
  for (FireswarmProcess* sim : {&sim_one, &sim_two}) {
    sim->Signal(SIGTERM);
    const RunResult fleet = sim->Finish(Clock::now() + kExitDeadline);
    EXPECT_EQ(fleet.exit_code, 0);
    ASSERT_FALSE(fleet.lines.empty());
    const Json figures = Json::parse(fleet.lines.back());
    ASSERT_EQ(figures.at("vehicles").size(), 1U);
    EXPECT_EQ(figures.at("vehicles").at(0).at("mode"), "landed");
  }
}

TEST_F(ServeCommand, ServerKilledMidMissionResumesFromItsJournal) {
  PtyCable cable;
  const std::string journal = PathOf("mission.journal");
  std::vector<std::string> serve_args = ServeArgs(cable.server_end());
  serve_args.insert(serve_args.end(), {"--journal", journal});
  FireswarmProcess sim(SimArgs(cable.fleet_end()));

  std::size_t reports_before_kill = 0;
  {
    FireswarmProcess serve(serve_args);
    std::vector<Json> seen;
    const auto deadline = Clock::now() + kMissionDeadline;
    ASSERT_TRUE(WaitForEvent(serve, "start", deadline, seen)) << "no start";
    // Killed once the fleet flies and a fire report is in.
    ASSERT_TRUE(WaitForEvent(serve, "report", deadline, seen)) << "no fire report";
    const auto running = [](const Json& j) {
      return j.value("event", "") == "state" && j.value("state", "") == "running";
    };
    while (std::none_of(seen.begin(), seen.end(), running)) {
      ASSERT_TRUE(WaitForEvent(serve, "state", deadline, seen)) << "the mission is not running";
    }
    for (const Json& j : seen) reports_before_kill += j.value("event", "") == "report" ? 1U : 0U;
    serve.Kill();
  }
  // The journal holds the mission, its start and the report(s).
  std::size_t journaled_reports = 0;
  {
    std::ifstream in(journal);
    for (std::string line; std::getline(in, line);) {
      journaled_reports += Json::parse(line).at("kind") == "report" ? 1U : 0U;
    }
  }
  EXPECT_GE(journaled_reports, reports_before_kill);
  ASSERT_GE(reports_before_kill, 1U);

  FireswarmProcess restarted(serve_args);
  std::vector<Json> seen;
  const std::optional<Json> resumed =
      WaitForEvent(restarted, "resumed", Clock::now() + kStartDeadline, seen);
  ASSERT_TRUE(resumed.has_value()) << "no 'resumed' line";
  EXPECT_GE(resumed->at("tracks").get<std::size_t>(), 1U);
  EXPECT_EQ(resumed->at("state"), "running");
  const std::size_t tracks_before = resumed->at("tracks").get<std::size_t>();
  const RunResult run = restarted.Finish(Clock::now() + kMissionDeadline);
  ASSERT_EQ(run.exit_code, 0) << (run.lines.empty() ? "" : run.lines.back());
  const Json summary = SummaryOf(run);
  ExpectAllDone(summary);
  EXPECT_EQ(summary.at("resumed"), true);
  // Not planned or uploaded again: no "planned" line, no chunk on the air.
  for (const std::string& line : run.lines) EXPECT_EQ(line.find("\"planned\""), std::string::npos);
  EXPECT_EQ(summary.at("frames_sent").value("mission_chunk", 0), 0) << summary.dump();
  // Every track from before the kill is still there, with its ID.
  ASSERT_GE(summary.at("tracks").size(), tracks_before);
  for (std::size_t i = 0; i < tracks_before; ++i) {
    EXPECT_EQ(summary.at("tracks").at(i).at("id"), static_cast<int>(i) + 1);
  }
  sim.Signal(SIGTERM);
  EXPECT_EQ(sim.Finish(Clock::now() + kExitDeadline).exit_code, 0);
}

bool Mentions(const RunResult& run, const std::string& text) {
  return std::any_of(run.lines.begin(), run.lines.end(),
                     [&](const std::string& line) { return line.find(text) != std::string::npos; });
}

// Issue 19: a journal corrupt in its middle made serve refuse to start, with no
// way to keep the valid part while drones fly. The refusal names --recover;
// --recover resumes from the valid records and moves the rest aside, named.
TEST_F(ServeCommand, RecoverKeepsTheValidPrefixOfACorruptJournal) {
  const std::string journal = PathOf("mission.journal");
  // A real journal: the server starts a mission with nobody on the link.
  PtyCable cable;
  std::vector<std::string> args = ServeArgs(cable.server_end());
  args.erase(std::find(args.begin(), args.end(), "--until-complete"));
  *(std::find(args.begin(), args.end(), "--duration-s") + 1) = "0.2";
  args.insert(args.end(), {"--journal", journal});
  std::string command;
  for (const std::string& arg : args) command += " '" + arg + "'";
  RunResult run = RunFireswarm(command);
  ASSERT_EQ(run.exit_code, 0) << (run.lines.empty() ? "" : run.lines.back());
  std::vector<std::string> lines;
  {
    std::ifstream in(journal);
    for (std::string line; std::getline(in, line);) lines.push_back(line);
  }
  ASSERT_GE(lines.size(), 3U);
  // The last line but one is damaged: not a torn append, corruption.
  const std::size_t bad = lines.size() - 2;
  lines[bad][lines[bad].size() / 2] ^= 0x01;
  {
    std::ofstream out(journal, std::ios::trunc);
    for (const std::string& line : lines) out << line << "\n";
  }
  const auto text_of = [](const std::string& path) {
    std::ifstream in(path);
    return std::string(std::istreambuf_iterator<char>(in), {});
  };
  const std::string corrupt = text_of(journal);

  run = RunFireswarm(command);
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_TRUE(Mentions(run, journal + ": line " + std::to_string(bad + 1) + ": ")) << command;
  EXPECT_TRUE(Mentions(run, "start again with --recover"));
  EXPECT_EQ(text_of(journal), corrupt) << "the refused journal is left as it was";

  run = RunFireswarm(command + " --recover");
  ASSERT_EQ(run.exit_code, 0) << (run.lines.empty() ? "" : run.lines.back());
  const std::string aside = journal + ".corrupt";
  EXPECT_TRUE(Mentions(run, "moved 2 lines")) << "the bad line and the one after it";
  EXPECT_TRUE(Mentions(run, aside));
  bool resumed = false;
  for (const std::string& line : run.lines) {
    const Json j = Json::parse(line, nullptr, false);
    if (j.is_discarded() || j.value("event", "") != "resumed") continue;
    resumed = true;
    EXPECT_EQ(j.at("records"), bad) << line;
    EXPECT_EQ(j.at("moved_aside"), aside) << line;
  }
  EXPECT_TRUE(resumed) << "no 'resumed' line";
  EXPECT_EQ(text_of(aside), lines[bad] + "\n" + lines[bad + 1] + "\n");
  // The resumed server appended after the valid prefix: the journal reads again.
  run = RunFireswarm(command);
  EXPECT_EQ(run.exit_code, 0) << (run.lines.empty() ? "" : run.lines.back());
}

// Makes `key` the key of operator "ann" in the key store `dir` (the fixture's,
// which serve already takes with --keys for the vehicles).
void AddAnn(const std::string& dir, const common::SecretKey& key) {
  std::filesystem::create_directories(dir + "/operators");
  common::WriteSecretKeyFile(dir + "/operators/ann.key", key);
}

std::int64_t UnixMicrosNow() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

// Without --start the server waits for an operator's START on LCM (udpm:// on
// loopback; skipped, saying why, on a machine without a multicast route). An
// unsigned START is refused (and says why); a START signed with a key from
// --keys starts the mission.
TEST_F(ServeCommand, WaitsForAnOperatorStartOnLcm) {
  std::random_device random;
  const std::string url =
      "udpm://239.255.76.67:" + std::to_string(20'000 + random() % 40'000U) + "?ttl=0";
  lcm::LCM console(url);
  if (!console.good()) GTEST_SKIP() << "udpm:// needs a multicast route (scripts/install-deps.sh)";
  const common::SecretKey key = common::GenerateSecretKey();
  PtyCable cable;
  FireswarmProcess sim(SimArgs(cable.fleet_end()));
  std::vector<std::string> serve_args = ServeArgs(cable.server_end());
  std::erase(serve_args, "--start");
  AddAnn(keys_, key);
  serve_args.insert(serve_args.end(), {"--lcm", url});
  FireswarmProcess serve(serve_args);

  // Sends what `make` gives again until the server answers one that `counts`:
  // it may not be listening yet. Answers to the unsigned STARTs sent before can
  // still be on their way when the signed ones go out (a slow server: the
  // sanitizer build on a busy machine); those do not count for the signed.
  const auto deadline = Clock::now() + kStartDeadline;
  const auto send_until_answered = [&](const std::function<fireswarm::operator_command_t()>& make,
                                       const std::function<bool(const Json&)>& counts) {
    std::optional<Json> taken;
    while (!taken && Clock::now() < deadline) {
      const fireswarm::operator_command_t start = make();
      EXPECT_EQ(console.publish("FIRESWARM_OPERATOR_COMMAND", &start), 0);
      const auto retry_at = std::min(deadline, Clock::now() + std::chrono::milliseconds(200));
      while (const std::optional<std::string> line = serve.ReadLine(retry_at)) {
        Json j = Json::parse(*line, nullptr, false);
        if (!j.is_discarded() && j.value("event", "") == "operator_command" && counts(j)) {
          taken = j;
          break;
        }
      }
    }
    return taken;
  };
  const auto any_answer = [](const Json&) { return true; };
  // A signed START refused for its MAC is never taken: the test fails at the deadline.
  const auto not_a_bad_mac = [](const Json& answer) {
    return answer.value("accepted", false) ||
           !answer.value("why", std::string()).starts_with("bad_mac");
  };
  server::OperatorCommand start;
  start.reason = "operator console";
  const std::optional<Json> unsigned_start = send_until_answered([&] {
    fireswarm::operator_command_t m = server::ToLcm(server::SignCommand(
        start, "ann", common::GenerateSecretKey(), UnixMicrosNow(), server::RandomNonce()));
    return m;
  }, any_answer);
  ASSERT_TRUE(unsigned_start.has_value()) << "the server answered no START";
  EXPECT_EQ(unsigned_start->at("accepted"), false) << unsigned_start->dump();
  EXPECT_TRUE(unsigned_start->at("why").get<std::string>().starts_with("bad_mac"))
      << unsigned_start->dump();
  const std::optional<Json> signed_start = send_until_answered([&] {
    return server::ToLcm(
        server::SignCommand(start, "ann", key, UnixMicrosNow(), server::RandomNonce()));
  }, not_a_bad_mac);
  ASSERT_TRUE(signed_start.has_value()) << "the server took no signed START";
  EXPECT_EQ(signed_start->at("accepted"), true) << signed_start->dump();
  EXPECT_EQ(signed_start->at("operator"), "ann");
  const RunResult run = serve.Finish(Clock::now() + kMissionDeadline);
  ASSERT_EQ(run.exit_code, 0) << (run.lines.empty() ? "" : run.lines.back());
  ExpectAllDone(SummaryOf(run));
  sim.Signal(SIGTERM);
  EXPECT_EQ(sim.Finish(Clock::now() + kExitDeadline).exit_code, 0);
}

// The command center's WebSocket as the page reads it: the snapshot, then each
// delta merged into it (docs/command_center.md). Reads block; the server under
// test ends by itself (--duration-s), which closes the stream.
class LiveStream {
 public:
  explicit LiveStream(std::uint16_t port) : ws_(io_) {
    beast::get_lowest_layer(ws_).connect({asio::ip::make_address("127.0.0.1"), port});
    ws_.handshake("127.0.0.1", "/ws");
  }

  // Reads and merges until `done(state)` holds; false when the stream ends first.
  bool ReadUntil(const std::function<bool(const Json&)>& done) {
    while (!done(state_)) {
      beast::flat_buffer buffer;
      beast::error_code error;
      ws_.read(buffer, error);
      if (error) return false;
      Merge(Json::parse(beast::buffers_to_string(buffer.data())));
    }
    return true;
  }

  const Json& state() const { return state_; }

 private:
  void Merge(const Json& message) {
    if (message.at("type") == "snapshot") {
      state_ = message.at("state");
      Json commands = Json::object();  // by ID, as deltas update them
      for (const Json& command : state_.value("commands", Json::array())) {
        commands[std::to_string(command.at("id").get<int>())] = command;
      }
      state_["commands"] = std::move(commands);
      return;
    }
    if (message.at("type") != "delta") return;
    if (message.contains("mission")) state_["mission"] = message.at("mission");
    for (const Json& row : message.value("vehicles", Json::array())) {
      Json& vehicles = state_["vehicles"];
      const auto old = std::find_if(vehicles.begin(), vehicles.end(),
                                    [&](const Json& v) { return v.at("id") == row.at("id"); });
      if (old == vehicles.end()) {
        vehicles.push_back(row);
      } else {
        old->merge_patch(row);
      }
    }
    if (message.contains("refused")) state_["refused"] = message.at("refused");
    for (const Json& command : message.value("commands", Json::array())) {
      state_["commands"][std::to_string(command.at("id").get<int>())] = command;
    }
  }

  asio::io_context io_;
  beast::websocket::stream<beast::tcp_stream> ws_;
  Json state_ = Json::object();
};

// The page live on the real server: `serve --http` on a serial link to a
// simulated fleet. The page sees both drones heard over the link, an operator's
// start from the page goes through the server core and is acknowledged by both
// drones, and the mission flies to its end; without the token it is refused.
TEST_F(ServeCommand, TheCommandCenterShowsTheLinkAndStartsTheMission) {
  PtyCable cable;
  FireswarmProcess sim(SimArgs(cable.fleet_end()));
  std::vector<std::string> serve_args = ServeArgs(cable.server_end());
  std::erase(serve_args, "--start");
  const std::string token = PathOf("token");
  std::ofstream(token) << "page-operator\n";
  ::chmod(token.c_str(), 0600);
  const common::SecretKey key = common::GenerateSecretKey();
  AddAnn(keys_, key);
  serve_args.insert(serve_args.end(), {"--http", "127.0.0.1:0", "--operator-token-file", token});
  FireswarmProcess serve(serve_args);
  const std::optional<std::uint16_t> port = serve.ReadListeningPort(Clock::now() + kStartDeadline);
  ASSERT_TRUE(port) << "no listening line";

  LiveStream stream(*port);
  const auto heard = [](const Json& state) {
    int ok = 0;
    for (const Json& v : state.value("vehicles", Json::array())) ok += v.at("link") == "ok";
    return ok == 2;
  };
  ASSERT_TRUE(stream.ReadUntil(heard)) << stream.state().dump();
  EXPECT_EQ(stream.state().at("source"), "live");
  EXPECT_EQ(stream.state().at("read_only"), false);

  EXPECT_EQ(HttpFetch(*port, http::verb::post, "/api/command", R"({"kind":"start"})").result(),
            http::status::unauthorized);
  ASSERT_TRUE(stream.ReadUntil([](const Json& state) { return state.value("refused", 0) == 1; }))
      << "the page counts the refusal";
  // With the token but unsigned: refused (401) and journaled.
  const auto unsigned_start =
      HttpFetch(*port, http::verb::post, "/api/command", R"({"kind":"start"})", "page-operator");
  EXPECT_EQ(unsigned_start.result(), http::status::unauthorized) << unsigned_start.body();
  EXPECT_NE(unsigned_start.body().find("auth: required"), std::string::npos)
      << unsigned_start.body();
  // Signed as the page signs (docs/command_center.md): the auth member.
  const server::SignedCommand start = server::SignCommand(server::OperatorCommand{}, "ann", key,
                                                          UnixMicrosNow(), server::RandomNonce());
  const Json body = {{"kind", "start"}, {"auth", server::WebCredentialsJson(start.credentials)}};
  const auto accepted =
      HttpFetch(*port, http::verb::post, "/api/command", body.dump(), "page-operator");
  ASSERT_EQ(accepted.result(), http::status::accepted) << accepted.body();
  const std::string id = std::to_string(Json::parse(accepted.body()).at("id").get<int>());
  ASSERT_TRUE(stream.ReadUntil([&](const Json& state) {
    return state.contains("commands") && state.at("commands").contains(id) &&
           state.at("commands").at(id).at("state") == "acknowledged";
  })) << stream.state().dump();
  EXPECT_EQ(stream.state().at("commands").at(id).at("targets").size(), 2U);
  ASSERT_TRUE(stream.ReadUntil([](const Json& state) {
    return state.contains("mission") && state.at("mission").at("state") != "idle" &&
           state.at("mission").at("state") != "uploading";
  })) << stream.state().dump();

  const RunResult run = serve.Finish(Clock::now() + kMissionDeadline);
  ASSERT_EQ(run.exit_code, 0) << (run.lines.empty() ? "" : run.lines.back());
  ExpectAllDone(SummaryOf(run));
  // The unsigned start was journaled (serve prints every journal entry as a line).
  EXPECT_TRUE(std::any_of(run.lines.begin(), run.lines.end(), [](const std::string& line) {
    return line.find(R"("event":"command_refused")") != std::string::npos &&
           line.find("malformed: auth: required") != std::string::npos;
  }));
  sim.Signal(SIGTERM);
  EXPECT_EQ(sim.Finish(Clock::now() + kExitDeadline).exit_code, 0);
}

// Real operations launch from several road-side points and fly sorties: serve
// plans with the sites given (--launch repeated, or a file fixing the drones per
// site) and the endurance, and says so in its "planned" line.
TEST_F(ServeCommand, PlansFromSeveralLaunchSitesInSorties) {
  const std::string west = LatLonText(0, 0);
  const std::string east = LatLonText(340, 0);
  const std::string base = "serve --area " + area_ +
                           " --drones 2 --udp 127.0.0.1:0 127.0.0.1:9 --checksum crc16 --start "
                           "--duration-s 0.2 ";
  const auto planned = [](const RunResult& run) {
    for (const std::string& line : run.lines) {
      const Json j = Json::parse(line, nullptr, false);
      if (!j.is_discarded() && j.value("event", "") == "planned") return j;
    }
    return Json();
  };
  const RunResult repeated =
      RunFireswarm(base + "--launch " + west + " --launch " + east + " --endurance-s 130");
  ASSERT_EQ(repeated.exit_code, 0) << (repeated.lines.empty() ? "" : repeated.lines.back());
  const Json plan = planned(repeated);
  ASSERT_EQ(plan.at("sites").size(), 2U) << plan.dump();
  EXPECT_NEAR(plan.at("sites")[1].at("lon").get<double>(),
              std::stod(east.substr(east.find(',') + 1)), 1e-6);
  EXPECT_EQ(
      plan.at("sites")[0].at("drones").get<int>() + plan.at("sites")[1].at("drones").get<int>(), 2);
  // 130 s of which 80 go up and down: more sorties than drones.
  EXPECT_GT(plan.at("sorties").get<int>(), 2) << plan.dump();

  const std::string sites = PathOf("sites.geojson");
  std::ofstream(sites)
      << R"({"type":"FeatureCollection","features":[)"
      << R"({"type":"Feature","properties":{"drones":1},"geometry":{"type":"Point","coordinates":[)"
      << east.substr(east.find(',') + 1) << "," << east.substr(0, east.find(','))
      << R"(]}},{"type":"Feature","properties":{"drones":1},"geometry":{"type":"Point","coordinates":[)"
      << west.substr(west.find(',') + 1) << "," << west.substr(0, west.find(',')) << "]}}]}";
  const RunResult from_file = RunFireswarm(base + "--launch-file " + sites);
  ASSERT_EQ(from_file.exit_code, 0) << (from_file.lines.empty() ? "" : from_file.lines.back());
  const Json fixed = planned(from_file);
  ASSERT_EQ(fixed.at("sites").size(), 2U) << fixed.dump();
  EXPECT_EQ(fixed.at("sites")[0].at("drones"), 1);
  EXPECT_EQ(fixed.at("sites")[1].at("drones"), 1);
}

TEST_F(ServeCommand, BadFlagsExitTwoNamingTheFlag) {
  const std::string link = " --udp 127.0.0.1:0 127.0.0.1:9";
  const std::string serve = "serve --area " + area_ + " --drones 2 --start";
  const std::string sim = "sim --launch 46.5,7.5";
  struct Case {
    std::string args;
    std::vector<std::string> named;
  };
  for (const Case& c : std::vector<Case>{
           {serve, {"--udp", "--serial"}},
           {serve + link + " --serial /dev/null", {"--udp", "--serial"}},
           {"serve --drones 2 --start" + link, {"--area"}},
           {"serve --area " + area_ + " --drones 0 --start" + link, {"--drones"}},
           {"serve --area " + area_ + " --drones 2" + link, {"--start", "--lcm"}},
           {"serve --area " + area_ + " --drones 2 --lcm memq://" + link, {"--keys"}},
           {serve + " --checksum crc16 --keys " + PathOf("no-store") + link,
            {"--keys", "no-store"}},
           {serve + " --first-id 254" + link, {"--first-id"}},
           {serve + " --mode token" + link, {"--mode"}},
           {serve + " --checksum sum" + link, {"--checksum"}},
           {serve + link, {"--keys"}},
           {serve + " --keys " + PathOf("no_store") + " --radio-state " + PathOf("s") + link,
            {"no_store"}},
           {serve + " --keys " + keys_ + link, {"--journal", "--radio-state"}},
           {"serve --area " + area_ + " --drones 2 --lcm memq:// --checksum crc16 --keys " + keys_ +
                link,
            {"--keys", "operators"}},
           {serve + " --launch 95,7" + link, {"--launch"}},
           {serve + " --launch 46.5,7.5 --launch 46.5" + link, {"--launch"}},
           {serve + " --launch 46.5,7.5 --launch-file sites.geojson" + link, {"--launch-file"}},
           {serve + " --endurance-s 0" + link, {"--endurance-s"}},
           {serve + " --swap-s -1" + link, {"--swap-s"}},
           {serve + " --altitude-m -5" + link, {"--altitude-m"}},
           {serve + " --camera flir" + link, {"--camera"}},
           {serve + " --telemetry-hz 0" + link, {"--telemetry-hz"}},
           {serve + " --duration-s 0" + link, {"--duration-s"}},
           {serve + " --duration-s 1e12" + link, {"--duration-s must be in (0, 2.592e+06]"}},
           {serve + " --altitude-m 100000" + link, {"--altitude-m must be in (0, 1000]"}},
           {serve + " --speed-mps 1e9" + link, {"--speed-mps must be in (0, 100]"}},
           {serve + " --recover --checksum crc16" + link, {"--recover goes with --journal"}},
           {serve + " --checksum crc16 --log " + area_ + link, {"--log", "is the input"}},
           {serve + " --checksum crc16 --journal " + keys_ + link, {"--journal", "a directory"}},
           {"serve --area " + PathOf("missing.geojson") + " --drones 2 --start --checksum crc16" +
                link,
            {"missing.geojson"}},
           {"sim" + link, {"--launch"}},
           {sim, {"--udp", "--serial"}},
           {"sim --launch 46.5" + link, {"--launch"}},
           {sim + " --count 0" + link, {"--count"}},
           {sim + " --count 2 --first-id 254" + link, {"--first-id"}},
           {sim + " --fire 1,2,3" + link, {"--fire"}},
           {sim + " --fire 48,7.5 --checksum crc16" + link, {"--fire"}},
           {sim + " --speed 0.5" + link, {"--speed"}},
           {sim + " --camera flir" + link, {"--camera"}},
           {sim + " --link-lost-timeout-s 1" + link, {"--link-lost-timeout-s"}},
           {sim + link, {"--keys"}},
           {sim + " --count 3 --keys " + keys_ + link, {"3.key"}},
       }) {
    const RunResult run = RunFireswarm(c.args);
    EXPECT_EQ(run.exit_code, 2) << c.args;
    for (const std::string& flag : c.named) EXPECT_TRUE(Mentions(run, flag)) << c.args;
  }
}

TEST(SimCommand, StopsAfterTheDurationWithOneSummaryForTheFleet) {
  const RunResult run = RunFireswarm(
      "sim --count 3 --first-id 5 --launch 46.5,7.5 --udp 127.0.0.1:0 127.0.0.1:9 --speed 20 "
      "--duration-s 2 --checksum crc16");
  EXPECT_EQ(run.exit_code, 0);
  ASSERT_EQ(run.lines.size(), 1U);
  const Json summary = Json::parse(run.lines[0]);
  EXPECT_NEAR(summary.at("sim_seconds").get<double>(), 2.0, 0.02);
  ASSERT_EQ(summary.at("vehicles").size(), 3U);
  for (int i = 0; i < 3; ++i) {
    const Json& vehicle = summary.at("vehicles").at(static_cast<std::size_t>(i));
    EXPECT_EQ(vehicle.at("id"), 5 + i);
    EXPECT_EQ(vehicle.at("mode"), "idle");
  }
}

}  // namespace
}  // namespace fireswarm::app
