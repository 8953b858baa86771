#include "web_hub.hpp"

#include <algorithm>
#include <iostream>
#include <utility>

namespace fireswarm::server::web {
namespace {

constexpr int kOk = 200;

Text EmptyObject() {
  return std::make_shared<const std::string>("{}");
}

Text SnapshotMessage(const Text& state) {
  return std::make_shared<const std::string>(R"({"type":"snapshot","state":)" + *state + "}");
}

// Takes everything from `queue` once it has something or `wait` passed.
template <class T>
std::vector<T> TakeAll(std::unique_lock<std::mutex>& lock, std::condition_variable& arrived,
                       std::deque<T>& queue, std::chrono::milliseconds wait) {
  if (queue.empty() && wait.count() > 0) {
    arrived.wait_for(lock, wait, [&] { return !queue.empty(); });
  }
  std::vector<T> taken(std::make_move_iterator(queue.begin()),
                       std::make_move_iterator(queue.end()));
  queue.clear();
  return taken;
}

}  // namespace

Hub::Hub(WebServerConfig config, std::unique_ptr<MbTiles> tiles)
    : config_(std::move(config)),
      tiles_(std::move(tiles)),
      documents_{EmptyObject(), EmptyObject(), EmptyObject()},
      snapshots_held_(config_.wait_for_first_state) {}

Documents Hub::documents() const {
  const std::lock_guard lock(mutex_);
  return documents_;
}

void Hub::SetDocuments(Text state, Text plan, Text coverage) {
  std::vector<std::shared_ptr<WsClient>> released;
  std::vector<Responder> requests;  // GET /api/state waiting for this state
  Text snapshot;
  {
    const std::lock_guard lock(mutex_);
    documents_ = {std::move(state), std::move(plan), std::move(coverage)};
    snapshots_held_ = false;
    snapshot_wanted_.store(false, std::memory_order_release);
    for (const std::uint64_t id : state_requests_) {
      const auto open = open_.find(id);
      if (open == open_.end()) continue;  // expired
      requests.push_back(std::move(open->second));
      open_.erase(open);
    }
    state_requests_.clear();
    if (!waiting_.empty()) {
      snapshot = SnapshotMessage(documents_.state);
      for (auto& [id, client] : waiting_) {
        if (auto locked = client.lock()) released.push_back(std::move(locked));
        clients_.emplace(id, std::move(client));
      }
      waiting_.clear();
    }
    state = documents_.state;
  }
  // Sent after the lock. SetDocuments and Broadcast come from one thread (the
  // feed's), so no broadcast overtakes the snapshot on a client's queue.
  for (const auto& client : released) client->Send(snapshot);
  for (const Responder& request : requests) request(kOk, *state);
}

void Hub::SetPlanDocuments(Text plan, Text coverage) {
  const std::lock_guard lock(mutex_);
  documents_.plan = std::move(plan);
  documents_.coverage = std::move(coverage);
}

void Hub::HoldSnapshots() {
  const std::lock_guard lock(mutex_);
  snapshots_held_ = true;
}

bool Hub::snapshot_wanted() const {
  return snapshot_wanted_.load(std::memory_order_acquire);
}

std::uint64_t Hub::WaitForState(Responder responder) {
  Text state;
  {
    const std::lock_guard lock(mutex_);
    if (snapshots_held_) {
      const std::uint64_t id = next_id_++;
      open_.emplace(id, std::move(responder));
      state_requests_.push_back(id);
      snapshot_wanted_.store(true, std::memory_order_release);
      return id;
    }
    state = documents_.state;
  }
  responder(kOk, *state);
  return 0;
}

std::uint64_t Hub::QueueCommand(nlohmann::json body, std::string peer, Responder responder) {
  std::uint64_t id = 0;
  {
    const std::lock_guard lock(mutex_);
    id = next_id_++;
    commands_.push_back({id, std::move(body), std::move(peer)});
    commands_waiting_.store(true, std::memory_order_release);
    open_.emplace(id, std::move(responder));
  }
  arrived_.notify_all();
  return id;
}

std::vector<PendingCommand> Hub::TakeCommands(std::chrono::milliseconds wait) {
  // The feed asks at every simulation step; most of the time nothing waits.
  if (wait.count() <= 0 && !commands_waiting_.load(std::memory_order_acquire)) return {};
  std::unique_lock lock(mutex_);
  std::vector<PendingCommand> taken = TakeAll(lock, arrived_, commands_, wait);
  commands_waiting_.store(false, std::memory_order_release);
  return taken;
}

bool Hub::Answer(std::uint64_t id, int http_status, std::string json_body) {
  Responder responder;
  {
    const std::lock_guard lock(mutex_);
    const auto open = open_.find(id);
    if (open == open_.end()) return false;
    responder = std::move(open->second);
    open_.erase(open);
  }
  responder(http_status, std::move(json_body));
  return true;
}

bool Hub::Expire(std::uint64_t id) {
  Responder dropped;  // destroyed outside the lock (it holds the session)
  const std::lock_guard lock(mutex_);
  const auto open = open_.find(id);
  if (open == open_.end()) return false;
  dropped = std::move(open->second);
  open_.erase(open);
  std::erase_if(commands_, [id](const PendingCommand& c) { return c.id == id; });
  return true;
}

void Hub::Refuse(const std::string& peer, const std::string& reason) {
  ++refused_;
  std::cerr << "web: refused a command from " << peer << ": " << reason << std::endl;
}

std::uint64_t Hub::AddClient(std::weak_ptr<WsClient> client, Text* snapshot) {
  const std::lock_guard lock(mutex_);
  const std::uint64_t id = next_id_++;
  if (snapshots_held_) {
    waiting_.emplace(id, std::move(client));
    snapshot_wanted_.store(true, std::memory_order_release);
    *snapshot = nullptr;
  } else {
    clients_.emplace(id, std::move(client));
    *snapshot = SnapshotMessage(documents_.state);
  }
  return id;
}

void Hub::RemoveClient(std::uint64_t id) {
  const std::lock_guard lock(mutex_);
  clients_.erase(id);
  waiting_.erase(id);
}

void Hub::Broadcast(const Text& message) {
  std::vector<std::shared_ptr<WsClient>> clients;
  {
    const std::lock_guard lock(mutex_);
    for (const auto& [id, client] : clients_) {
      if (auto locked = client.lock()) clients.push_back(std::move(locked));
    }
  }
  for (const auto& client : clients) client->Send(message);
}

bool Hub::SendTo(std::uint64_t id, const Text& message) {
  std::shared_ptr<WsClient> client;
  {
    const std::lock_guard lock(mutex_);
    const auto found = clients_.find(id);
    if (found != clients_.end()) client = found->second.lock();
  }
  if (!client) return false;
  client->Send(message);
  return true;
}

std::size_t Hub::clients() const {
  const std::lock_guard lock(mutex_);
  return clients_.size() + waiting_.size();
}

void Hub::PushClientMessage(ClientMessage message) {
  {
    const std::lock_guard lock(mutex_);
    client_messages_.push_back(std::move(message));
    messages_waiting_.store(true, std::memory_order_release);
  }
  arrived_.notify_all();
}

std::vector<ClientMessage> Hub::TakeClientMessages(std::chrono::milliseconds wait) {
  if (wait.count() <= 0 && !messages_waiting_.load(std::memory_order_acquire)) return {};
  std::unique_lock lock(mutex_);
  std::vector<ClientMessage> taken = TakeAll(lock, arrived_, client_messages_, wait);
  messages_waiting_.store(false, std::memory_order_release);
  return taken;
}

void Hub::DropAll() {
  std::map<std::uint64_t, Responder> open;
  std::map<std::uint64_t, std::weak_ptr<WsClient>> clients;
  {
    const std::lock_guard lock(mutex_);
    open.swap(open_);
    clients.swap(clients_);
    waiting_.clear();
    state_requests_.clear();
    commands_.clear();
  }
}

}  // namespace fireswarm::server::web
