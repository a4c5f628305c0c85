#include "hubrt/hal/common/debouncer.h"

namespace hubrt::hal {

bool Debouncer::update(bool raw, Time now) noexcept {
  if (!stable_.has_value() || window_ <= Duration::zero()) {
    stable_ = raw;
    candidate_pending_ = false;
    return raw;
  }
  if (raw == *stable_) {
    candidate_pending_ = false;
    return raw;
  }
  // Two levels only: a sample that differs from the stable level is the candidate level.
  if (!candidate_pending_) {
    candidate_pending_ = true;
    candidate_since_ = now;
  }
  if (now - candidate_since_ >= window_) {
    stable_ = raw;
    candidate_pending_ = false;
  }
  return *stable_;
}

void Debouncer::reset() noexcept {
  stable_.reset();
  candidate_pending_ = false;
}

}  // namespace hubrt::hal
