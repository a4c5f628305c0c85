// The simulated MiR100 as a real HTTP server on loopback (cpp-httplib), serving a MirPlatform
// under /api/v2.0.0 from its own thread, so that the real HTTP client backend is tested for real.
// Faults a REST device shows: server errors, refused authorization, slow or missing answers, a
// refused connection, malformed JSON.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <thread>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/hal/fake/mir_platform.h"

namespace httplib {
class Server;
}

namespace hubrt::hal::fake {

enum class MirServerFault : std::uint8_t {
  kNone,
  kServerError,    // every request: HTTP 500
  kUnauthorized,   // every request: HTTP 401, whatever the header
  kSlow,           // every answer goes out after slow_delay (longer than a client's read timeout)
  kNoAnswer,       // requests are read, never answered (until the fault is cleared or the server stops)
  kMalformedJson,  // 200 with a body cut in the middle of its JSON
};

// "server_error" ... as /sim/fault names them; kNotFound for another name (fault none: "answer").
[[nodiscard]] Result<MirServerFault> parse_mir_fault(std::string_view name) noexcept;

struct MirSimServerOptions {
  std::string address = "127.0.0.1";
  std::uint16_t port = 0;  // 0: a free port (see port())
  std::string base_path = "/api/v2.0.0";
  Duration slow_delay = std::chrono::seconds(3);
};

// Thread-safe. The platform and clock must outlive it.
class MirSimServer {
 public:
  // Errors: kInvalidArgument (not a loopback IPv4 address), kBusy (the port is taken).
  static Expected<std::unique_ptr<MirSimServer>> start(MirPlatform& platform, const Clock& clock,
                                                       MirSimServerOptions options = {});
  ~MirSimServer();
  MirSimServer(const MirSimServer&) = delete;
  MirSimServer& operator=(const MirSimServer&) = delete;

  [[nodiscard]] std::uint16_t port() const noexcept { return port_; }
  void set_fault(MirServerFault fault) noexcept { fault_.store(fault); }
  [[nodiscard]] MirServerFault fault() const noexcept { return fault_.load(); }
  // Fault: the server goes away (connections refused) / comes back on the same port.
  void go_down();
  Expected<void> come_back();
  [[nodiscard]] bool is_up() const;
  [[nodiscard]] std::uint64_t requests() const noexcept { return requests_.load(); }

 private:
  MirSimServer(MirPlatform& platform, const Clock& clock, MirSimServerOptions options);
  Expected<void> listen();  // with lifecycle_mutex_ held
  void stop_locked();
  void install_handlers(httplib::Server& server);

  MirPlatform& platform_;
  const Clock& clock_;
  const MirSimServerOptions options_;
  std::uint16_t port_ = 0;
  std::atomic<MirServerFault> fault_{MirServerFault::kNone};
  std::atomic<bool> stopping_{false};
  std::atomic<std::uint64_t> requests_{0};
  mutable std::mutex lifecycle_mutex_;
  std::unique_ptr<httplib::Server> server_;  // guarded by lifecycle_mutex_
  std::thread thread_;                       // guarded by lifecycle_mutex_
};

}  // namespace hubrt::hal::fake
