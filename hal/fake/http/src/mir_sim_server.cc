// The MiR simulator's REST server on cpp-httplib (start_mir_sim_server), built into the module
// hubrt-mir-sim.so and the simulator's tests.
#include "hubrt/hal/fake/mir_sim_server.h"

#include <httplib.h>

#include <atomic>
#include <mutex>
#include <thread>

#include <fmt/format.h>

namespace hubrt::hal::fake {
namespace {

class HttplibMirSimServer final : public MirSimServer {
 public:
  HttplibMirSimServer(MirPlatform& platform, const Clock& clock, MirSimServerOptions options)
      : platform_(platform), clock_(clock), options_(std::move(options)), port_(options_.port) {}
  ~HttplibMirSimServer() override {
    stopping_.store(true);
    const std::lock_guard lock(lifecycle_mutex_);
    stop_locked();
  }
  HttplibMirSimServer(const HttplibMirSimServer&) = delete;
  HttplibMirSimServer& operator=(const HttplibMirSimServer&) = delete;

  // Precondition: lifecycle_mutex_ is not held.
  Expected<void> start() {
    const std::lock_guard lock(lifecycle_mutex_);
    return listen();
  }

  [[nodiscard]] std::uint16_t port() const noexcept override { return port_; }
  void set_fault(MirServerFault fault) noexcept override { fault_.store(fault); }
  [[nodiscard]] MirServerFault fault() const noexcept override { return fault_.load(); }
  void go_down() override;
  Expected<void> come_back() override;
  [[nodiscard]] bool is_up() const override;
  [[nodiscard]] std::uint64_t requests() const noexcept override { return requests_.load(); }

 private:
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

void HttplibMirSimServer::install_handlers(httplib::Server& server) {
  const auto serve = [this](std::string_view method) {
    return [this, method](const httplib::Request& req, httplib::Response& res) {
      requests_.fetch_add(1);
      const MirServerFault fault = fault_.load();
      if (fault == MirServerFault::kNoAnswer) {
        // Hold the request unanswered until the fault is cleared or the server stops (the
        // client's read timeout ends it first); then answer "unavailable".
        while (fault_.load() == MirServerFault::kNoAnswer && !stopping_.load()) {
          std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
        res.status = 503;
        return;
      }
      if (fault == MirServerFault::kSlow) {
        const auto until = std::chrono::steady_clock::now() + options_.slow_delay;
        while (std::chrono::steady_clock::now() < until && !stopping_.load()) {
          std::this_thread::sleep_for(std::chrono::milliseconds(10));
        }
      }
      if (fault == MirServerFault::kServerError) {
        res.status = 500;
        res.set_content(R"({"error_code":"500","error_human":"Internal server error"})", "application/json");
        return;
      }
      if (fault == MirServerFault::kUnauthorized) {
        res.status = 401;
        res.set_content(R"({"error_code":"401","error_human":"Unauthorized"})", "application/json");
        return;
      }
      const std::string path = req.path.substr(options_.base_path.size());
      const MirAnswer answer =
          platform_.handle(method, path, req.body, req.get_header_value("Authorization"), clock_.now().mono);
      res.status = answer.status;
      std::string body = answer.body;
      if (fault == MirServerFault::kMalformedJson) body = body.substr(0, body.size() / 2);
      if (!body.empty()) res.set_content(body, "application/json");
    };
  };
  const std::string pattern = options_.base_path + "/.*";
  server.Get(pattern, serve("GET"));
  server.Put(pattern, serve("PUT"));
  server.Post(pattern, serve("POST"));
  server.Delete(pattern, serve("DELETE"));
}

Expected<void> HttplibMirSimServer::listen() {
  auto server = std::make_unique<httplib::Server>();
  install_handlers(*server);
  if (port_ == 0) {
    const int port = server->bind_to_any_port(options_.address);
    if (port <= 0) {
      return make_error(ErrorCode::kBusy,
                        fmt::format("MiR simulator: cannot listen on {}", options_.address));
    }
    port_ = static_cast<std::uint16_t>(port);
  } else if (!server->bind_to_port(options_.address, port_)) {
    return make_error(ErrorCode::kBusy,
                      fmt::format("MiR simulator: cannot listen on {}:{}", options_.address, port_));
  }
  httplib::Server* raw = server.get();
  server_ = std::move(server);
  thread_ = std::thread([raw] { raw->listen_after_bind(); });
  // httplib::Server::stop() does nothing before the thread has entered its accept loop
  // (is_running()), so a stop right after the start would leave it listening forever: wait.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (!raw->is_running() && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  return {};
}

void HttplibMirSimServer::stop_locked() {
  if (server_ == nullptr) return;
  server_->stop();
  if (thread_.joinable()) thread_.join();
  server_.reset();
}

void HttplibMirSimServer::go_down() {
  const std::lock_guard lock(lifecycle_mutex_);
  stopping_.store(true);  // ends requests held by kNoAnswer or kSlow, so that stop() can join them
  stop_locked();
  stopping_.store(false);
}

Expected<void> HttplibMirSimServer::come_back() {
  const std::lock_guard lock(lifecycle_mutex_);
  if (server_ != nullptr) return {};
  return listen();
}

bool HttplibMirSimServer::is_up() const {
  const std::lock_guard lock(lifecycle_mutex_);
  return server_ != nullptr;
}

}  // namespace

Expected<std::unique_ptr<MirSimServer>> start_mir_sim_server(MirPlatform& platform, const Clock& clock,
                                                             MirSimServerOptions options) {
  if (!options.address.starts_with("127.")) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("MiR simulator: '{}' is not a loopback address", options.address));
  }
  auto server = std::make_unique<HttplibMirSimServer>(platform, clock, std::move(options));
  if (auto ok = server->start(); !ok) return std::move(ok).error();
  return std::unique_ptr<MirSimServer>(std::move(server));
}

}  // namespace hubrt::hal::fake
