#include "hubrt/hub_api/remote_state.h"

namespace hubrt::hub_api {

std::string_view RemoteStateBase::loss_reason(Time now) noexcept {
  if (received_ == 0) {
    reason_.format("input '{}' ({}): no State received yet", name_, topic_);
  } else if (now - last_arrival_ > timeout_) {
    reason_.format("input '{}' ({}): no State for {:.2f} s (limit {:.2f} s)", name_, topic_,
                   to_seconds(now - last_arrival_), to_seconds(timeout_));
  } else {
    reason_.clear();
  }
  return reason_.view();
}

}  // namespace hubrt::hub_api
