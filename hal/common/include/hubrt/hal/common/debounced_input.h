// A DigitalInput decorator that applies DigitalInputConfig::debounce to any backend's input.
#pragma once

#include <memory>

#include "hubrt/hal/common/debouncer.h"
#include "hubrt/hal/digital_io.h"

namespace hubrt::hal {

// Reads the wrapped input and reports a new level only after it has held for `window` (see
// Debouncer for the exact rule). A failed read returns the wrapped input's error unchanged and
// leaves the debouncing state as it was. Not thread-safe (as every DigitalInput); never allocates
// in read().
class DebouncedInput final : public DigitalInput {
 public:
  // Precondition: `inner` is not null.
  DebouncedInput(std::unique_ptr<DigitalInput> inner, Duration window) noexcept;

 private:
  Result<bool> do_read(Time now) noexcept override;

  std::unique_ptr<DigitalInput> inner_;
  Debouncer debouncer_;
};

// Wraps `inner` in a DebouncedInput when `window` is positive, else returns it unchanged.
std::unique_ptr<DigitalInput> debounce(std::unique_ptr<DigitalInput> inner, Duration window);

}  // namespace hubrt::hal
