#include <httplib.h>

#include <fmt/format.h>

#include "hubrt/hal/httplib/open_httplib.h"

namespace hubrt::hal::httplib_client {
namespace {

// cpp-httplib's timeouts are (seconds, microseconds) pairs.
std::pair<time_t, time_t> split(Duration d) {
  const auto us = std::chrono::duration_cast<std::chrono::microseconds>(d).count();
  return {static_cast<time_t>(us / 1'000'000), static_cast<time_t>(us % 1'000'000)};
}

class HttplibClient final : public HttpClient {
 public:
  explicit HttplibClient(const HttpConfig& config) : config_(config), client_(config.host, config.port) {
    const auto [connect_s, connect_us] = split(config.connect_timeout);
    const auto [read_s, read_us] = split(config.read_timeout);
    client_.set_connection_timeout(connect_s, connect_us);
    // Both bound each socket read/write (httplib::ClientImpl, select_read/select_write): an answer
    // that never comes ends the call after read_timeout with Error::Read.
    client_.set_read_timeout(read_s, read_us);
    client_.set_write_timeout(read_s, read_us);
    client_.set_keep_alive(false);
  }

  Status send(const HttpRequest& request, HttpResponse& out) noexcept override {
    try {
      return send_checked(request, out);
    } catch (const std::exception& e) {  // std::bad_alloc, or one of httplib's std::function calls
      last_error_ = fmt::format("{} {}: {}", to_string(request.method), request.path.view(), e.what());
      return Status(ErrorCode::kIo);
    }
  }

  [[nodiscard]] std::string_view last_error() const noexcept override { return last_error_; }

 private:
  Status send_checked(const HttpRequest& request, HttpResponse& out) {
    httplib::Request req;
    req.method = std::string(to_string(request.method));
    req.path = config_.base_path + std::string(request.path.view());
    req.headers.emplace("Accept", "application/json");
    // MiR's REST API: "Authorization: Basic <base64(user:sha256(password))>" on every call.
    if (!config_.authorization.empty()) req.headers.emplace("Authorization", config_.authorization);
    if (!request.body.empty()) {
      req.headers.emplace("Content-Type", "application/json");
      req.body = std::string(request.body.view());
    }
    out.body.clear();
    out.status = 0;
    bool too_long = false;
    // The answer goes through this receiver instead of res.body, so that a server sending more
    // than max_response_bytes is cut off (returning false cancels: Error::Canceled).
    req.content_receiver = [&](const char* data, std::size_t length, std::uint64_t, std::uint64_t) {
      if (out.body.size() + length > config_.max_response_bytes) {
        too_long = true;
        return false;
      }
      out.body.append(data, length);
      return true;
    };
    httplib::Response res;
    httplib::Error error = httplib::Error::Success;
    const std::string where = fmt::format("{} {} ({}:{})", req.method, req.path, config_.host, config_.port);
    if (!client_.send(req, res, error)) {
      if (too_long) {
        last_error_ = fmt::format("{}: answer longer than {} bytes", where, config_.max_response_bytes);
        return Status(ErrorCode::kOutOfRange);
      }
      last_error_ = fmt::format("{}: {}", where, describe(error));
      return Status(code_of(error));
    }
    out.status = res.status;
    return Status::ok();
  }

  static std::string_view describe(httplib::Error error) {
    switch (error) {
      case httplib::Error::Connection:
        return "cannot connect (refused or unreachable)";
      case httplib::Error::ConnectionTimeout:
        return "connect timed out";
      case httplib::Error::Read:
        return "no (complete) answer within the read timeout";
      case httplib::Error::Write:
        return "sending the request failed";
      default:
        return "transfer failed";
    }
  }

  static ErrorCode code_of(httplib::Error error) {
    switch (error) {
      case httplib::Error::Connection:
        return ErrorCode::kUnavailable;
      case httplib::Error::ConnectionTimeout:
      case httplib::Error::Read:
        return ErrorCode::kTimeout;
      default:
        return ErrorCode::kIo;
    }
  }

  HttpConfig config_;
  httplib::Client client_;
  std::string last_error_;
};

}  // namespace

Expected<std::unique_ptr<HttpClient>> open_httplib(const HttpConfig& config) {
  const auto invalid = [&](std::string_view why) {
    return make_error(ErrorCode::kInvalidArgument, fmt::format("{}: {}", describe_http(config), why));
  };
  if (config.host.empty()) return invalid("no host");
  if (config.port == 0) return invalid("port 0");
  if (config.connect_timeout <= Duration::zero() || config.read_timeout <= Duration::zero()) {
    return invalid("timeouts must be positive");
  }
  if (!config.base_path.empty() && config.base_path.front() != '/')
    return invalid("base path must start with '/'");
  if (config.authorization.find_first_of("\r\n") != std::string::npos) {
    return invalid("the authorization value contains a line break");
  }
  return std::unique_ptr<HttpClient>(std::make_unique<HttplibClient>(config));
}

}  // namespace hubrt::hal::httplib_client
