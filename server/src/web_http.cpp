// An HTTP session: reads requests one at a time, answers them from the routes,
// queues commands for the caller and waits (without blocking the io thread) for
// its answer, and hands a WebSocket upgrade to web_socket.cpp. Plain and TLS
// sessions are one template over the stream (Beast's advanced server, flex).
#include <array>
#include <boost/asio/dispatch.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/ssl.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket/rfc6455.hpp>
#include <optional>

#include "web_sessions.hpp"

namespace fireswarm::server::web {
namespace {

/// A connection idle (or a request this slow) this long is closed.
constexpr std::chrono::seconds kIdle{30};
/// After an error reply that closes the connection, what the peer still sends is
/// read and dropped this long, so the close does not reset the reply away.
constexpr std::chrono::seconds kLinger{2};

std::string PeerOf(const tcp::socket& socket) {
  boost::system::error_code error;
  const tcp::endpoint peer = socket.remote_endpoint(error);
  if (error) return "unknown";
  const std::string address = peer.address().to_string();
  return (peer.address().is_v6() ? "[" + address + "]" : address) + ":" +
         std::to_string(peer.port());
}

template <class Stream>
class HttpSession : public std::enable_shared_from_this<HttpSession<Stream>> {
 public:
  template <class... Args>
  HttpSession(std::shared_ptr<Hub> hub, std::string peer, Args&&... stream)
      : hub_(std::move(hub)),
        peer_(std::move(peer)),
        stream_(std::forward<Args>(stream)...),
        answer_timer_(stream_.get_executor()) {}

  void Start() {
    if constexpr (std::is_same_v<Stream, TlsStream>) {
      beast::get_lowest_layer(stream_).expires_after(kIdle);
      stream_.async_handshake(asio::ssl::stream_base::server,
                              [self = this->shared_from_this()](beast::error_code error) {
                                if (!error) self->Read();
                              });
    } else {
      Read();
    }
  }

 private:
  void Read() {
    parser_.emplace();
    parser_->body_limit(hub_->config().max_command_bytes);
    beast::get_lowest_layer(stream_).expires_after(kIdle);
    http::async_read(stream_, buffer_, *parser_,
                     [self = this->shared_from_this()](beast::error_code error, std::size_t) {
                       self->OnRead(error);
                     });
  }

  void OnRead(beast::error_code error) {
    if (error == http::error::end_of_stream) return Close();
    if (error == http::error::body_limit) {
      hub_->Refuse(peer_, "request body over " + std::to_string(hub_->config().max_command_bytes) +
                              " bytes");
      return WriteFinal(http::status::bad_request, "request body too large");
    }
    if (error == http::error::header_limit) {
      return WriteFinal(http::status::bad_request, "request header too large");
    }
    if (error && error.category() == http::make_error_code(http::error::bad_target).category()) {
      return WriteFinal(http::status::bad_request, "malformed request");
    }
    if (error) return;  // timeout, reset: the connection is gone
    Request request = parser_->release();
    const std::optional<std::string> path = DecodePath(View(request.target()));
    if (beast::websocket::is_upgrade(request)) {
      if (path == "/ws") {
        beast::get_lowest_layer(stream_).expires_never();
        StartWebSocket(hub_, std::move(stream_), std::move(request), peer_);
        return;
      }
      return Write(ErrorReply(request, http::status::not_found, "the WebSocket is at /ws"));
    }
    if (path == "/api/command") return Command(std::move(request));
    if (path == "/api/state" &&
        (request.method() == http::verb::get || request.method() == http::verb::head)) {
      return State(std::move(request));
    }
    Write(Route(*hub_, request));
  }

  // An answer from the caller's thread, posted here. It holds the session alive
  // until then.
  Responder AnswerLater(const Request& request) {
    return [self = this->shared_from_this(), executor = stream_.get_executor(), request](
               int status, std::string body) {
      asio::post(executor, [self, request, status, body = std::move(body)]() mutable {
        self->answer_timer_.cancel();
        self->Write(
            Reply(request, static_cast<http::status>(status), std::move(body), "application/json"));
      });
    };
  }

  // The state document, fresh: while the feed's deltas are ahead of it, the
  // answer waits for the feed's next state (Hub::WaitForState).
  void State(Request request) {
    const std::uint64_t id = hub_->WaitForState(AnswerLater(request));
    if (id == 0) return;
    std::weak_ptr<HttpSession> weak = this->shared_from_this();
    answer_timer_.expires_after(hub_->config().answer_timeout);
    answer_timer_.async_wait([weak, id, request = std::move(request)](beast::error_code error) {
      auto self = weak.lock();
      if (error || !self || !self->hub_->Expire(id)) return;
      self->Write(ErrorReply(request, http::status::service_unavailable,
                             "the server made no new state in time"));
    });
  }

  void Command(Request request) {
    std::weak_ptr<HttpSession> weak = this->shared_from_this();
    std::uint64_t id = 0;
    std::optional<Response> refused =
        AdmitCommand(*hub_, request, peer_, AnswerLater(request), &id);
    if (refused) return Write(std::move(*refused));
    answer_timer_.expires_after(hub_->config().answer_timeout);
    answer_timer_.async_wait([weak, id, request = std::move(request)](beast::error_code error) {
      auto self = weak.lock();
      if (error || !self || !self->hub_->Expire(id)) return;
      self->hub_->Refuse(self->peer_, "command " + std::to_string(id) + " not answered in time");
      self->Write(ErrorReply(request, http::status::service_unavailable,
                             "the server did not answer the command in time"));
    });
  }

  void Write(Response response) {
    response_ = std::move(response);
    http::async_write(stream_, response_,
                      [self = this->shared_from_this()](beast::error_code error, std::size_t) {
                        if (error) return;
                        if (self->response_.need_eof()) return self->Close();
                        self->Read();
                      });
  }

  // An error reply after which the request cannot be read on: reply, then close.
  void WriteFinal(http::status status, const std::string& text) {
    Request request;
    request.version(11);
    request.keep_alive(false);
    Write(ErrorReply(request, status, text));
  }

  void Close() {
    if constexpr (std::is_same_v<Stream, TlsStream>) {
      beast::get_lowest_layer(stream_).expires_after(kLinger);
      stream_.async_shutdown([self = this->shared_from_this()](beast::error_code) {});
    } else {
      beast::error_code ignored;
      stream_.socket().shutdown(tcp::socket::shutdown_send, ignored);
      Drain();
    }
  }

  // Reads until the peer closes too (or kLinger passes), dropping the bytes.
  void Drain() {
    stream_.expires_after(kLinger);
    stream_.async_read_some(asio::buffer(drain_), [self = this->shared_from_this()](
                                                      beast::error_code error, std::size_t) {
      if (!error) self->Drain();
    });
  }

  std::shared_ptr<Hub> hub_;
  std::string peer_;
  Stream stream_;
  asio::steady_timer answer_timer_;
  beast::flat_buffer buffer_;
  std::optional<http::request_parser<http::string_body>> parser_;
  Response response_;
  std::array<char, 4096> drain_{};
};

}  // namespace

void StartPlainSession(std::shared_ptr<Hub> hub, tcp::socket socket) {
  std::string peer = PeerOf(socket);
  std::make_shared<HttpSession<PlainStream>>(std::move(hub), std::move(peer), std::move(socket))
      ->Start();
}

void StartTlsSession(std::shared_ptr<Hub> hub, tcp::socket socket, asio::ssl::context& tls) {
  std::string peer = PeerOf(socket);
  std::make_shared<HttpSession<TlsStream>>(std::move(hub), std::move(peer), std::move(socket), tls)
      ->Start();
}

}  // namespace fireswarm::server::web
