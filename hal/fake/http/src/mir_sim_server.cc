#include "hubrt/hal/fake/mir_sim_server.h"

#include <httplib.h>

#include <fmt/format.h>

namespace hubrt::hal::fake {

Result<MirServerFault> parse_mir_fault(std::string_view name) noexcept {
  if (name == "answer") return MirServerFault::kNone;
  if (name == "server_error") return MirServerFault::kServerError;
  if (name == "unauthorized") return MirServerFault::kUnauthorized;
  if (name == "slow") return MirServerFault::kSlow;
  if (name == "stop_answering") return MirServerFault::kNoAnswer;
  if (name == "malformed_json") return MirServerFault::kMalformedJson;
  return Status(ErrorCode::kNotFound);
}

MirSimServer::MirSimServer(MirPlatform& platform, const Clock& clock, MirSimServerOptions options)
    : platform_(platform), clock_(clock), options_(std::move(options)), port_(options_.port) {}

Expected<std::unique_ptr<MirSimServer>> MirSimServer::start(MirPlatform& platform, const Clock& clock,
                                                            MirSimServerOptions options) {
  if (!options.address.starts_with("127.")) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("MiR simulator: '{}' is not a loopback address", options.address));
  }
  std::unique_ptr<MirSimServer> server(new MirSimServer(platform, clock, std::move(options)));
  const std::lock_guard lock(server->lifecycle_mutex_);
  if (auto ok = server->listen(); !ok) return std::move(ok).error();
  return server;
}

MirSimServer::~MirSimServer() {
  stopping_.store(true);
  const std::lock_guard lock(lifecycle_mutex_);
  stop_locked();
}

void MirSimServer::install_handlers(httplib::Server& server) {
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

Expected<void> MirSimServer::listen() {
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

void MirSimServer::stop_locked() {
  if (server_ == nullptr) return;
  server_->stop();
  if (thread_.joinable()) thread_.join();
  server_.reset();
}

void MirSimServer::go_down() {
  const std::lock_guard lock(lifecycle_mutex_);
  stopping_.store(true);  // ends requests held by kNoAnswer or kSlow, so that stop() can join them
  stop_locked();
  stopping_.store(false);
}

Expected<void> MirSimServer::come_back() {
  const std::lock_guard lock(lifecycle_mutex_);
  if (server_ != nullptr) return {};
  return listen();
}

bool MirSimServer::is_up() const {
  const std::lock_guard lock(lifecycle_mutex_);
  return server_ != nullptr;
}

}  // namespace hubrt::hal::fake
