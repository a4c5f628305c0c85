// AsyncHttp on a worker thread of its own around any blocking HttpClient (cpp-httplib on Linux,
// the same client against the fake backend's simulator server), with the caller's decoder run on
// that thread too: the cycle only copies a fixed-size Reply. A template (the Reply is the
// protocol's), so it lives in this header.
#pragma once

#include <condition_variable>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <system_error>
#include <thread>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/hal/async_http.h"
#include "hubrt/hal/http_client.h"

namespace hubrt::hal {

// Turns an answer into the caller's Reply, on the worker thread (it may allocate, parse and
// fail: it must not throw). `response.status` is the HTTP status; `reply` starts default.
template <class Reply>
using HttpDecoder =
    std::function<void(const HttpRequest& request, const HttpResponse& response, Reply& reply)>;

// A request timeout that covers one request on `config`: the connect timeout plus two read
// timeouts (sending the request and waiting for the answer are each bounded by it).
[[nodiscard]] inline Duration http_request_timeout(const HttpConfig& config) noexcept {
  return config.connect_timeout + 2 * config.read_timeout;
}

namespace detail {

template <class Reply>
class ThreadedAsyncHttp final : public AsyncHttp<Reply> {
 public:
  ThreadedAsyncHttp(std::unique_ptr<HttpClient> client, HttpDecoder<Reply> decode, Duration request_timeout,
                    std::string description)
      : client_(std::move(client)),
        decode_(std::move(decode)),
        request_timeout_(request_timeout),
        description_(std::move(description)) {}

  void start() {
    thread_ = std::thread([this] { run(); });
  }

  ~ThreadedAsyncHttp() override {
    {
      const std::lock_guard lock(mutex_);
      stopping_ = true;
    }
    wake_.notify_one();
    if (thread_.joinable()) thread_.join();
  }
  ThreadedAsyncHttp(const ThreadedAsyncHttp&) = delete;
  ThreadedAsyncHttp& operator=(const ThreadedAsyncHttp&) = delete;

  Result<std::uint64_t> submit(const HttpRequest& request, Time now) noexcept override {
    if (request.path.empty()) return Status(ErrorCode::kInvalidArgument);
    const std::uint64_t id = ++last_id_;
    {
      const std::lock_guard lock(mutex_);
      waiting_ = request;  // replaces one that has not started
      waiting_id_ = id;
      has_waiting_ = true;
    }
    wake_.notify_one();
    latest_ = id;
    latest_submitted_at_ = now;
    latest_reported_ = false;
    return id;
  }

  bool poll(Time now, HttpCompletion<Reply>& out) noexcept override {
    if (latest_reported_) return false;
    bool finished = false;
    {
      const std::lock_guard lock(mutex_);
      if (finished_id_ == latest_) {
        finished = true;
        out.transport = finished_.transport;
        out.http_status = finished_.http_status;
        out.reply = finished_.reply;
        out.transport_error = finished_.transport_error;
      } else if (now - latest_submitted_at_ > request_timeout_) {
        if (has_waiting_ && waiting_id_ == latest_) has_waiting_ = false;  // withdrawn
      } else {
        return false;
      }
    }
    if (!finished) {
      out.transport = Status(ErrorCode::kTimeout);
      out.http_status = 0;
      out.reply = Reply{};
      out.transport_error.assign_cut("no answer within the request timeout");
    }
    out.timed_out = !finished;
    out.id = latest_;
    out.submitted_at = latest_submitted_at_;
    out.completed_at = now;
    latest_reported_ = true;
    return true;
  }

  void set_request_on_close(const HttpRequest& request) noexcept override {
    const std::lock_guard lock(mutex_);
    on_close_ = request;
    has_on_close_ = true;
  }

  [[nodiscard]] std::string_view description() const noexcept override { return description_; }

 private:
  struct Finished {
    Status transport;
    int http_status = 0;
    Reply reply{};
    FixedText<120> transport_error;
  };

  void run() noexcept {
    std::unique_lock lock(mutex_);
    for (;;) {
      wake_.wait(lock, [this] { return stopping_ || has_waiting_; });
      if (stopping_) break;
      const HttpRequest request = waiting_;
      const std::uint64_t id = waiting_id_;
      has_waiting_ = false;
      lock.unlock();
      const Finished done = execute(request);
      lock.lock();
      finished_ = done;
      finished_id_ = id;
    }
    const bool send_on_close = has_on_close_;
    const HttpRequest last = on_close_;
    lock.unlock();
    // Best effort on the way out: bounded by the client's timeouts, nobody to tell.
    if (send_on_close) execute(last);
  }

  Finished execute(const HttpRequest& request) noexcept {
    Finished done;
    done.transport = client_->send(request, response_);
    if (!done.transport.is_ok()) {
      done.transport_error.assign_cut(client_->last_error());
      return done;
    }
    done.http_status = response_.status;
    try {
      decode_(request, response_, done.reply);
    } catch (...) {  // a decoder must not throw; if one does, the answer is not understood
      done.reply = Reply{};
      done.transport = Status(ErrorCode::kProtocol);
      done.transport_error.assign_cut("the answer's decoder failed");
    }
    return done;
  }

  std::unique_ptr<HttpClient> client_;  // the worker thread's only
  HttpDecoder<Reply> decode_;           // the worker thread's only
  HttpResponse response_;               // the worker thread's only (its body's storage is reused)
  const Duration request_timeout_;
  const std::string description_;

  std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false;          // guarded by mutex_
  HttpRequest waiting_;            // guarded by mutex_
  std::uint64_t waiting_id_ = 0;   // guarded by mutex_
  bool has_waiting_ = false;       // guarded by mutex_
  Finished finished_;              // guarded by mutex_
  std::uint64_t finished_id_ = 0;  // guarded by mutex_
  HttpRequest on_close_;           // guarded by mutex_
  bool has_on_close_ = false;      // guarded by mutex_

  // The owner's (submit/poll) only.
  std::uint64_t last_id_ = 0;
  std::uint64_t latest_ = 0;
  Time latest_submitted_at_{};
  bool latest_reported_ = true;

  std::thread thread_;
};

}  // namespace detail

// Starts a worker thread that owns `client` and runs the submitted requests on it, decoding each
// answer with `decode` there (see AsyncHttp for the rules). `request_timeout`: the deadline after
// submit() at which poll() reports a request as timed out. `description` names the device.
// Errors (the message names the device): kInvalidArgument (no client or decoder, request_timeout
// not positive), kUnavailable (the thread could not be started).
template <class Reply>
Expected<std::unique_ptr<AsyncHttp<Reply>>> open_threaded_async_http(std::unique_ptr<HttpClient> client,
                                                                     HttpDecoder<Reply> decode,
                                                                     Duration request_timeout,
                                                                     std::string description) {
  if (client == nullptr || !decode) {
    return make_error(ErrorCode::kInvalidArgument, description + ": no HTTP client or decoder to run");
  }
  if (request_timeout <= Duration::zero()) {
    return make_error(ErrorCode::kInvalidArgument, description + ": request timeout must be positive");
  }
  auto device = std::make_unique<detail::ThreadedAsyncHttp<Reply>>(std::move(client), std::move(decode),
                                                                   request_timeout, description);
  try {
    device->start();
  } catch (const std::system_error& error) {
    return make_error(ErrorCode::kUnavailable,
                      description + ": cannot start its HTTP worker thread: " + error.what());
  }
  return std::unique_ptr<AsyncHttp<Reply>>(std::move(device));
}

}  // namespace hubrt::hal
