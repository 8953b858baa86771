// What the web server's sessions (on its io thread) and the caller's thread
// share: the documents, the commands waiting for an answer, the WebSocket clients
// and the messages they sent, the refusal count. No Asio here: a session hands in
// callbacks that post to its own executor.
#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "fireswarm/server/mbtiles.hpp"
#include "fireswarm/server/web_server.hpp"

namespace fireswarm::server::web {

using Text = std::shared_ptr<const std::string>;

/// A connected WebSocket client as the hub sees it. Send may be called from any
/// thread; it queues the message on the client's own executor.
class WsClient {
 public:
  virtual ~WsClient() = default;
  virtual void Send(Text message) = 0;
};

/// Replies to a queued command (posts the reply to its session); any thread.
using Responder = std::function<void(int http_status, std::string json_body)>;

struct Documents {
  Text state;
  Text plan;
  Text coverage;
};

class Hub {
 public:
  Hub(WebServerConfig config, std::unique_ptr<MbTiles> tiles);

  const WebServerConfig& config() const { return config_; }
  const MbTiles* tiles() const { return tiles_.get(); }

  Documents documents() const;
  /// Sets the three documents; every client waiting for its snapshot gets it now.
  void SetDocuments(Text state, Text plan, Text coverage);
  /// Sets the plan and coverage documents; the state stays.
  void SetPlanDocuments(Text plan, Text coverage);
  /// The state document no longer holds everything broadcast: clients that connect
  /// from now on wait for the next SetDocuments for their snapshot.
  void HoldSnapshots();
  /// True while a client waits for its snapshot or a GET /api/state for the
  /// state (no lock: the feed looks at every step).
  bool snapshot_wanted() const;
  /// GET /api/state: `responder` gets (200, the state document) now unless
  /// snapshots are held, else at the next SetDocuments. Returns 0 when answered
  /// now, else the request's ID for Expire.
  std::uint64_t WaitForState(Responder responder);

  /// Queues a command for the caller; `responder` is called once by Answer().
  std::uint64_t QueueCommand(nlohmann::json body, std::string peer, Responder responder);
  std::vector<PendingCommand> TakeCommands(std::chrono::milliseconds wait);
  bool Answer(std::uint64_t id, int http_status, std::string json_body);
  /// Forgets an unanswered command; true when it was still waiting (its session
  /// then replies 503 itself).
  bool Expire(std::uint64_t id);

  /// Logs a refused request on stderr (one line) and counts it.
  void Refuse(const std::string& peer, const std::string& reason);
  std::uint64_t refused() const { return refused_.load(); }

  /// Registers a client; returns its number and the snapshot message it must get
  /// first (taken together, so no broadcast falls between them). While snapshots
  /// are held, the snapshot is null: the client gets it, and the broadcasts after
  /// it, with the next SetDocuments.
  std::uint64_t AddClient(std::weak_ptr<WsClient> client, Text* snapshot);
  void RemoveClient(std::uint64_t id);
  void Broadcast(const Text& message);
  bool SendTo(std::uint64_t id, const Text& message);
  std::size_t clients() const;
  void PushClientMessage(ClientMessage message);
  std::vector<ClientMessage> TakeClientMessages(std::chrono::milliseconds wait);

  /// Drops every responder and client (they hold sessions): on shutdown.
  void DropAll();

 private:
  const WebServerConfig config_;
  const std::unique_ptr<MbTiles> tiles_;
  mutable std::mutex mutex_;
  std::condition_variable arrived_;  // a command or a client message
  Documents documents_;
  std::uint64_t next_id_ = 1;
  std::deque<PendingCommand> commands_;      // not taken yet
  std::map<std::uint64_t, Responder> open_;  // not answered yet
  std::map<std::uint64_t, std::weak_ptr<WsClient>> clients_;
  std::map<std::uint64_t, std::weak_ptr<WsClient>> waiting_;  // for their snapshot
  std::vector<std::uint64_t> state_requests_;  // GET /api/state in open_, for the next state
  bool snapshots_held_ = false;
  std::atomic<bool> snapshot_wanted_{false};  // !waiting_.empty() || !state_requests_.empty()
  std::deque<ClientMessage> client_messages_;
  std::atomic<std::uint64_t> refused_{0};
  // Set (under mutex_) when one is queued, cleared when all are taken: a look
  // without the lock for the caller that polls at every step.
  std::atomic<bool> commands_waiting_{false};
  std::atomic<bool> messages_waiting_{false};
};

}  // namespace fireswarm::server::web
