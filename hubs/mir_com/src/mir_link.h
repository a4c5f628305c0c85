// The node's side of the platform's REST API: one request in flight at a time on the HAL's
// asynchronous HTTP device (submit, then poll with `now`: no thread, no clock, no allocation
// here), the last status the platform answered and when, and the last thing that went wrong.
// Both node types (robot_mover_logic.h, pose_saver_logic.h) keep one.
#pragma once

#include <memory>

#include "hubrt/base/time.h"
#include "hubrt/hal/async_http.h"
#include "hubrt/protocol/mir_rest.h"
#include "hubrt/runtime/error_list.h"

#include "mir_settings.h"

namespace hubrt::mir_com {

using MirDevice = hal::AsyncHttp<protocol::mir::MirReply>;
using MirCompletion = hal::HttpCompletion<protocol::mir::MirReply>;

class MirLink {
 public:
  MirLink(std::unique_ptr<MirDevice> device, const MirLinkSettings& settings) noexcept
      : device_(std::move(device)), poll_(settings.poll), answer_within_(settings.answer_within) {}

  // Collects the request in flight if it finished; true with `done` filled then. A status in any
  // answer (GET or PUT /status) becomes the last status; a failure becomes the last problem.
  bool collect(Time now, MirCompletion& done) noexcept;
  // Submits `request` unless one is in flight. False when busy or refused (an empty path: a name
  // that does not fit; counted as a problem).
  bool send(const hal::HttpRequest& request, Time now) noexcept;
  [[nodiscard]] bool busy() const noexcept { return in_flight_; }
  // A GET /status is due (poll interval since the last status request).
  [[nodiscard]] bool status_due(Time now) const noexcept {
    return !asked_status_ || now - status_asked_at_ >= poll_;
  }
  // Sends GET /status when due and idle.
  void poll_status(Time now) noexcept;

  // The platform answered a status within answer_within.
  [[nodiscard]] bool answering(Time now) const noexcept {
    return has_status_ && now - status_at_ <= answer_within_;
  }
  [[nodiscard]] bool has_status() const noexcept { return has_status_; }
  [[nodiscard]] const protocol::mir::MirStatus& status() const noexcept { return status_; }
  [[nodiscard]] Time status_at() const noexcept { return status_at_; }
  [[nodiscard]] Duration answer_within() const noexcept { return answer_within_; }

  // What went wrong with the last request that failed, until one succeeds; into `errors`
  // ("mir (http://...): GET /status: HTTP 500 (internal server error)"), and "not answering".
  void report(runtime::ErrorList& errors, Time now) const noexcept;
  [[nodiscard]] std::string_view description() const noexcept { return device_->description(); }
  [[nodiscard]] MirDevice& device() noexcept { return *device_; }

 private:
  std::unique_ptr<MirDevice> device_;
  Duration poll_;
  Duration answer_within_;
  bool in_flight_ = false;
  bool asked_status_ = false;
  Time status_asked_at_{};
  bool has_status_ = false;
  Time status_at_{};
  protocol::mir::MirStatus status_;
  hal::FixedText<160> problem_;  // empty: the last request succeeded
};

}  // namespace hubrt::mir_com
