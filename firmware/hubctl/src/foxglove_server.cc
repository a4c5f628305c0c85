// Boost.Beast 1.74 (libboost-dev): the HTTP/1.1 upgrade and the WebSocket framing (RFC 6455) are
// Beast's; this file only decides who is let in and moves the sessions' frames.
#include "foxglove_server.h"

#include <array>
#include <atomic>
#include <chrono>
#include <map>
#include <optional>
#include <thread>

#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/websocket.hpp>
#include <fmt/format.h>

#include "listen_address.h"

namespace hubrt::hubctl::foxglove {
namespace {

namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
namespace net = boost::asio;
using tcp = net::ip::tcp;

constexpr auto kHandshakeTime = std::chrono::seconds(10);
constexpr std::uint32_t kMaxRequestHeader = 8 * 1024;
constexpr auto kStopGrace = std::chrono::seconds(2);
constexpr std::string_view kServerHeader = "hubrt hubctl foxglove";

std::string_view view(beast::string_view text) {
  return {text.data(), text.size()};
}

beast::string_view beast_view(std::string_view text) {
  return {text.data(), text.size()};
}

// Whether the request's Sec-WebSocket-Protocol lists the one this server speaks (RFC 6455 4.1:
// a comma-separated list, the header possibly repeated).
bool offers_subprotocol(const http::request<http::empty_body>& request) {
  const auto headers = request.equal_range(http::field::sec_websocket_protocol);
  for (auto header = headers.first; header != headers.second; ++header) {
    std::string_view list = view(header->value());
    while (!list.empty()) {
      const auto comma = list.find(',');
      std::string_view token = list.substr(0, comma);
      while (!token.empty() && (token.front() == ' ' || token.front() == '\t')) token.remove_prefix(1);
      while (!token.empty() && (token.back() == ' ' || token.back() == '\t')) token.remove_suffix(1);
      if (token == kSubprotocol) return true;
      list = comma == std::string_view::npos ? std::string_view() : list.substr(comma + 1);
    }
  }
  return false;
}

class Connection;

}  // namespace

struct WebSocketServer::Impl {
  Impl(const ServerOptions& o, Bridge& b, LogFn l) : options(o), bridge(b), log(std::move(l)) {}
  void accept();
  void stop();

  const ServerOptions options;
  Bridge& bridge;
  const LogFn log;
  // Before io: a Connection that io's queue still holds when io goes is destroyed with it.
  std::atomic<std::size_t> alive{0};  // Connection objects not yet destroyed
  net::io_context io{1};
  tcp::acceptor acceptor{io};
  std::uint16_t port = 0;
  std::size_t handshakes = 0;                                  // the I/O thread's
  std::map<const Connection*, std::weak_ptr<Connection>> all;  // the I/O thread's
  std::thread thread;
};

namespace {

class Connection final : public ClientLink, public std::enable_shared_from_this<Connection> {
 public:
  Connection(tcp::socket socket, WebSocketServer::Impl& server) : ws_(std::move(socket)), server_(server) {
    ++server_.alive;
  }
  ~Connection() override { --server_.alive; }

  void start() {
    beast::error_code ec;
    const tcp::endpoint remote = ws_.next_layer().socket().remote_endpoint(ec);
    const std::string address = remote.address().to_string();
    peer_ = ec                         ? std::string("?")
            : remote.address().is_v6() ? fmt::format("[{}]:{}", address, remote.port())
                                       : fmt::format("{}:{}", address, remote.port());
    // One small frame need not wait for the last one's ACK (Nagle).
    ws_.next_layer().socket().set_option(tcp::no_delay(true), ec);
    ws_.next_layer().socket().set_option(
        net::socket_base::send_buffer_size(server_.options.socket_send_buffer), ec);
    ++server_.handshakes;
    in_handshake_ = true;
    ws_.next_layer().expires_after(kHandshakeTime);
    parser_.emplace();
    parser_->header_limit(kMaxRequestHeader);
    http::async_read(ws_.next_layer(), buffer_, *parser_,
                     [self = shared_from_this()](beast::error_code e, std::size_t) { self->on_request(e); });
  }

  void wake() noexcept override {
    net::post(ws_.get_executor(), [self = shared_from_this()] { self->write_next(); });
  }
  void close() noexcept override {
    net::post(ws_.get_executor(), [self = shared_from_this()] { self->shut(); });
  }

  // After the I/O thread ended: the bridge forgets a client whose end it did not see.
  void abandon() { finish({}); }

  // On the I/O thread: the socket closes, every pending operation ends with an error.
  void shut() {
    beast::error_code ignored;
    ws_.next_layer().socket().shutdown(tcp::socket::shutdown_both, ignored);
    ws_.next_layer().close();
  }

 private:
  void end_handshake() {
    if (!in_handshake_) return;
    in_handshake_ = false;
    --server_.handshakes;
  }

  void on_request(beast::error_code ec) {
    if (ec) return finish({});  // gone, too slow or too long a header: nobody to answer
    const auto& request = parser_->get();
    origin_ = std::string(view(request[http::field::origin]));
    if (!host_allowed(view(request[http::field::host]), server_.options.address, server_.port))
      return refuse(http::status::forbidden, "unknown Host (this server answers its own address only)");
    if (!websocket::is_upgrade(request))
      return refuse(http::status::upgrade_required,
                    "hubctl foxglove serves the Foxglove WebSocket protocol: in Foxglove, Open connection, "
                    "Foxglove WebSocket, ws://<this address>");
    if (!offers_subprotocol(request))
      return refuse(http::status::bad_request, fmt::format("ask for the subprotocol {}", kSubprotocol));
    if (!server_.bridge.reserve())
      return refuse(http::status::service_unavailable,
                    "too many clients (hubctl foxglove --max-clients): try again later");
    reserved_ = true;
    ws_.set_option(websocket::stream_base::decorator([](websocket::response_type& response) {
      response.set(http::field::sec_websocket_protocol, beast_view(kSubprotocol));
      response.set(http::field::server, beast_view(kServerHeader));
    }));
    ws_.read_message_max(kMaxClientMessageBytes);
    ws_.async_accept(request, [self = shared_from_this()](beast::error_code e) { self->on_accept(e); });
  }

  void refuse(http::status status, const std::string& why) {
    if (server_.log) server_.log(fmt::format("refused {}: {}", peer_, why));
    response_.emplace(status, parser_->get().version());
    response_->set(http::field::server, beast_view(kServerHeader));
    response_->set(http::field::content_type, "text/plain; charset=utf-8");
    response_->keep_alive(false);
    response_->body() = why + "\n";
    response_->prepare_payload();
    http::async_write(ws_.next_layer(), *response_,
                      [self = shared_from_this()](beast::error_code, std::size_t) { self->finish({}); });
  }

  void on_accept(beast::error_code ec) {
    end_handshake();
    if (ec) {
      server_.bridge.release();
      reserved_ = false;
      return finish({});
    }
    ws_.next_layer().expires_never();
    // Beast's server settings: handshake and close within 30 s, a ping when the client has been
    // silent for half of 300 s, closed when it stays silent (a dead peer does not hold a place).
    ws_.set_option(websocket::stream_base::timeout::suggested(beast::role_type::server));
    parser_.reset();
    reserved_ = false;
    session_ = server_.bridge.connect(peer_, origin_, shared_from_this());
    read();
  }

  void read() {
    ws_.async_read(buffer_,
                   [self = shared_from_this()](beast::error_code e, std::size_t) { self->on_read(e); });
  }

  void on_read(beast::error_code ec) {
    if (ec) return finish(ec == websocket::error::closed ? std::string() : ec.message());
    const auto data = buffer_.cdata();
    const Time now = std::chrono::steady_clock::now();
    const bool wake =
        ws_.got_text()
            ? session_->on_text({static_cast<const char*>(data.data()), data.size()}, now)
            : session_->on_binary({static_cast<const std::uint8_t*>(data.data()), data.size()}, now);
    buffer_.consume(buffer_.size());
    if (wake) write_next();
    read();
  }

  void write_next() {
    if (writing_ || finished_ || !session_) return;
    writing_ = session_->next_frame();
    if (!writing_) return;
    auto done = [self = shared_from_this()](beast::error_code e, std::size_t) { self->on_write(e); };
    if (writing_->is_text()) {
      ws_.text(true);
      ws_.async_write(net::buffer(*writing_->text), std::move(done));
    } else {
      // The header and the sample's own bytes: no copy of the payload per client.
      ws_.binary(true);
      buffers_ = {net::buffer(writing_->header), net::buffer(writing_->sample->cdr)};
      ws_.async_write(buffers_, std::move(done));
    }
  }

  void on_write(beast::error_code ec) {
    writing_.reset();
    if (ec) return finish(ec.message());
    write_next();
  }

  void finish(const std::string& why) {
    if (finished_) return;
    finished_ = true;
    end_handshake();
    if (reserved_) server_.bridge.release();
    reserved_ = false;
    if (session_) {
      if (!why.empty() && server_.log)
        server_.log(fmt::format("client {} ({}): connection ended: {}", session_->id(), peer_, why));
      server_.bridge.disconnect(session_->id());
    }
    shut();
    server_.all.erase(this);
  }

  websocket::stream<beast::tcp_stream> ws_;
  WebSocketServer::Impl& server_;
  beast::flat_buffer buffer_;
  std::optional<http::request_parser<http::empty_body>> parser_;
  std::optional<http::response<http::string_body>> response_;
  std::string peer_;
  std::string origin_;
  bool in_handshake_ = false;
  bool reserved_ = false;
  bool finished_ = false;
  std::shared_ptr<ClientSession> session_;
  std::optional<OutFrame> writing_;
  std::array<net::const_buffer, 2> buffers_;
};

}  // namespace

void WebSocketServer::Impl::accept() {
  acceptor.async_accept([this](beast::error_code ec, tcp::socket socket) {
    if (!acceptor.is_open()) return;
    if (ec) {
      // Out of descriptors, say: try again shortly rather than spin.
      if (log) log(fmt::format("accept: {}", ec.message()));
      auto timer = std::make_shared<net::steady_timer>(io, std::chrono::milliseconds(100));
      timer->async_wait([this, timer](beast::error_code) { accept(); });
      return;
    }
    if (handshakes >= options.max_handshakes) {
      beast::error_code ignored;
      socket.close(ignored);
    } else {
      auto connection = std::make_shared<Connection>(std::move(socket), *this);
      all.emplace(connection.get(), connection);
      connection->start();
    }
    accept();
  });
}

void WebSocketServer::Impl::stop() {
  beast::error_code ignored;
  acceptor.close(ignored);
  for (auto& [key, weak] : all) {
    if (auto connection = weak.lock()) connection->shut();
  }
}

WebSocketServer::WebSocketServer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

Expected<std::unique_ptr<WebSocketServer>> WebSocketServer::start(const ServerOptions& options,
                                                                  Bridge& bridge, LogFn log) {
  auto impl = std::make_unique<Impl>(options, bridge, std::move(log));
  const auto failed = [&](const std::string& what, const beast::error_code& ec) {
    return make_error(ErrorCode::kUnavailable, fmt::format("cannot listen on {}:{}: {}: {}", options.address,
                                                           options.port, what, ec.message()));
  };
  beast::error_code ec;
  const auto address =
      net::ip::make_address(options.address == "localhost" ? "127.0.0.1" : options.address, ec);
  if (ec) return failed("address", ec);
  const tcp::endpoint endpoint(address, options.port);
  impl->acceptor.open(endpoint.protocol(), ec);
  if (!ec) impl->acceptor.set_option(net::socket_base::reuse_address(true), ec);
  if (!ec) impl->acceptor.bind(endpoint, ec);
  if (ec) return failed("bind", ec);
  impl->acceptor.listen(net::socket_base::max_listen_connections, ec);
  if (ec) return failed("listen", ec);
  impl->port = impl->acceptor.local_endpoint(ec).port();
  impl->accept();
  Impl* raw = impl.get();
  impl->thread = std::thread([raw] { raw->io.run(); });
  return std::unique_ptr<WebSocketServer>(new WebSocketServer(std::move(impl)));
}

WebSocketServer::~WebSocketServer() {
  Impl* impl = impl_.get();
  net::post(impl->io, [impl] { impl->stop(); });
  // The closed sockets end every pending operation; wait a little for them to, then stop the rest.
  const auto deadline = std::chrono::steady_clock::now() + kStopGrace;
  while (impl->alive > 0 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  impl->io.stop();
  impl->thread.join();
  // The I/O thread is gone: what it did not finish is finished here, so that the bridge holds no
  // connection of a server that is no more.
  const auto all = impl->all;
  for (const auto& [key, weak] : all) {
    if (auto connection = weak.lock()) connection->abandon();
  }
}

std::uint16_t WebSocketServer::port() const noexcept {
  return impl_->port;
}

}  // namespace hubrt::hubctl::foxglove
