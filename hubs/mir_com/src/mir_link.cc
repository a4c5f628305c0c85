#include "mir_link.h"

#include <fmt/format.h>

namespace hubrt::mir_com {

using protocol::mir::MirCall;

bool MirLink::collect(Time now, MirCompletion& done) noexcept {
  if (!in_flight_ || !device_->poll(now, done)) return false;
  in_flight_ = false;
  const MirCall call = done.reply.call;
  if (!done.transport.is_ok()) {
    // format_to_n: no allocation; the HAL's message names the request and the address.
    const auto out = fmt::format_to_n(problem_.data(), decltype(problem_)::kCapacity, "{}: {}",
                                      to_string(done.transport.code()), done.transport_error.view());
    problem_.set_length(out.size);
    return true;
  }
  if (!done.reply.ok) {
    problem_.assign_cut(done.reply.problem.view());
    return true;
  }
  problem_.clear();
  if (call == MirCall::kGetStatus || call == MirCall::kSetState || call == MirCall::kClearError) {
    status_ = done.reply.status;
    has_status_ = true;
    // The status was read between submit and now: its age is judged from the submission.
    status_at_ = done.submitted_at;
  }
  return true;
}

bool MirLink::send(const hal::HttpRequest& request, Time now) noexcept {
  if (in_flight_) return false;
  const Result<std::uint64_t> id = device_->submit(request, now);
  if (!id.is_ok()) {
    problem_.assign_cut("a request could not be built (a name or guid that does not fit)");
    return false;
  }
  in_flight_ = true;
  if (static_cast<MirCall>(request.tag) == MirCall::kGetStatus) {
    asked_status_ = true;
    status_asked_at_ = now;
  }
  return true;
}

void MirLink::poll_status(Time now) noexcept {
  if (!in_flight_ && status_due(now)) send(protocol::mir::get_status(), now);
}

void MirLink::report(runtime::ErrorList& errors, Time now) const noexcept {
  if (!answering(now)) {
    if (has_status_) {
      errors.add("platform {} not answering: no status for {:.1f} s", device_->description(),
                 to_seconds(now - status_at_));
    } else {
      errors.add("platform {} not answering yet", device_->description());
    }
  }
  if (!problem_.empty()) errors.add("platform {}: {}", device_->description(), problem_.view());
}

}  // namespace hubrt::mir_com
