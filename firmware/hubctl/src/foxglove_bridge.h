// The middle of `hubctl foxglove`: the tap's topics as Foxglove channels, handed to every client
// session; the clients' connections (foxglove_server.h) come and go through it. No WebSocket, no
// DDS here: the tap's events come in (dispatch), the connections are woken through ClientLink.
//
// Threads: one dispatcher (the command's main loop) calls dispatch() and tick(); the WebSocket
// side calls reserve/connect/disconnect from its I/O thread. A sample reaches each subscribed
// client's queue in one push that never waits on the client (foxglove_session.h); the dispatcher
// itself reads a bounded TapQueue, so even a stuck dispatcher never holds the tap (tap.h).
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"

#include "foxglove_protocol.h"
#include "foxglove_session.h"
#include "tap.h"

namespace hubrt::hubctl::foxglove {

// The connection of one client, as the bridge sees it.
class ClientLink {
 public:
  virtual ~ClientLink() = default;
  // Frames wait in the session: send them. Called from any thread; must not block.
  virtual void wake() noexcept = 0;
  // The client must go (its JSON backlog passed its bound, hubctl stops). Any thread; no blocking.
  virtual void close() noexcept = 0;
};

struct BridgeOptions {
  SessionLimits limits;
  std::size_t max_clients = 32;
  bool allow_publish = false;
  // Origins (the browser's Origin header) whose pages may publish; a client that sends no Origin
  // (not a web page) may. Empty: web pages may not publish.
  std::vector<std::string> publish_origins;
  std::string server_name = "hubrt hubctl foxglove";
  std::map<std::string, std::string> metadata;  // serverInfo's
  std::string session_id;
};

struct BridgeCounters {
  std::size_t clients = 0;
  std::size_t channels = 0;           // advertised now
  std::uint64_t connections = 0;      // ever
  std::uint64_t refused_clients = 0;  // turned away: too many
};

class Bridge {
 public:
  // `sink` (may be null when !options.allow_publish) must outlive the bridge. `log` gets hubctl's
  // own lines (connections, drops, refusals); it is called from both threads.
  Bridge(BridgeOptions options, CommandSink* sink, LogFn log);

  // ---- The WebSocket side (one I/O thread).
  // Holds a place for a client about to be upgraded; false when max_clients are connected or
  // held (the server then answers HTTP 503). A held place is taken by connect() or given back
  // with release().
  bool reserve();
  void release();
  // The client completed the handshake on a held place: its session, which has "Server Info" and
  // an "Advertise" of every channel queued. `origin` is its Origin header ("" when none).
  std::shared_ptr<ClientSession> connect(const std::string& peer, const std::string& origin,
                                         std::shared_ptr<ClientLink> link);
  // Its connection ended. Logs its totals.
  void disconnect(std::uint32_t client_id);

  // ---- The dispatcher.
  // A tap event: a topic appeared (advertised to every client), went away (unadvertised), a
  // sample (to every client subscribed to its channel).
  void dispatch(const TapEvent& event);
  // About once a second: drop reports, and clients beyond help closed.
  void tick(Time now);

  [[nodiscard]] BridgeCounters counters() const;

 private:
  struct Client {
    std::shared_ptr<ClientSession> session;
    std::shared_ptr<ClientLink> link;
  };
  struct ChannelEntry {
    Channel channel;
    std::shared_ptr<const std::string> advertise;
    bool live = false;
  };
  PublishPermission permission_for(const std::string& origin) const;

  const BridgeOptions options_;
  CommandSink* const sink_;
  const LogFn log_;

  mutable std::mutex mutex_;
  std::map<std::uint32_t, ChannelEntry> channels_;  // by channel id = tap topic id
  std::map<std::uint32_t, Client> clients_;
  std::size_t reserved_ = 0;
  std::uint32_t next_client_ = 1;
  BridgeCounters counters_;
};

}  // namespace hubrt::hubctl::foxglove
