// The simulated MiR100 as a real HTTP server on loopback (cpp-httplib), serving a MirPlatform
// under /api/v2.0.0 from its own thread, so that the real HTTP client backend is tested for real.
// Faults a REST device shows: server errors, refused authorization, slow or missing answers, a
// refused connection, malformed JSON.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/hal/fake/mir_platform.h"

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

// Thread-safe. The platform and clock must outlive it. An interface: the server runs on
// cpp-httplib, which lives in the module hubrt-mir-sim.so (load_mir_sim_server), so that a
// simulated hub without a MiR never maps it.
class MirSimServer {
 public:
  virtual ~MirSimServer() = default;

  [[nodiscard]] virtual std::uint16_t port() const noexcept = 0;
  virtual void set_fault(MirServerFault fault) noexcept = 0;
  [[nodiscard]] virtual MirServerFault fault() const noexcept = 0;
  // Fault: the server goes away (connections refused) / comes back on the same port.
  virtual void go_down() = 0;
  virtual Expected<void> come_back() = 0;
  [[nodiscard]] virtual bool is_up() const = 0;
  [[nodiscard]] virtual std::uint64_t requests() const noexcept = 0;
};

// Starts a server in this process (hubrt_hal_fake_http_server, which links cpp-httplib: the module
// and the simulator's own tests). Errors: kInvalidArgument (not a loopback IPv4 address), kBusy
// (the port is taken).
Expected<std::unique_ptr<MirSimServer>> start_mir_sim_server(MirPlatform& platform, const Clock& clock,
                                                             MirSimServerOptions options = {});

// <program>/../lib/hubrt/hubrt-mir-sim.so, then (native builds) the module of the build tree.
std::vector<std::string> default_mir_sim_module_paths();

// start_mir_sim_server through the first of `module_paths` that loads (hal/common/module_loader.h).
// Errors: those of load_module_symbol (kUnavailable: no module), then of start_mir_sim_server.
Expected<std::unique_ptr<MirSimServer>> load_mir_sim_server(const std::vector<std::string>& module_paths,
                                                            MirPlatform& platform, const Clock& clock,
                                                            const MirSimServerOptions& options = {});

}  // namespace hubrt::hal::fake
