#include "fireswarm/server/web_server.hpp"

#include <gtest/gtest.h>

#include <ctime>
#include <future>
#include <thread>

#include "web_test_support.hpp"

namespace fireswarm::server {
namespace {

using namespace std::chrono_literals;
using testing::Fetch;
using testing::Get;
using testing::MakeRequest;
using testing::WsTestClient;
namespace http = testing::http;

constexpr const char* kToken = "s3cret-operator-token";
constexpr auto kWait = 5s;  // what a test waits for the server at most

class WebServerTest : public testing::ScratchTest {
 protected:
  void SetUp() override {
    ScratchTest::SetUp();
    Write("web/index.html", "<!doctype html><title>fireswarm</title>");
    Write("web/app.js", "console.log('page');");
    Write("web/node_modules/leaflet/dist/leaflet.js", "/* leaflet */");
    Write("secret.txt", "not for the web");
  }

  WebServerConfig Config() const {
    WebServerConfig config;
    config.web_root = dir_ / "web";
    config.operator_token = kToken;
    return config;
  }

  static http::request<http::string_body> Command(const std::string& body,
                                                  const std::string& token = kToken) {
    return MakeRequest(http::verb::post, "/api/command", body,
                       {{http::field::authorization, "Bearer " + token}});
  }
};

nlohmann::json BodyOf(const testing::Response& response) {
  return nlohmann::json::parse(response.body());
}

TEST_F(WebServerTest, ServesTheWebRootsFilesWithTheirTypes) {
  const WebServer server(Config());
  const auto index = Get(server.port(), "/");
  EXPECT_EQ(index.result(), http::status::ok);
  EXPECT_EQ(index.body(), "<!doctype html><title>fireswarm</title>");
  EXPECT_EQ(index[http::field::content_type], "text/html; charset=utf-8");
  const auto script = Get(server.port(), "/app.js?v=2");
  EXPECT_EQ(script.body(), "console.log('page');");
  EXPECT_EQ(script[http::field::content_type], "text/javascript; charset=utf-8");
  const auto leaflet = Get(server.port(), "/node_modules/leaflet/dist/leaflet.js");
  EXPECT_EQ(leaflet.result(), http::status::ok);
  EXPECT_EQ(leaflet.body(), "/* leaflet */");
  const auto head = Fetch(server.port(), MakeRequest(http::verb::head, "/app.js"));
  EXPECT_EQ(head.result(), http::status::ok);
  EXPECT_EQ(head[http::field::content_length], "20");
  EXPECT_EQ(Get(server.port(), "/missing.js").result(), http::status::not_found);
  EXPECT_EQ(Fetch(server.port(), MakeRequest(http::verb::delete_, "/app.js")).result(),
            http::status::method_not_allowed);
  EXPECT_EQ(server.url(), "http://127.0.0.1:" + std::to_string(server.port()) + "/");
}

TEST_F(WebServerTest, RefusesPathsThatLeaveTheWebRootEncodedOrNot) {
  const WebServer server(Config());
  for (const char* target : {"/../secret.txt", "/%2e%2e/secret.txt", "/%2E%2E%2Fsecret.txt",
                             "/node_modules/../../secret.txt", "/..%5csecret.txt", "/%00"}) {
    const auto response = Get(server.port(), target);
    EXPECT_TRUE(response.result() == http::status::not_found ||
                response.result() == http::status::bad_request)
        << target << ": " << response.result_int();
    EXPECT_EQ(response.body().find("not for the web"), std::string::npos) << target;
  }
}

TEST_F(WebServerTest, ServesTheDocumentsItWasGiven) {
  WebServer server(Config());
  EXPECT_EQ(Get(server.port(), "/api/state").body(), "{}");
  server.SetDocuments(R"({"time_s":1.5})", R"({"type":"FeatureCollection"})", R"({"rows":3})");
  const auto state = Get(server.port(), "/api/state");
  EXPECT_EQ(state.result(), http::status::ok);
  EXPECT_EQ(state[http::field::content_type], "application/json");
  EXPECT_EQ(state.body(), R"({"time_s":1.5})");
  EXPECT_EQ(Get(server.port(), "/api/plan").body(), R"({"type":"FeatureCollection"})");
  EXPECT_EQ(Get(server.port(), "/api/coverage").body(), R"({"rows":3})");
  EXPECT_EQ(Get(server.port(), "/api/other").result(), http::status::not_found);
}

TEST_F(WebServerTest, CountsTheCpuTimeOfItsIoThreadAlone) {
  WebServer server(Config());
  server.SetDocuments(std::string(1 << 20, ' ') + "{}", "{}", "{}");
  const double before_s = server.io_cpu_seconds();
  for (int i = 0; i < 20; ++i)
    ASSERT_EQ(Get(server.port(), "/api/state").result(), http::status::ok);
  const double after_s = server.io_cpu_seconds();
  EXPECT_GT(after_s, before_s) << "serving 20 MiB took no CPU on the io thread";
  // This thread's work (the requests, the reads) is not the io thread's.
  timespec process{};
  ASSERT_EQ(clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &process), 0);
  EXPECT_LT(after_s,
            static_cast<double>(process.tv_sec) + static_cast<double>(process.tv_nsec) * 1e-9);
}

TEST_F(WebServerTest, QueuesACommandWithTheRightTokenAndRepliesWithTheCallersAnswer) {
  WebServer server(Config());
  auto reply = std::async(std::launch::async, [&] {
    return Fetch(server.port(), Command(R"({"kind":"hold","vehicle":3})"));
  });
  const std::vector<PendingCommand> commands = server.TakeCommands(kWait);
  ASSERT_EQ(commands.size(), 1U);
  EXPECT_EQ(commands[0].body, nlohmann::json::parse(R"({"kind":"hold","vehicle":3})"));
  EXPECT_TRUE(commands[0].peer.starts_with("127.0.0.1:")) << commands[0].peer;
  EXPECT_TRUE(server.Answer(commands[0].id, 202, R"({"id":7,"state":"queued"})"));
  const auto response = reply.get();
  EXPECT_EQ(response.result(), http::status::accepted);
  EXPECT_EQ(BodyOf(response), nlohmann::json::parse(R"({"id":7,"state":"queued"})"));
  EXPECT_FALSE(server.Answer(commands[0].id, 202, "{}")) << "answered twice";
  EXPECT_EQ(server.refused(), 0U);
}

TEST_F(WebServerTest, RefusesACommandWithoutOrWithTheWrongToken401) {
  WebServer server(Config());
  const auto missing = Fetch(server.port(), MakeRequest(http::verb::post, "/api/command",
                                                        R"({"kind":"hold","vehicle":3})"));
  EXPECT_EQ(missing.result(), http::status::unauthorized);
  EXPECT_TRUE(BodyOf(missing).contains("error"));
  const auto wrong = Fetch(server.port(), Command(R"({"kind":"hold","vehicle":3})", "guess"));
  EXPECT_EQ(wrong.result(), http::status::unauthorized);
  const auto longer = Fetch(server.port(), Command("{}", std::string(kToken) + "x"));
  EXPECT_EQ(longer.result(), http::status::unauthorized);
  EXPECT_EQ(server.refused(), 3U);
  EXPECT_TRUE(server.TakeCommands().empty());
}

TEST_F(WebServerTest, RefusesEveryCommandWhenReadOnlyOrWithoutAToken403) {
  WebServerConfig read_only = Config();
  read_only.read_only = true;
  WebServer replay(read_only);
  EXPECT_EQ(Fetch(replay.port(), Command(R"({"kind":"start"})")).result(), http::status::forbidden);
  EXPECT_EQ(replay.refused(), 1U);

  WebServerConfig tokenless = Config();
  tokenless.operator_token.reset();
  WebServer open(tokenless);
  EXPECT_EQ(Fetch(open.port(), Command(R"({"kind":"start"})")).result(), http::status::forbidden);
  EXPECT_EQ(open.refused(), 1U);
  EXPECT_TRUE(open.TakeCommands().empty());
}

TEST_F(WebServerTest, RefusesMalformedAndOversizedBodies400) {
  WebServer server(Config());
  EXPECT_EQ(Fetch(server.port(), Command("{\"kind\":")).result(), http::status::bad_request);
  EXPECT_EQ(Fetch(server.port(), Command("[1,2]")).result(), http::status::bad_request);
  const std::string huge = R"({"reason":")" + std::string(40'000, 'a') + R"("})";
  const auto oversized = Fetch(server.port(), Command(huge));
  EXPECT_EQ(oversized.result(), http::status::bad_request);
  EXPECT_EQ(server.refused(), 3U);
  EXPECT_TRUE(server.TakeCommands().empty());
  EXPECT_EQ(Get(server.port(), "/api/state").result(), http::status::ok) << "still serving";
}

TEST_F(WebServerTest, ACommandNobodyAnswersGets503) {
  WebServerConfig config = Config();
  config.answer_timeout = 50ms;
  WebServer server(config);
  const auto response = Fetch(server.port(), Command(R"({"kind":"start"})"));
  EXPECT_EQ(response.result(), http::status::service_unavailable);
  EXPECT_EQ(server.refused(), 1U);
  EXPECT_TRUE(server.TakeCommands().empty()) << "an expired command is not handed out";
}

TEST_F(WebServerTest, WebSocketClientsGetTheSnapshotThenEveryBroadcast) {
  WebServer server(Config());
  server.SetDocuments(R"({"time_s":2})", "{}", "{}");
  WsTestClient first(server.port());
  WsTestClient second(server.port());
  const nlohmann::json snapshot =
      nlohmann::json::parse(R"({"type":"snapshot","state":{"time_s":2}})");
  EXPECT_EQ(nlohmann::json::parse(first.Read()), snapshot);
  EXPECT_EQ(nlohmann::json::parse(second.Read()), snapshot);
  // Both are registered once they have their snapshot.
  EXPECT_EQ(server.clients(), 2U);
  server.Broadcast(R"({"type":"delta","time_s":2.2})");
  server.Broadcast(R"({"type":"delta","time_s":2.4})");
  for (WsTestClient* client : {&first, &second}) {
    EXPECT_EQ(client->Read(), R"({"type":"delta","time_s":2.2})");
    EXPECT_EQ(client->Read(), R"({"type":"delta","time_s":2.4})");
  }
}

// The feed serialises the whole state seldom and broadcasts deltas often: a client
// that connects while the state document lags the deltas waits for a fresh one,
// and gets no delta before it (its snapshot holds them).
TEST_F(WebServerTest, HeldSnapshotsWaitForTheNextStateWithoutTheDeltasBefore) {
  WebServer server(Config());
  server.SetDocuments(R"({"time_s":2})", "{}", "{}");
  WsTestClient early(server.port());
  EXPECT_EQ(nlohmann::json::parse(early.Read()).at("state").at("time_s"), 2);
  EXPECT_FALSE(server.snapshot_wanted());
  server.HoldSnapshots();
  server.Broadcast(R"({"type":"delta","time_s":2.2})");
  WsTestClient late(server.port());
  const auto deadline = std::chrono::steady_clock::now() + kWait;
  while (!server.snapshot_wanted() && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::yield();  // the io thread registers it after the handshake
  }
  ASSERT_TRUE(server.snapshot_wanted());
  EXPECT_EQ(server.clients(), 2U);
  server.Broadcast(R"({"type":"delta","time_s":2.4})");
  server.SetDocuments(R"({"time_s":2.4})", "{}", "{}");
  EXPECT_FALSE(server.snapshot_wanted());
  server.Broadcast(R"({"type":"delta","time_s":2.6})");
  EXPECT_EQ(late.Read(), R"({"type":"snapshot","state":{"time_s":2.4}})");
  EXPECT_EQ(late.Read(), R"({"type":"delta","time_s":2.6})");
  for (const char* time : {"2.2", "2.4", "2.6"}) {
    EXPECT_EQ(early.Read(), std::string(R"({"type":"delta","time_s":)") + time + "}");
  }
  // Not held any more: the next client gets the state at once.
  WsTestClient next(server.port());
  EXPECT_EQ(next.Read(), R"({"type":"snapshot","state":{"time_s":2.4}})");
  // GET /api/plan follows SetPlanDocuments; the state stays.
  server.SetPlanDocuments(R"({"plan":2})", R"({"rows":2})");
  EXPECT_EQ(Get(server.port(), "/api/plan").body(), R"({"plan":2})");
  EXPECT_EQ(Get(server.port(), "/api/coverage").body(), R"({"rows":2})");
  EXPECT_EQ(Get(server.port(), "/api/state").body(), R"({"time_s":2.4})");
}

// The feed serialises the state only when asked: a GET /api/state while the
// deltas are ahead of the state document waits for the next one, never gets the
// stale one, and gets 503 if none comes in time.
TEST_F(WebServerTest, AStateRequestWhileSnapshotsAreHeldGetsTheNextState) {
  WebServerConfig config = Config();
  config.answer_timeout = 300ms;
  WebServer server(config);
  server.SetDocuments(R"({"time_s":1})", "{}", "{}");
  EXPECT_EQ(Get(server.port(), "/api/state").body(), R"({"time_s":1})") << "not held: at once";
  EXPECT_FALSE(server.snapshot_wanted());

  server.HoldSnapshots();
  std::future<testing::Response> answer =
      std::async(std::launch::async, [&] { return Get(server.port(), "/api/state"); });
  const auto deadline = std::chrono::steady_clock::now() + kWait;
  while (!server.snapshot_wanted() && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::yield();  // the io thread registers the request
  }
  ASSERT_TRUE(server.snapshot_wanted());
  server.SetDocuments(R"({"time_s":2})", "{}", "{}");
  EXPECT_FALSE(server.snapshot_wanted());
  const testing::Response fresh = answer.get();
  EXPECT_EQ(fresh.result(), http::status::ok);
  EXPECT_EQ(fresh.body(), R"({"time_s":2})");
  EXPECT_EQ(fresh[http::field::content_type], "application/json");

  // Held, and no state comes: 503 after answer_timeout; a later state is no harm.
  server.HoldSnapshots();
  const testing::Response late = Get(server.port(), "/api/state");
  EXPECT_EQ(late.result(), http::status::service_unavailable);
  EXPECT_NE(BodyOf(late).at("error").get<std::string>().find("no new state"), std::string::npos);
  server.SetDocuments(R"({"time_s":3})", "{}", "{}");
  const testing::Response head =
      Fetch(server.port(), MakeRequest(http::verb::head, "/api/state", "", {}));
  EXPECT_EQ(head.result(), http::status::ok);
  EXPECT_EQ(head[http::field::content_length], std::to_string(std::string(R"({"time_s":3})").size()));
}

// A server that listens before its feed has a state: the first clients get the
// first state, never the empty placeholder.
TEST_F(WebServerTest, WaitingForTheFirstStateNobodyGetsTheEmptyOne) {
  WebServerConfig config = Config();
  config.wait_for_first_state = true;
  WebServer server(config);
  WsTestClient early(server.port());
  std::future<testing::Response> answer =
      std::async(std::launch::async, [&] { return Get(server.port(), "/api/state"); });
  const auto deadline = std::chrono::steady_clock::now() + kWait;
  while (!server.snapshot_wanted() && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::yield();  // the io thread registers the client (or the request)
  }
  ASSERT_TRUE(server.snapshot_wanted());
  server.SetDocuments(R"({"time_s":0.2})", "{}", "{}");
  EXPECT_EQ(early.Read(), R"({"type":"snapshot","state":{"time_s":0.2}})");
  EXPECT_EQ(answer.get().body(), R"({"time_s":0.2})");
}

TEST_F(WebServerTest, AMalformedClientMessageGetsAnErrorAndTheServerServesOn) {
  WebServerConfig config = Config();
  config.max_client_message_bytes = 256;
  WebServer server(config);
  WsTestClient client(server.port());
  client.Read();  // snapshot
  client.Write("{\"type\":");
  EXPECT_EQ(nlohmann::json::parse(client.Read()).at("type"), "error");
  client.Write("42");
  EXPECT_EQ(nlohmann::json::parse(client.Read()).at("type"), "error");
  client.Write(R"({"type":"replay","pad":")" + std::string(300, 'x') + R"("})");
  const nlohmann::json too_long = nlohmann::json::parse(client.Read());
  EXPECT_EQ(too_long.at("type"), "error");
  EXPECT_NE(too_long.at("error").get<std::string>().find("256"), std::string::npos);
  client.Write(R"({"type":"replay","action":"pause"})");
  const std::vector<ClientMessage> messages = server.TakeClientMessages(kWait);
  ASSERT_EQ(messages.size(), 1U);
  EXPECT_EQ(messages[0].message.at("action"), "pause");
  EXPECT_TRUE(server.SendTo(messages[0].client, R"({"type":"replay","playing":false})"));
  EXPECT_EQ(client.Read(), R"({"type":"replay","playing":false})");
  EXPECT_EQ(Get(server.port(), "/api/state").result(), http::status::ok);
}

TEST_F(WebServerTest, DropsAClientThatFallsTooFarBehind) {
  WebServerConfig config = Config();
  config.max_client_queue = 4;
  WebServer server(config);
  WsTestClient reader(server.port());
  reader.Read();
  {
    WsTestClient stalled(server.port());
    stalled.Read();
    ASSERT_EQ(server.clients(), 2U);
    // The stalled client reads nothing more: once the socket buffers are full its
    // queue grows past 4 and it is dropped; the reader keeps up.
    const std::string big(64 * 1024, 'x');
    for (int i = 0; i < 20'000 && server.clients() == 2U; ++i) {
      server.Broadcast(big);
      EXPECT_EQ(reader.Read().size(), big.size());
    }
    EXPECT_EQ(server.clients(), 1U);
  }
  server.Broadcast("{}");
  EXPECT_EQ(reader.Read(), "{}");
}

TEST_F(WebServerTest, ServesHttpsAndWssWithTheGivenCertificate) {
  const auto cert = dir_ / "cert.pem";
  const auto key = dir_ / "key.pem";
  testing::WriteSelfSignedCertificate(cert, key);
  WebServerConfig config = Config();
  config.tls_cert = cert;
  config.tls_key = key;
  WebServer server(config);
  EXPECT_EQ(server.url(), "https://127.0.0.1:" + std::to_string(server.port()) + "/");
  server.SetDocuments(R"({"tls":true})", "{}", "{}");
  const auto state =
      testing::FetchTls(server.port(), cert, MakeRequest(http::verb::get, "/api/state"));
  EXPECT_EQ(state.body(), R"({"tls":true})");
  const auto index = testing::FetchTls(server.port(), cert, MakeRequest(http::verb::get, "/"));
  EXPECT_EQ(index.result(), http::status::ok);

  auto reply = std::async(std::launch::async, [&] {
    return testing::FetchTls(server.port(), cert, Command(R"({"kind":"start"})"));
  });
  const auto commands = server.TakeCommands(kWait);
  ASSERT_EQ(commands.size(), 1U);
  server.Answer(commands[0].id, 409, R"({"error":"no mission"})");
  EXPECT_EQ(reply.get().result(), http::status::conflict);

  WsTestClient client(server.port(), cert);
  EXPECT_EQ(nlohmann::json::parse(client.Read()).at("state").at("tls"), true);
  server.Broadcast(R"({"type":"delta"})");
  EXPECT_EQ(client.Read(), R"({"type":"delta"})");
  EXPECT_THROW(Get(server.port(), "/api/state"), boost::system::system_error)
      << "plain HTTP to the TLS port";
}

TEST_F(WebServerTest, ServesMbTilesWithTheRowFlippedAnd404ForAMissingTile) {
  WebServer plain(Config());
  EXPECT_EQ(Get(plain.port(), "/tiles/1/0/1.png").result(), http::status::not_found);

  const auto file = dir_ / "map.mbtiles";
  testing::WriteMbTiles(file, "tile-bytes");
  WebServerConfig config = Config();
  config.tiles = file;
  WebServer server(config);
  const auto tile = Get(server.port(), "/tiles/1/0/1.png");
  EXPECT_EQ(tile.result(), http::status::ok);
  EXPECT_EQ(tile.body(), "tile-bytes");
  EXPECT_EQ(tile[http::field::content_type], "image/png");
  EXPECT_EQ(Get(server.port(), "/tiles/1/0/0.png").result(), http::status::not_found);
  EXPECT_EQ(Get(server.port(), "/tiles/1/0/x.png").result(), http::status::not_found);
  const auto metadata = Get(server.port(), "/tiles/metadata.json");
  EXPECT_EQ(BodyOf(metadata).at("maxzoom"), 1);
  EXPECT_EQ(BodyOf(metadata).at("format"), "png");
}

// The message names the flag to fix.
void ExpectRefused(const WebServerConfig& config, const std::string& flag) {
  try {
    const WebServer server(config);
    ADD_FAILURE() << "taken; expected a refusal naming " << flag;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(flag), std::string::npos) << e.what();
  }
}

TEST_F(WebServerTest, RefusesABadConfigurationNamingTheFlag) {
  WebServerConfig open = Config();
  open.host = "0.0.0.0";
  ExpectRefused(open, "--http");
  WebServerConfig named = Config();
  named.host = "example.org";
  ExpectRefused(named, "--http");
  WebServerConfig no_root = Config();
  no_root.web_root = dir_ / "nowhere";
  ExpectRefused(no_root, "--web-root");
  WebServerConfig no_cert = Config();
  no_cert.tls_cert = dir_ / "missing.pem";
  no_cert.tls_key = dir_ / "missing-key.pem";
  ExpectRefused(no_cert, "--tls-cert");
  WebServerConfig bad_cert = Config();
  bad_cert.tls_cert = Write("cert.pem", "not a certificate");
  bad_cert.tls_key = Write("key.pem", "not a key");
  ExpectRefused(bad_cert, "--tls-cert");
  WebServerConfig half = Config();
  half.tls_cert = bad_cert.tls_cert;
  ExpectRefused(half, "--tls-key");
  WebServerConfig tiles = Config();
  tiles.tiles = Write("map.mbtiles", "not sqlite");
  ExpectRefused(tiles, "--tiles");
}

}  // namespace
}  // namespace fireswarm::server
