// HTTP without blocking the caller: node logic submits a request and polls for its completion in
// a later cycle, passing the time in each call — the pattern of AsyncModbus (async_modbus.h). The
// request is sent and its answer decoded somewhere else (a worker thread of the HAL's:
// threaded_async_http.h), so that the cycle neither waits on the network nor parses (or allocates
// for) an answer: what it polls is a fixed-size `Reply` the decoder filled in.
#pragma once

#include <cstdint>
#include <string_view>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/hal/http_client.h"

namespace hubrt::hal {

// How a request ended. Times are in the caller's time base: `submitted_at` is the `now` given to
// submit(), `completed_at` the `now` of the poll() that reported it.
template <class Reply>
struct HttpCompletion {
  std::uint64_t id = 0;  // what submit() returned
  Time submitted_at{};
  Time completed_at{};
  // The transport's outcome (HttpClient::send's codes); kTimeout also when the request's deadline
  // passed (timed_out). ok means an answer arrived: see http_status and reply.
  Status transport;
  bool timed_out = false;
  int http_status = 0;             // 0 without an answer
  Reply reply{};                   // the decoder's work (left default without an answer)
  FixedText<120> transport_error;  // HttpClient::last_error() of a failed send
};

// Requests run one at a time, in the order submitted, with a queue of depth one: a later submit()
// replaces a request still waiting; poll() reports only the latest submission's completion, once.
// A request not complete by its deadline (submit's `now` plus the device's request timeout, judged
// at poll's `now`) is reported as timed out, and withdrawn if it had not started.
//
// Thread-safety: submit(), poll() and set_request_on_close() are called by one owner thread (the
// cycle's) and never block on the network (a short mutex for a copy). Destroying the device ends
// the request in progress (bounded by the client's timeouts), drops a waiting one, then sends the
// request-on-close (bounded likewise): destruction may block that long.
template <class Reply>
class AsyncHttp {
 public:
  virtual ~AsyncHttp() = default;
  AsyncHttp(const AsyncHttp&) = delete;
  AsyncHttp& operator=(const AsyncHttp&) = delete;

  // Queues `request`; returns its id (counting from 1). Errors: kInvalidArgument (an empty path).
  virtual Result<std::uint64_t> submit(const HttpRequest& request, Time now) noexcept = 0;
  // True, with `out` filled, when the latest submission completed (or its deadline passed) and was
  // not reported yet. False: nothing new.
  virtual bool poll(Time now, HttpCompletion<Reply>& out) noexcept = 0;
  // A request sent once when the device is closed (destroyed), after the one in progress — e.g.
  // "pause the platform", so it is the last word whatever the logic was doing.
  virtual void set_request_on_close(const HttpRequest& request) noexcept = 0;
  // The device as messages name it, e.g. "mir (http://192.168.12.20:80/api/v2.0.0)".
  [[nodiscard]] virtual std::string_view description() const noexcept = 0;

 protected:
  AsyncHttp() = default;
};

}  // namespace hubrt::hal
