// An HTTP/1.1 client talking to one REST server (e.g. a MiR100's REST API on the platform's LAN).
// Requests are fixed-size values (they are built in the cycle, which allocates nothing); the
// blocking client that sends them runs off the cycle (threaded_async_http.h), where the answer's
// body may be stored and parsed.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"

namespace hubrt::hal {

// Text of at most N bytes stored inline: never allocates.
template <std::size_t N>
class FixedText {
 public:
  static constexpr std::size_t kCapacity = N;
  // False (and the text left empty) when `text` does not fit.
  bool assign(std::string_view text) noexcept {
    if (text.size() > N) {
      length_ = 0;
      return false;
    }
    text.copy(data_.data(), text.size());
    length_ = text.size();
    return true;
  }
  // Copies what fits of `text` (a message: cutting is better than nothing).
  void assign_cut(std::string_view text) noexcept { assign(text.substr(0, N)); }
  [[nodiscard]] std::string_view view() const noexcept { return {data_.data(), length_}; }
  [[nodiscard]] bool empty() const noexcept { return length_ == 0; }
  [[nodiscard]] char* data() noexcept { return data_.data(); }
  // For formatting into data(): `length` is clamped to the capacity.
  void set_length(std::size_t length) noexcept { length_ = length < N ? length : N; }
  void clear() noexcept { length_ = 0; }

 private:
  std::array<char, N> data_{};
  std::size_t length_ = 0;
};

inline constexpr std::size_t kMaxHttpPath = 160;         // after the base path, with the query
inline constexpr std::size_t kMaxHttpRequestBody = 512;  // JSON bodies of the requests we send
inline constexpr std::size_t kMaxHttpKey = 64;

enum class HttpMethod : std::uint8_t { kGet, kPut, kPost, kDelete };

// "GET", "PUT", "POST", "DELETE".
[[nodiscard]] constexpr std::string_view to_string(HttpMethod method) noexcept {
  switch (method) {
    case HttpMethod::kGet:
      return "GET";
    case HttpMethod::kPut:
      return "PUT";
    case HttpMethod::kPost:
      return "POST";
    case HttpMethod::kDelete:
      return "DELETE";
  }
  return "?";
}

struct HttpRequest {
  HttpMethod method = HttpMethod::kGet;
  FixedText<kMaxHttpPath> path;         // e.g. "/status" (the device's base path is put before it)
  FixedText<kMaxHttpRequestBody> body;  // JSON; empty: none
  // Not sent: for whoever decodes the answer (what was asked, e.g. the position name looked for).
  std::uint32_t tag = 0;
  FixedText<kMaxHttpKey> key;
};

struct HttpResponse {
  int status = 0;    // the HTTP status code (200, 401, 500, ...)
  std::string body;  // at most HttpConfig::max_response_bytes
};

struct HttpConfig {
  std::string device;  // logical name used in messages, e.g. "mir"
  std::string host = "127.0.0.1";
  std::uint16_t port = 80;
  std::string base_path;      // put before every request's path, e.g. "/api/v2.0.0"
  std::string authorization;  // the Authorization header's value, e.g. "Basic ..."; empty: none
  Duration connect_timeout = std::chrono::milliseconds(500);
  Duration read_timeout = std::chrono::milliseconds(1000);  // for each read and write on the socket
  std::size_t max_response_bytes = std::size_t{64} * 1024;
};

// One request at a time; every call is bounded by the connect timeout plus the read timeout for
// each read of the answer. An HTTP status (401, 500) is an answer, not a failure of send().
// Errors: kUnavailable (cannot connect: refused, unreachable), kTimeout (connect or an answer
// timed out), kOutOfRange (answer over max_response_bytes, the connection is dropped), kIo (any other
// transfer failure). Not thread-safe: one owner.
class HttpClient {
 public:
  virtual ~HttpClient() = default;
  HttpClient(const HttpClient&) = delete;
  HttpClient& operator=(const HttpClient&) = delete;

  virtual Status send(const HttpRequest& request, HttpResponse& out) noexcept = 0;
  // What the last failed send() saw, e.g. "connection refused (127.0.0.1:8080)".
  [[nodiscard]] virtual std::string_view last_error() const noexcept = 0;

 protected:
  HttpClient() = default;
};

// "mir (http://192.168.12.20:80/api/v2.0.0)".
[[nodiscard]] inline std::string describe_http(const HttpConfig& config) {
  return config.device + " (http://" + config.host + ":" + std::to_string(config.port) + config.base_path +
         ")";
}

}  // namespace hubrt::hal
