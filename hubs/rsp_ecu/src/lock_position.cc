#include "lock_position.h"

namespace hubrt::rsp_ecu {

void LockPosition::drive(bool open, Time now) noexcept {
  if (open == open_) return;
  open_ = open;
  settled_ = false;
  stroke_start_ = pressure_ok_ ? std::optional<Time>(now) : std::nullopt;
}

void LockPosition::pressure(bool ok, Time now) noexcept {
  if (ok == pressure_ok_) return;
  pressure_ok_ = ok;
  if (settled_) return;
  // A stroke needs pressure all the way: losing it stops the piston, regaining it starts anew.
  stroke_start_ = ok ? std::optional<Time>(now) : std::nullopt;
}

void LockPosition::advance(Time now) noexcept {
  if (!settled_ && stroke_start_ && now - *stroke_start_ >= actuation_) settled_ = true;
}

std::string_view LockPosition::name() const noexcept {
  if (settled_) return open_ ? "open" : "closed";
  return open_ ? "opening" : "closing";
}

}  // namespace hubrt::rsp_ecu
