#include "hubrt/hal/common/debounced_input.h"

#include <cassert>

namespace hubrt::hal {

DebouncedInput::DebouncedInput(std::unique_ptr<DigitalInput> inner, Duration window) noexcept
    : inner_(std::move(inner)), debouncer_(window) {
  assert(inner_ != nullptr);
}

Result<bool> DebouncedInput::do_read(Time now) noexcept {
  const Result<bool> raw = inner_->read(now);
  if (!raw.is_ok()) return raw;
  return debouncer_.update(raw.value(), now);
}

std::unique_ptr<DigitalInput> debounce(std::unique_ptr<DigitalInput> inner, Duration window) {
  if (window <= Duration::zero()) return inner;
  return std::make_unique<DebouncedInput>(std::move(inner), window);
}

}  // namespace hubrt::hal
