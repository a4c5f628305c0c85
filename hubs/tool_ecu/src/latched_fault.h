// A fault that latches: active while its cause is present and afterwards, until a reset. A cause
// still present when the reset comes stays active by its presence, but latches again only after
// it was seen gone once — so one reset is enough when the cause clears later, and a cause that
// comes back after that needs another reset.
#pragma once

namespace hubrt::tool_ecu {

// Plain value type; not thread-safe.
class LatchedFault {
 public:
  // The cause's presence at this sample.
  void observe(bool present) noexcept {
    present_ = present;
    if (!present) {
      armed_ = true;
    } else if (armed_) {
      latched_ = true;
    }
  }
  void reset() noexcept {
    latched_ = false;
    armed_ = false;
  }

  [[nodiscard]] bool present() const noexcept { return present_; }
  // Latched and the cause gone: only a reset clears it.
  [[nodiscard]] bool only_latched() const noexcept { return latched_ && !present_; }
  [[nodiscard]] bool active() const noexcept { return present_ || latched_; }
  // Latched (present or not): a reset is needed to clear it.
  [[nodiscard]] bool latched() const noexcept { return latched_; }

 private:
  bool present_ = false;
  bool latched_ = false;
  bool armed_ = true;
};

}  // namespace hubrt::tool_ecu
