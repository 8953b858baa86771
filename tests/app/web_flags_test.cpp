// The command center's flags (app/web_flags.cpp) end to end through `fireswarm
// run`: the page served while a paced run goes, the listening line, and bad web
// flags refused with exit 2 naming the flag or file.
#include <sys/stat.h>

#include <boost/asio/ip/tcp.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "app/fireswarm_process.hpp"
#include "app/http_fetch.hpp"
#include "app/run_fireswarm.hpp"
#include "fireswarm/common/secret_key.hpp"
#include "fireswarm/server/command_auth.hpp"
#include "fireswarm/server/web_command.hpp"

namespace fireswarm::app {
namespace {

namespace asio = boost::asio;
namespace beast = boost::beast;
namespace http = beast::http;

// 800 m x 500 m, two drones, one fire, 30 simulated s.
const std::string kScenario = TinyScenario(30);

http::response<http::string_body> Get(std::uint16_t port, const std::string& target) {
  return HttpFetch(port, http::verb::get, target);
}

class WebFlagsTest : public CommandTest {
 protected:
  std::string Write(const std::string& name, const std::string& text, int mode = 0600) const {
    std::ofstream(PathOf(name)) << text;
    ::chmod(PathOf(name).c_str(), static_cast<mode_t>(mode));
    return PathOf(name);
  }
  static bool Mentions(const RunResult& result, const std::string& text) {
    for (const std::string& line : result.lines) {
      if (line.find(text) != std::string::npos) return true;
    }
    return false;
  }
};

TEST_F(WebFlagsTest, RunServesThePageWhileItGoesAtThePaceAsked) {
  const std::string scenario = Write("tiny.yaml", kScenario);
  std::filesystem::create_directories(dir_ / "web");
  Write("web/index.html", "<title>command center</title>");
  const std::string token = Write("token", "  operator-token\n");
  const common::SecretKey key = common::GenerateSecretKey();
  std::filesystem::create_directories(dir_ / "keys" / "operators");
  common::WriteSecretKeyFile(dir_ / "keys" / "operators" / "ann.key", key);
  constexpr double kPace = 10.0;
  FireswarmProcess run({"run", scenario, "--report", PathOf("r.json"), "--http", "127.0.0.1:0",
                        "--web-root", PathOf("web"), "--operator-token-file", token, "--keys",
                        PathOf("keys"), "--pace", std::to_string(kPace)});
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  const std::optional<std::uint16_t> port = run.ReadListeningPort(deadline);
  ASSERT_TRUE(port) << "no listening line";
  const auto index = Get(*port, "/");
  EXPECT_EQ(index.result(), http::status::ok);
  EXPECT_EQ(index.body(), "<title>command center</title>");
  EXPECT_EQ(Get(*port, "/api/state").result(), http::status::ok);
  // The stream: the snapshot, then the model's deltas at 5 Hz of simulated time.
  asio::io_context io;
  beast::websocket::stream<beast::tcp_stream> ws(io);
  beast::get_lowest_layer(ws).connect({asio::ip::make_address("127.0.0.1"), *port});
  ws.handshake("127.0.0.1", "/ws");
  beast::flat_buffer buffer;
  ws.read(buffer);
  EXPECT_EQ(nlohmann::json::parse(beast::buffers_to_string(buffer.data())).at("type"), "snapshot");
  buffer.consume(buffer.size());
  ws.read(buffer);
  const nlohmann::json delta = nlohmann::json::parse(beast::buffers_to_string(buffer.data()));
  const auto read_ms = std::chrono::duration_cast<std::chrono::milliseconds>(
                           std::chrono::system_clock::now().time_since_epoch())
                           .count();
  EXPECT_EQ(delta.at("type"), "delta");
  // Stamped with the wall clock when the server built it: just before it was read.
  EXPECT_LE(delta.at("built_unix_ms").get<std::int64_t>(), read_ms);
  EXPECT_GT(delta.at("built_unix_ms").get<std::int64_t>(), read_ms - 5000);
  const nlohmann::json state = nlohmann::json::parse(Get(*port, "/api/state").body());
  EXPECT_EQ(state.at("source"), "simulated");
  // Fresh: built after the delta read, which it holds (the feed serialises the
  // state for the request at its next step).
  EXPECT_GE(state.at("built_unix_ms").get<std::int64_t>(),
            delta.at("built_unix_ms").get<std::int64_t>());
  // Commands reach the server core, which answers through the feed.
  const auto bogus =
      HttpFetch(*port, http::verb::post, "/api/command", R"({"kind":"bogus"})", "operator-token");
  EXPECT_EQ(bogus.result(), http::status::bad_request);
  EXPECT_NE(bogus.body().find("kind"), std::string::npos) << bogus.body();
  const auto unsigned_start =
      HttpFetch(*port, http::verb::post, "/api/command", R"({"kind":"start"})", "operator-token");
  EXPECT_EQ(unsigned_start.result(), http::status::unauthorized) << unsigned_start.body();
  // Signed on the run's clock (simulated us: the state's time_s), as the page does.
  const std::int64_t utime = std::llround(state.at("time_s").get<double>() * 1e6);
  const server::SignedCommand start =
      server::SignCommand({}, "ann", key, utime, server::RandomNonce());
  const nlohmann::json body = {{"kind", "start"},
                               {"auth", server::WebCredentialsJson(start.credentials)}};
  const auto again =
      HttpFetch(*port, http::verb::post, "/api/command", body.dump(), "operator-token");
  EXPECT_EQ(again.result(), http::status::conflict)
      << "the run started the mission already: " << again.body();
  EXPECT_EQ(
      HttpFetch(*port, http::verb::post, "/api/command", R"({"kind":"start"})", "guess").result(),
      http::status::unauthorized);
  const RunResult result = run.Finish(deadline);
  EXPECT_EQ(result.exit_code, 0);
  // Its last word: the web adapter's CPU, a part of the process's.
  std::optional<nlohmann::json> cpu;
  for (const std::string& line : result.lines) {
    if (line.find(R"("event":"web_cpu")") != std::string::npos) cpu = nlohmann::json::parse(line);
  }
  ASSERT_TRUE(cpu) << "no web_cpu line";
  EXPECT_GT(cpu->at("feed_cpu_s").get<double>(), 0.0);
  EXPECT_GT(cpu->at("io_cpu_s").get<double>(), 0.0) << "the io thread served requests";
  EXPECT_DOUBLE_EQ(cpu->at("web_cpu_s").get<double>(),
                   cpu->at("feed_cpu_s").get<double>() + cpu->at("io_cpu_s").get<double>());
  EXPECT_LT(cpu->at("web_cpu_s").get<double>(), cpu->at("process_cpu_s").get<double>());
  EXPECT_DOUBLE_EQ(cpu->at("share").get<double>(),
                   cpu->at("web_cpu_s").get<double>() / cpu->at("process_cpu_s").get<double>());
  const nlohmann::json report = nlohmann::json::parse(std::ifstream(PathOf("r.json")));
  // Paced: simulated time never ran ahead of K times the wall clock.
  EXPECT_GE(report.at("wall_seconds").get<double>(),
            report.at("sim_seconds").get<double>() / kPace * 0.99);
}

TEST_F(WebFlagsTest, RefusesBadWebFlagsNamingThem) {
  const std::string scenario = Write("tiny.yaml", kScenario);
  std::filesystem::create_directories(dir_ / "web");
  const std::string open_token = Write("open-token", "secret\n", 0644);
  const std::string empty_token = Write("empty-token", " \n");
  const std::string web = " --web-root " + PathOf("web");
  const struct {
    std::string args;
    std::string named;
  } cases[] = {
      {"--http 127.0.0.1:0 --operator-token-file " + open_token + web, open_token},
      {"--http 127.0.0.1:0 --operator-token-file " + empty_token + web, empty_token},
      {"--http 127.0.0.1:0 --operator-token-file " + PathOf("none") + web, PathOf("none")},
      {"--http 0.0.0.0:0" + web, "--http"},
      {"--http 127.0.0.1" + web, "--http"},
      {"--http 127.0.0.1:0 --web-root " + PathOf("nowhere"), "--web-root"},
      {"--tls-cert c.pem", "--tls-cert"},
      {"--pace 0", "--pace"},
      {"--pace -2 --http 127.0.0.1:0" + web, "--pace"},
  };
  for (const auto& c : cases) {
    const RunResult result = RunFireswarm("run " + scenario + " " + c.args);
    EXPECT_EQ(result.exit_code, 2) << c.args;
    EXPECT_TRUE(Mentions(result, c.named)) << c.args;
  }
}

}  // namespace
}  // namespace fireswarm::app
