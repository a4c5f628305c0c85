// The table behind crash_safe_outputs.h: open_gpiod_output() enters each output line request
// here and removes it before closing the descriptor.
#pragma once

namespace hubrt::hal::gpiod_detail {

// Enters a line request (`fd` from GPIO_GET_LINEHANDLE_IOCTL, one line) with its logical safe
// level and whether it was requested active-low. Returns the slot, or -1 when the table is full
// (the output then works, but a crash handler cannot reach it). Thread-safe, lock-free.
int enter_crash_safe_output(int fd, bool safe, bool active_low) noexcept;

// Frees `slot` (a value enter_crash_safe_output returned; -1 is ignored). Must be called before
// the descriptor is closed. Thread-safe, lock-free.
void leave_crash_safe_output(int slot) noexcept;

}  // namespace hubrt::hal::gpiod_detail
