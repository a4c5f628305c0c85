#include "hubrt/hubs/reopening_input.h"

namespace hubrt::hubs {

ReopeningInput::ReopeningInput(hal::Backend& backend, hal::DigitalInputConfig config, Duration retry_interval)
    : backend_(&backend), config_(std::move(config)), retry_interval_(retry_interval) {
  open_error_.assign("not opened yet");
}

void ReopeningInput::open_now(Time now) {
  next_attempt_ = now + retry_interval_;
  auto opened = backend_->open_input(config_);
  if (opened) {
    input_ = std::move(*opened);
    open_error_.clear();
  } else {
    open_error_.assign(opened.error().message);
  }
}

Result<bool> ReopeningInput::read(Time now) noexcept {
  if (input_ == nullptr && now >= next_attempt_) {
    try {
      open_now(now);
    } catch (const std::bad_alloc&) {
      open_error_.assign("out of memory while opening");
    }
  }
  if (input_ == nullptr) return Status(ErrorCode::kUnavailable);
  const Result<bool> level = input_->read(now);
  if (!level.is_ok() && level.status().code() == ErrorCode::kUnavailable) {
    // The chip went away: drop it and open it again later, like at start-up.
    input_.reset();
    open_error_.assign("device went away");
    next_attempt_ = now + retry_interval_;
  }
  return level;
}

}  // namespace hubrt::hubs
