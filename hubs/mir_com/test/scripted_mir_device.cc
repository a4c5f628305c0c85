#include "scripted_mir_device.h"

#include "hubrt/protocol/mir_rest.h"

namespace hubrt::mir_com::test {

Result<std::uint64_t> ScriptedMirDevice::submit(const hal::HttpRequest& request, Time now) noexcept {
  if (request.path.empty()) return Status(ErrorCode::kInvalidArgument);
  request_ = request;
  submitted_at_ = now;
  pending_ = true;
  return ++id_;
}

bool ScriptedMirDevice::poll(Time now, MirCompletion& out) noexcept {
  if (!pending_) return false;
  out = MirCompletion{};
  out.id = id_;
  out.submitted_at = submitted_at_;
  out.completed_at = now;
  if (fault_ == DeviceFault::kNoAnswer) {
    if (now - submitted_at_ <= request_timeout_) return false;
    pending_ = false;
    out.timed_out = true;
    out.transport = Status(ErrorCode::kTimeout);
    out.transport_error.assign("no answer within the request timeout");
    return true;
  }
  if (now - submitted_at_ < latency_) return false;
  pending_ = false;
  const std::string line = std::string(hal::to_string(request_.method)) + " " +
                           std::string(request_.path.view()) +
                           (request_.body.empty() ? "" : " " + std::string(request_.body.view()));
  if (fault_ == DeviceFault::kRefused) {
    out.transport = Status(ErrorCode::kUnavailable);
    out.transport_error.assign("cannot connect (refused or unreachable)");
    return true;
  }
  sent_.push_back(line);
  hal::HttpResponse response;
  if (fault_ == DeviceFault::kServerError) {
    response.status = 500;
  } else if (fault_ == DeviceFault::kUnauthorized) {
    response.status = 401;
  } else {
    const hal::fake::MirAnswer answer = platform_.handle(
        hal::to_string(request_.method), request_.path.view(), request_.body.view(), "", submitted_at_);
    response.status = answer.status;
    response.body = answer.body;
    if (fault_ == DeviceFault::kMalformedJson) response.body.resize(response.body.size() / 2);
  }
  out.http_status = response.status;
  protocol::mir::decode_reply(request_, response, out.reply);
  return true;
}

}  // namespace hubrt::mir_com::test
