// The WebSocket stream (/ws): a snapshot of the state first, then whatever the
// caller broadcasts, each client with a bounded queue of its own; messages from
// the client go to the hub, parsed, or get an error message back.
#include <boost/asio/post.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/websocket.hpp>
#include <boost/beast/websocket/ssl.hpp>
#include <deque>
#include <iostream>

#include "web_sessions.hpp"

namespace fireswarm::server::web {
namespace {

namespace websocket = beast::websocket;

/// A client message this many times over the configured limit closes the
/// connection (Beast's read limit), so no client makes the server buffer much.
constexpr std::size_t kHardLimitFactor = 16;

Text ErrorMessage(const std::string& error) {
  return std::make_shared<const std::string>(
      nlohmann::json{{"type", "error"}, {"error", error}}.dump());
}

template <class Stream>
class WsSession : public WsClient, public std::enable_shared_from_this<WsSession<Stream>> {
 public:
  WsSession(std::shared_ptr<Hub> hub, Stream stream, std::string peer)
      : hub_(std::move(hub)), peer_(std::move(peer)), ws_(std::move(stream)) {}

  ~WsSession() override {
    if (id_ != 0) hub_->RemoveClient(id_);
  }

  void Start(Request request) {
    ws_.set_option(websocket::stream_base::timeout::suggested(beast::role_type::server));
    ws_.read_message_max(kHardLimitFactor * hub_->config().max_client_message_bytes);
    ws_.async_accept(request, [self = this->shared_from_this()](beast::error_code error) {
      if (!error) self->OnAccept();
    });
  }

  void Send(Text message) override {
    asio::post(ws_.get_executor(), [self = this->shared_from_this(), message = std::move(message)] {
      self->Enqueue(message);
    });
  }

 private:
  void OnAccept() {
    Text snapshot;
    id_ = hub_->AddClient(this->weak_from_this(), &snapshot);
    if (snapshot) Enqueue(std::move(snapshot));  // else the hub sends it once it has one
    Read();
  }

  void Read() {
    ws_.async_read(buffer_, [self = this->shared_from_this()](
                                beast::error_code error, std::size_t) { self->OnRead(error); });
  }

  void OnRead(beast::error_code error) {
    if (error) return Drop();  // closed, timed out, over the hard limit
    std::string text = beast::buffers_to_string(buffer_.data());
    buffer_.consume(buffer_.size());
    const std::size_t limit = hub_->config().max_client_message_bytes;
    if (text.size() > limit) {
      Enqueue(ErrorMessage("message over " + std::to_string(limit) + " bytes"));
      return Read();
    }
    nlohmann::json message = nlohmann::json::parse(text, nullptr, false);
    if (message.is_discarded()) {
      Enqueue(ErrorMessage("the message is not JSON"));
    } else if (!message.is_object()) {
      Enqueue(ErrorMessage("the message is not a JSON object"));
    } else {
      hub_->PushClientMessage({id_, std::move(message), peer_});
    }
    Read();
  }

  void Enqueue(const Text& message) {
    if (dropped_) return;
    if (queue_.size() >= hub_->config().max_client_queue) {
      std::cerr << "web: dropped WebSocket client " << peer_ << ": more than "
                << hub_->config().max_client_queue << " messages behind" << std::endl;
      // Closing the socket ends the pending write and read; the read's end drops
      // the client. A polite close would wait behind the write that is stuck.
      beast::error_code ignored;
      beast::get_lowest_layer(ws_).socket().close(ignored);
      return Drop();
    }
    queue_.push_back(message);
    if (queue_.size() == 1) Write();
  }

  void Write() {
    ws_.text(true);
    const Text message = queue_.front();
    ws_.async_write(asio::buffer(*message), [self = this->shared_from_this(), message](
                                                beast::error_code error, std::size_t) {
      if (error || self->dropped_) return self->Drop();
      self->queue_.pop_front();
      if (!self->queue_.empty()) self->Write();
    });
  }

  void Drop() {
    dropped_ = true;
    queue_.clear();
    if (id_ != 0) hub_->RemoveClient(id_);
    id_ = 0;
  }

  std::shared_ptr<Hub> hub_;
  std::string peer_;
  websocket::stream<Stream> ws_;
  beast::flat_buffer buffer_;
  std::deque<Text> queue_;  // front: being written
  std::uint64_t id_ = 0;    // 0: not registered with the hub
  bool dropped_ = false;
};

}  // namespace

template <class Stream>
void StartWebSocket(std::shared_ptr<Hub> hub, Stream stream, Request request, std::string peer) {
  std::make_shared<WsSession<Stream>>(std::move(hub), std::move(stream), std::move(peer))
      ->Start(std::move(request));
}

template void StartWebSocket<PlainStream>(std::shared_ptr<Hub>, PlainStream, Request, std::string);
template void StartWebSocket<TlsStream>(std::shared_ptr<Hub>, TlsStream, Request, std::string);

}  // namespace fireswarm::server::web
