// The command center's HTTP/WebSocket adapter (docs/command_center.md): Boost.Beast
// on Boost.Asio, running its io_context on a thread of its own. It is transport
// only: the documents it serves, the commands it takes and the messages it
// broadcasts come from and go to the caller's thread (the server core and the
// page's model live there), through the calls below, each cheap and thread-safe.
//
// Routes: static files under the web root (GET/HEAD), `GET /api/state|plan|coverage`
// (the documents last given to SetDocuments), `POST /api/command` (authenticated,
// queued for the caller, answered by it), `GET /ws` (the WebSocket stream), and
// `GET /tiles/{z}/{x}/{y}.png` and `/tiles/metadata.json` from an MBTiles file.
// With a certificate and key, every route is HTTPS/WSS (Boost.Asio SSL, OpenSSL).
#pragma once

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace fireswarm::server {

struct WebServerConfig {
  /// Address to bind: an IPv4/IPv6 literal or "localhost". Anything but loopback
  /// needs TLS (tls_cert and tls_key).
  std::string host = "127.0.0.1";
  std::uint16_t port = 0;          ///< 0: any free port (WebServer::port() tells which)
  std::filesystem::path web_root;  ///< the page's files (GET /, /app.js, node_modules/...)
  /// The operator's token, expected as `Authorization: Bearer TOKEN` on commands;
  /// nullopt: every command is refused (403).
  std::optional<std::string> operator_token;
  std::filesystem::path tls_cert;  ///< PEM certificate (chain); empty: plain HTTP
  std::filesystem::path tls_key;   ///< PEM private key; given exactly when tls_cert is
  std::filesystem::path tiles;     ///< MBTiles file for /tiles/...; empty: none (404)
  bool read_only = false;          ///< every command is refused (403), e.g. a replay
  /// Until the first SetDocuments, new WebSocket clients and GET /api/state wait
  /// (as when held: HoldSnapshots) rather than get `{}`: for a server that
  /// listens before its feed has a state.
  bool wait_for_first_state = false;
  /// A command's body may be this long at most, bytes (longer: 400).
  std::size_t max_command_bytes = 16 * 1024;
  /// A command the caller has not answered this long after it arrived gets 503.
  std::chrono::milliseconds answer_timeout{5000};
  /// A WebSocket client more than this many messages behind is disconnected
  /// (rather than queueing without bound); it can reconnect and get a snapshot.
  std::size_t max_client_queue = 256;
  /// A WebSocket message from a client may be this long, bytes (longer: an error
  /// message back; over 16 times this the connection is closed).
  std::size_t max_client_message_bytes = 4 * 1024;
};

/// A command received on POST /api/command, waiting for the caller's Answer().
struct PendingCommand {
  std::uint64_t id = 0;  ///< what Answer() takes
  nlohmann::json body;   ///< the request's JSON body (an object)
  std::string peer;      ///< the client's address, "127.0.0.1:41234"
};

/// A message a WebSocket client sent (e.g. replay controls), parsed.
struct ClientMessage {
  std::uint64_t client = 0;  ///< the connection's number, for SendTo()
  nlohmann::json message;    ///< a JSON object
  std::string peer;
};

class WebServer {
 public:
  /// Checks the configuration, binds and starts serving on its own thread. Throws
  /// std::invalid_argument naming the flag (--http, --web-root, --tls-cert,
  /// --tls-key, --tiles) for a non-loopback host without TLS, a web root that is
  /// not a directory, a certificate, key or tiles file that cannot be read or
  /// used; std::runtime_error naming the address when it cannot be bound.
  explicit WebServer(WebServerConfig config);
  /// Stops serving: open connections are closed, unanswered commands dropped.
  ~WebServer();
  WebServer(const WebServer&) = delete;
  WebServer& operator=(const WebServer&) = delete;

  /// The port bound (the configured one, or the one picked for port 0).
  std::uint16_t port() const;
  /// "http://HOST:PORT/" or "https://HOST:PORT/" (IPv6 hosts in brackets).
  std::string url() const;

  /// The JSON documents served as /api/state, /api/plan and /api/coverage from now
  /// on; `state` is also each new WebSocket client's snapshot. Until the first
  /// call, each is `{}`.
  void SetDocuments(std::string state_json, std::string plan_json, std::string coverage_json);
  /// Replaces the /api/plan and /api/coverage documents; the state stays.
  void SetPlanDocuments(std::string plan_json, std::string coverage_json);
  /// For a caller that rebuilds the state document less often than it broadcasts
  /// (serialising a big fleet's state at every update costs more than the delta):
  /// call before broadcasting a change the state document does not hold yet. New
  /// WebSocket clients then wait, without broadcasts, until the next SetDocuments
  /// gives them a snapshot that holds it, and GET /api/state waits for that
  /// document too. SetDocuments, SetPlanDocuments,
  /// HoldSnapshots and Broadcast are to be called from one thread.
  void HoldSnapshots();
  /// True while a WebSocket client waits for its snapshot, or a GET /api/state
  /// for the state, because snapshots are held (see HoldSnapshots): the caller
  /// should SetDocuments soon. GET /api/state gets 503 after answer_timeout.
  bool snapshot_wanted() const;

  /// Sends `json` to every connected WebSocket client (queued per client).
  void Broadcast(std::string json);
  /// Sends `json` to one WebSocket client; false when it is not connected.
  bool SendTo(std::uint64_t client, std::string json);

  /// The commands received since the last call, oldest first. Waits up to `wait`
  /// for one when there is none.
  std::vector<PendingCommand> TakeCommands(std::chrono::milliseconds wait = {});
  /// Replies to a command with `http_status` and `json_body`. False when the
  /// command is unknown or was already answered (503 after answer_timeout).
  bool Answer(std::uint64_t id, int http_status, std::string json_body);

  /// The WebSocket messages received since the last call, oldest first. Waits up
  /// to `wait` for one when there is none.
  std::vector<ClientMessage> TakeClientMessages(std::chrono::milliseconds wait = {});

  /// Commands refused here (401, 403, 400, 503 unanswered), since the start;
  /// each was logged on stderr with the peer and the reason.
  std::uint64_t refused() const;
  /// WebSocket clients connected now.
  std::size_t clients() const;
  /// CPU time the io thread (every connection's HTTP, WebSocket and TLS work)
  /// has taken since it started, s: the adapter's own share of the process's CPU.
  double io_cpu_seconds() const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace fireswarm::server
