// Where the changer's lock is. The lock has no position sensor, so this follows the valve: a
// stroke ends one actuation time after the valve changed, provided supply pressure was there for
// all of it (without pressure the piston stays put; when pressure returns the stroke starts over).
// The actuation time is the longest a stroke takes, so "closed" is never claimed early.
#pragma once

#include <optional>
#include <string_view>

#include "hubrt/base/time.h"

namespace hubrt::rsp_ecu {

// Not thread-safe; never allocates.
class LockPosition {
 public:
  // The valve starts de-energised (closed) at `now`; until one actuation time has passed the lock
  // may still be closing (the hub may have restarted with the changer open).
  LockPosition(Duration actuation, Time now) noexcept : actuation_(actuation), stroke_start_(now) {}

  // The valve drives the lock open (true) or closed (false) from `now` on.
  void drive(bool open, Time now) noexcept;
  // Supply pressure as seen at `now`.
  void pressure(bool ok, Time now) noexcept;
  // Completes a stroke whose time is up at `now`.
  void advance(Time now) noexcept;

  [[nodiscard]] bool open_commanded() const noexcept { return open_; }
  // The lock is closed and not moving.
  [[nodiscard]] bool closed() const noexcept { return settled_ && !open_; }
  // "closed", "opening", "open" or "closing".
  [[nodiscard]] std::string_view name() const noexcept;

 private:
  Duration actuation_;
  bool open_ = false;
  bool settled_ = false;
  bool pressure_ok_ = true;
  std::optional<Time> stroke_start_;  // empty while a stroke waits for pressure
};

}  // namespace hubrt::rsp_ecu
