#include "reopening_output.h"

#include <new>

namespace hubrt::rsp_ecu {

ReopeningOutput::ReopeningOutput(hal::Backend& backend, hal::DigitalOutputConfig config,
                                 Duration retry_interval)
    : backend_(&backend), config_(std::move(config)), retry_interval_(retry_interval) {
  open_error_.assign("not opened yet");
}

void ReopeningOutput::open_now(Time now) {
  next_attempt_ = now + retry_interval_;
  auto opened = backend_->open_output(config_);
  if (opened) {
    output_ = std::move(*opened);
    open_error_.clear();
  } else {
    open_error_.assign(opened.error().message);
  }
}

Status ReopeningOutput::write(bool active, Time now) noexcept {
  if (output_ == nullptr && now >= next_attempt_) {
    try {
      open_now(now);
    } catch (const std::bad_alloc&) {
      open_error_.assign("out of memory while opening");
    }
  }
  if (output_ == nullptr) return Status(ErrorCode::kUnavailable);
  const Status written = output_->write(active);
  if (!written.is_ok() && written.code() == ErrorCode::kUnavailable) {
    output_.reset();
    open_error_.assign("device went away");
    next_attempt_ = now + retry_interval_;
  }
  return written;
}

Status ReopeningOutput::write_if_open(bool active) noexcept {
  if (output_ == nullptr) return Status(ErrorCode::kUnavailable);
  return output_->write(active);
}

}  // namespace hubrt::rsp_ecu
