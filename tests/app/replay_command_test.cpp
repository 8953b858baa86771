// `fireswarm replay` end to end: a run's LCM log (`fireswarm run --log`) replayed
// on the command center's API and stream through real sockets: scrubbed to the
// end it holds the run report's final tracks, play moves the timeline on and
// pauses at the end, a seek back rebuilds, commands are refused, and bad logs
// exit 2 naming the file.
#include <gtest/gtest.h>
#include <signal.h>

#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "app/fireswarm_process.hpp"
#include "app/http_fetch.hpp"
#include "app/run_fireswarm.hpp"

namespace fireswarm::app {
namespace {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;
using Json = nlohmann::json;
using std::chrono::seconds;
using std::chrono::steady_clock;

// 800 m x 500 m, two drones, one fire in the middle: the whole search (planned
// at 6.7 min) passes over it, whatever order the plan sweeps in.
const std::string kScenario = TinyScenario(600);

constexpr auto kTimeout = seconds(60);

Json GetState(std::uint16_t port) {
  return Json::parse(HttpFetch(port, http::verb::get, "/api/state").body());
}

// The page's side of the WebSocket stream; every read has a deadline.
class Stream {
 public:
  explicit Stream(std::uint16_t port) : ws_(io_) {
    beast::get_lowest_layer(ws_).connect({asio::ip::make_address("127.0.0.1"), port});
    ws_.handshake("127.0.0.1", "/ws");
  }
  void Send(const Json& message) { ws_.write(asio::buffer(message.dump())); }
  // The next message; null when none came within the timeout.
  Json Read() {
    Json got;
    beast::get_lowest_layer(ws_).expires_after(kTimeout);
    ws_.async_read(buffer_, [&](beast::error_code error, std::size_t) {
      if (!error) got = Json::parse(beast::buffers_to_string(buffer_.data()));
      buffer_.consume(buffer_.size());
    });
    io_.restart();
    io_.run();
    return got;
  }
  // Reads until a message `wanted` accepts; null when the stream ends first.
  Json ReadUntil(const std::function<bool(const Json&)>& wanted) {
    for (Json message = Read(); !message.is_null(); message = Read()) {
      if (wanted(message)) return message;
    }
    return nullptr;
  }

 private:
  asio::io_context io_;
  beast::websocket::stream<beast::tcp_stream> ws_;
  beast::flat_buffer buffer_;
};

bool IsType(const Json& message, const char* type) {
  return message.value("type", "") == type;
}

// Metres between two points a few metres apart (equirectangular).
double DistanceM(double lat1, double lon1, double lat2, double lon2) {
  constexpr double kMetresPerDegree = 111'320.0;
  const double north = (lat2 - lat1) * kMetresPerDegree;
  const double east = (lon2 - lon1) * kMetresPerDegree * std::cos(lat1 * M_PI / 180.0);
  return std::hypot(north, east);
}

class ReplayCommandTest : public CommandTest {
 protected:
  // Flies kScenario with --log run.lcmlog and --report report.json; the report.
  Json FlyAndLog() {
    std::ofstream(PathOf("tiny.yaml")) << kScenario;
    const RunResult run = RunFireswarm("run " + PathOf("tiny.yaml") + " --log " +
                                       PathOf("run.lcmlog") + " --report " + PathOf("report.json"));
    EXPECT_EQ(run.exit_code, 0) << Output(run);
    return Json::parse(std::ifstream(PathOf("report.json")));
  }
  // `fireswarm replay LOG --http 127.0.0.1:0` started; its port.
  std::optional<std::uint16_t> StartReplay(const std::string& log) {
    replay_.emplace(std::vector<std::string>{"replay", log, "--http", "127.0.0.1:0"});
    return replay_->ReadListeningPort(steady_clock::now() + kTimeout);
  }
  static std::string Output(const RunResult& result) {
    std::string text;
    for (const std::string& line : result.lines) text += line + "\n";
    return text;
  }
  static bool Mentions(const RunResult& result, const std::string& text) {
    return Output(result).find(text) != std::string::npos;
  }

  std::optional<FireswarmProcess> replay_;
};

TEST_F(ReplayCommandTest, ScrubbedToTheEndHoldsTheRunReportsFinalTracksAndRefusesCommands) {
  const Json report = FlyAndLog();
  ASSERT_FALSE(report.at("tracks").empty()) << "the scenario must track its fire";
  const std::optional<std::uint16_t> port = StartReplay(PathOf("run.lcmlog"));
  ASSERT_TRUE(port) << "no listening line";

  const Json at_start = GetState(*port);
  EXPECT_EQ(at_start.at("source"), "replay");
  EXPECT_EQ(at_start.at("read_only"), true);
  const Json timeline = at_start.at("replay");
  EXPECT_EQ(timeline.at("playing"), false) << "starts paused";
  EXPECT_EQ(timeline.at("time_s"), timeline.at("start_s")) << "at the start";
  const double end_s = timeline.at("end_s");
  EXPECT_NEAR(end_s, report.at("sim_seconds").get<double>(), 1.0);

  Stream stream(*port);
  const Json snapshot = stream.Read();
  ASSERT_TRUE(IsType(snapshot, "snapshot")) << snapshot;
  EXPECT_EQ(snapshot.at("state").at("replay"), timeline);
  stream.Send({{"type", "replay"}, {"action", "seek"}, {"time_s", end_s}, {"speed", 1}});
  const Json after_seek = stream.ReadUntil([](const Json& m) { return IsType(m, "snapshot"); });
  ASSERT_FALSE(after_seek.is_null());
  const Json status = stream.Read();
  ASSERT_TRUE(IsType(status, "replay")) << status;
  EXPECT_EQ(status.at("time_s"), end_s);
  EXPECT_EQ(status.at("playing"), false);

  // The state served now is the run's end: the report's tracks, statuses, positions.
  const Json at_end = GetState(*port);
  EXPECT_EQ(at_end.at("tracks"), after_seek.at("state").at("tracks"));
  std::map<int, Json> shown;
  for (const Json& track : at_end.at("tracks")) shown[track.at("id").get<int>()] = track;
  ASSERT_EQ(shown.size(), report.at("tracks").size()) << at_end.at("tracks");
  for (const Json& track : report.at("tracks")) {
    const int id = track.at("track_id");
    ASSERT_EQ(shown.count(id), 1U) << "track " << id;
    EXPECT_EQ(shown[id].at("status"), track.at("status")) << "track " << id;
    const Json& position = shown[id].at("position");
    EXPECT_LT(DistanceM(position[0], position[1], track.at("lat"), track.at("lon")), 1.0)
        << "track " << id;
  }

  const auto refused =
      HttpFetch(*port, http::verb::post, "/api/command", R"({"kind":"hold_all"})", "anything");
  EXPECT_EQ(refused.result(), http::status::forbidden);
  replay_->Signal(SIGTERM);
  EXPECT_EQ(replay_->Finish(steady_clock::now() + kTimeout).exit_code, 0);
}

TEST_F(ReplayCommandTest, PlayMovesTheTimelineOnPausesAtTheEndAndASeekBackRebuilds) {
  const Json report = FlyAndLog();
  const std::optional<std::uint16_t> port = StartReplay(PathOf("run.lcmlog"));
  ASSERT_TRUE(port) << "no listening line";
  Stream stream(*port);
  const Json snapshot = stream.Read();
  ASSERT_TRUE(IsType(snapshot, "snapshot")) << snapshot;
  const Json timeline = snapshot.at("state").at("replay");
  EXPECT_TRUE(snapshot.at("state").at("tracks").empty()) << "no track at the start";

  // A malformed control changes nothing and gets an error naming the field.
  stream.Send({{"type", "replay"}, {"action", "rewind"}});
  const Json error = stream.Read();
  ASSERT_TRUE(IsType(error, "error")) << error;
  EXPECT_NE(error.at("error").get<std::string>().find("action"), std::string::npos) << error;

  // 120 log seconds at 100 times the wall clock: about 1.2 s.
  stream.Send({{"type", "replay"}, {"action", "play"}, {"speed", 100}});
  const Json playing = stream.ReadUntil([](const Json& m) { return IsType(m, "replay"); });
  ASSERT_FALSE(playing.is_null());
  EXPECT_EQ(playing.at("playing"), true);
  EXPECT_EQ(playing.at("speed"), 100);
  const Json delta = stream.ReadUntil([](const Json& m) { return IsType(m, "delta"); });
  ASSERT_FALSE(delta.is_null());
  EXPECT_GT(delta.at("time_s").get<double>(), timeline.at("start_s").get<double>());
  const Json ended = stream.ReadUntil(
      [](const Json& m) { return IsType(m, "replay") && m.at("playing") == false; });
  ASSERT_FALSE(ended.is_null());
  EXPECT_EQ(ended.at("time_s"), timeline.at("end_s")) << "paused at the end";
  EXPECT_EQ(GetState(*port).at("tracks").size(), report.at("tracks").size());

  // Back to the start: the model rebuilt, so the tracks found later are gone.
  stream.Send({{"type", "replay"}, {"action", "seek"}, {"time_s", -1000}});
  const Json rebuilt = stream.ReadUntil([](const Json& m) { return IsType(m, "snapshot"); });
  ASSERT_FALSE(rebuilt.is_null());
  EXPECT_TRUE(rebuilt.at("state").at("tracks").empty());
  EXPECT_EQ(rebuilt.at("state").at("replay").at("time_s"), timeline.at("start_s")) << "clamped";
}

TEST_F(ReplayCommandTest, ALogCutShortReplaysWhatItHoldsWithAWarning) {
  FlyAndLog();
  const auto size = std::filesystem::file_size(PathOf("run.lcmlog"));
  std::filesystem::resize_file(PathOf("run.lcmlog"), size - 10);
  const RunResult result =
      RunFireswarm("replay " + PathOf("run.lcmlog") + " --http 127.0.0.1:0 --duration-s 0.5");
  EXPECT_EQ(result.exit_code, 0) << Output(result);
  EXPECT_TRUE(Mentions(result, "warning: " + PathOf("run.lcmlog"))) << Output(result);
  EXPECT_TRUE(Mentions(result, "http: listening on http://127.0.0.1:")) << Output(result);
}

TEST_F(ReplayCommandTest, ExitsTwoNamingAMissingOrGarbageLogOrABadFlag) {
  std::ofstream(PathOf("garbage.lcmlog")) << std::string(4096, 'x');
  std::ofstream(PathOf("empty.lcmlog"));
  const struct {
    std::string args;
    std::string named;
  } cases[] = {
      {PathOf("missing.lcmlog") + " --http 127.0.0.1:0", PathOf("missing.lcmlog")},
      {PathOf("garbage.lcmlog") + " --http 127.0.0.1:0", PathOf("garbage.lcmlog")},
      {PathOf("empty.lcmlog") + " --http 127.0.0.1:0", PathOf("empty.lcmlog")},
      {PathOf("garbage.lcmlog"), "--http"},
      {PathOf("garbage.lcmlog") + " --http 127.0.0.1:0 --speed 0", "--speed"},
      {PathOf("garbage.lcmlog") + " --http 127.0.0.1:0 --duration-s -1", "--duration-s"},
  };
  for (const auto& c : cases) {
    const RunResult result = RunFireswarm("replay " + c.args);
    EXPECT_EQ(result.exit_code, 2) << c.args << "\n" << Output(result);
    EXPECT_TRUE(Mentions(result, c.named)) << c.args << "\n" << Output(result);
  }
}

}  // namespace
}  // namespace fireswarm::app
