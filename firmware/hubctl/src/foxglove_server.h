// The WebSocket side of `hubctl foxglove`, on Boost.Beast (Debian's libboost-dev; Beast and Asio
// are header-only and heavy to compile, so they stay in foxglove_server.cc alone). One I/O thread
// accepts clients, checks each handshake (a Host this server answers, the subprotocol
// "foxglove.websocket.v1", a place among max_clients), reads what clients send into their sessions
// and writes each session's frames, one at a time per client: a client that does not read only
// stops its own writes (foxglove_session.h holds and drops its frames).
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "hubrt/base/status.h"

#include "foxglove_bridge.h"

namespace hubrt::hubctl::foxglove {

struct ServerOptions {
  std::string address = "127.0.0.1";
  std::uint16_t port = 8765;  // 0: a free one (port() says which)
  // Connections still in their HTTP handshake, each for at most 10 s: beyond, new ones are closed
  // at once (a client cannot hold more sockets than this while not being a client).
  std::size_t max_handshakes = 64;
  // SO_SNDBUF of each client's socket (Linux doubles it). Fixed rather than autotuned (up to
  // tcp_wmem's 4 MiB, 1.3 MiB seen on loopback): what a client that stops reading holds in the
  // kernel stays small, and its backlog shows in its session's queue, where it is bounded, dropped
  // and reported. 256 KiB in flight is 2.5 MB/s at 100 ms of round trip, far above the station's
  // traffic.
  int socket_send_buffer = 128 * 1024;
};

class WebSocketServer {
 public:
  // Listens and starts the I/O thread. `bridge` must outlive the server. Errors: kUnavailable
  // naming the address and the system's reason (in use, no such address, permission).
  static Expected<std::unique_ptr<WebSocketServer>> start(const ServerOptions& options, Bridge& bridge,
                                                          LogFn log);
  // Closes every connection and the listener, then joins the I/O thread.
  ~WebSocketServer();
  WebSocketServer(const WebSocketServer&) = delete;
  WebSocketServer& operator=(const WebSocketServer&) = delete;

  [[nodiscard]] std::uint16_t port() const noexcept;

  struct Impl;  // foxglove_server.cc's (its connections use it)

 private:
  explicit WebSocketServer(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace hubrt::hubctl::foxglove
