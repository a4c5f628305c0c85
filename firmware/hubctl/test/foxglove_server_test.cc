// The WebSocket side of hubctl foxglove on loopback, seen from a plain TCP client: who is let in.
// A handshake is answered with HTTP — 426 for a request that is no upgrade, 400 without the
// subprotocol foxglove.websocket.v1, 403 for a Host the server does not answer (DNS rebinding),
// 503 past max_clients — and a good one with 101 selecting the subprotocol, then Server Info and
// an Advertise. (The frames themselves are Beast's; the ecosystem tier speaks to the server with
// the protocol's own client.)
#include "foxglove_server.h"

#include <poll.h>
#include <unistd.h>

#include <chrono>
#include <mutex>
#include <thread>

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>

namespace hubrt::hubctl::foxglove {
namespace {

// Loopback answers in microseconds; generous for sanitizer builds on a loaded machine.
constexpr int kPatienceMs = 10'000;

class Client {
 public:
  explicit Client(std::uint16_t port) : fd_(::socket(AF_INET, SOCK_STREAM, 0)) {
    sockaddr_in address{};
    address.sin_family = AF_INET;
    address.sin_port = htons(port);
    address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    connected_ = ::connect(fd_, reinterpret_cast<const sockaddr*>(&address), sizeof address) == 0;
  }
  ~Client() { ::close(fd_); }
  Client(const Client&) = delete;
  Client& operator=(const Client&) = delete;

  // Sends `request`, then reads until `until` is in what came back, the server closes, or patience
  // runs out. Returns all that came back.
  std::string exchange(const std::string& request, const std::string& until) {
    EXPECT_TRUE(connected_);
    EXPECT_EQ(::send(fd_, request.data(), request.size(), MSG_NOSIGNAL),
              static_cast<ssize_t>(request.size()));
    return read_until(until);
  }

  std::string read_until(const std::string& until) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(kPatienceMs);
    while (received_.find(until) == std::string::npos && std::chrono::steady_clock::now() < deadline) {
      pollfd p{fd_, POLLIN, 0};
      if (::poll(&p, 1, 100) <= 0) continue;
      char buffer[4096];
      const ssize_t n = ::recv(fd_, buffer, sizeof buffer, 0);
      if (n <= 0) break;
      received_.append(buffer, static_cast<std::size_t>(n));
    }
    return received_;
  }

 private:
  int fd_;
  bool connected_ = false;
  std::string received_;
};

std::string upgrade(std::uint16_t port, const std::string& protocols, const std::string& host = {}) {
  std::string request =
      "GET / HTTP/1.1\r\nHost: " + (host.empty() ? "127.0.0.1:" + std::to_string(port) : host) +
      "\r\nUpgrade: websocket\r\nConnection: Upgrade\r\n"
      "Sec-WebSocket-Key: dGhlIHNhbXBsZSBub25jZQ==\r\nSec-WebSocket-Version: 13\r\n";
  if (!protocols.empty()) request += "Sec-WebSocket-Protocol: " + protocols + "\r\n";
  return request + "\r\n";
}

class ServerTest : public ::testing::Test {
 protected:
  void start(BridgeOptions options = {}) {
    bridge_.emplace(options, nullptr, [this](std::string_view line) {
      const std::lock_guard lock(mutex_);
      log_.emplace_back(line);
    });
    ServerOptions server_options;
    server_options.port = 0;
    auto server = WebSocketServer::start(server_options, *bridge_, [this](std::string_view line) {
      const std::lock_guard lock(mutex_);
      log_.emplace_back(line);
    });
    ASSERT_TRUE(server) << server.error().message;
    server_ = std::move(*server);
    port_ = server_->port();
    ASSERT_NE(port_, 0);
  }
  void TearDown() override { server_.reset(); }

  std::optional<Bridge> bridge_;  // before the server: it outlives it
  std::unique_ptr<WebSocketServer> server_;
  std::uint16_t port_ = 0;
  std::mutex mutex_;
  std::vector<std::string> log_;
};

TEST_F(ServerTest, RefusesWhatIsNoFoxgloveHandshake) {
  start();
  Client plain(port_);
  const std::string page = plain.exchange(
      "GET / HTTP/1.1\r\nHost: 127.0.0.1:" + std::to_string(port_) + "\r\n\r\n", "Foxglove WebSocket");
  EXPECT_TRUE(page.starts_with("HTTP/1.1 426")) << page;

  Client other_protocol(port_);
  const std::string bad = other_protocol.exchange(upgrade(port_, "json"), "foxglove.websocket.v1\n");
  EXPECT_TRUE(bad.starts_with("HTTP/1.1 400")) << bad;

  Client rebinding(port_);
  const std::string evil =
      rebinding.exchange(upgrade(port_, "foxglove.websocket.v1", "evil.example:8765"), "unknown Host");
  EXPECT_TRUE(evil.starts_with("HTTP/1.1 403")) << evil;
  EXPECT_EQ(bridge_->counters().connections, 0U);
}

TEST_F(ServerTest, SelectsTheSubprotocolThenSendsServerInfoAndAdvertise) {
  start();
  Client client(port_);
  const std::string reply =
      client.exchange(upgrade(port_, "json, foxglove.websocket.v1"), R"("op":"advertise")");
  EXPECT_TRUE(reply.starts_with("HTTP/1.1 101")) << reply;
  EXPECT_NE(reply.find("Sec-WebSocket-Protocol: foxglove.websocket.v1\r\n"), std::string::npos) << reply;
  const auto info = reply.find(R"({"op":"serverInfo")");
  const auto advertise = reply.find(R"({"op":"advertise","channels":[]})");
  ASSERT_NE(info, std::string::npos) << reply;
  ASSERT_NE(advertise, std::string::npos) << reply;
  EXPECT_LT(info, advertise);
  EXPECT_EQ(bridge_->counters().clients, 1U);
}

TEST_F(ServerTest, PlacesAreBoundedAndFreedWhenAClientGoes) {
  BridgeOptions options;
  options.max_clients = 1;
  start(options);
  const auto connected = [this] { return bridge_->counters().clients; };
  {
    Client first(port_);
    EXPECT_TRUE(
        first.exchange(upgrade(port_, "foxglove.websocket.v1"), "serverInfo").starts_with("HTTP/1.1 101"));
    Client second(port_);
    const std::string refused = second.exchange(upgrade(port_, "foxglove.websocket.v1"), "try again later");
    EXPECT_TRUE(refused.starts_with("HTTP/1.1 503")) << refused;
    EXPECT_EQ(connected(), 1U);
  }
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::milliseconds(kPatienceMs);
  while (connected() != 0 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  EXPECT_EQ(connected(), 0U);
  Client third(port_);
  EXPECT_TRUE(
      third.exchange(upgrade(port_, "foxglove.websocket.v1"), "serverInfo").starts_with("HTTP/1.1 101"));
  EXPECT_EQ(bridge_->counters().refused_clients, 1U);
}

}  // namespace
}  // namespace hubrt::hubctl::foxglove
