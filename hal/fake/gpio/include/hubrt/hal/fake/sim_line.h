// One GPIO line as a simulated device sees it: in its own terms ("sensor active", "solenoid
// energised"), turned into electrical levels by the wiring's polarity, as a real device is wired.
#pragma once

#include "hubrt/hal/digital_io.h"
#include "hubrt/hal/fake/fake_gpio_chip.h"

namespace hubrt::hal::fake {

// A reference to a line; the chip must outlive it. Not thread-safe (as FakeGpio).
class SimLine {
 public:
  // Precondition: line < chip.num_lines().
  SimLine(FakeGpioChip& chip, unsigned line, Polarity polarity) noexcept
      : chip_(&chip), line_(line), active_low_(polarity == Polarity::kActiveLow) {}

  // Drives the line to the electrical level that means `active`, from time `at`.
  void drive(bool active, Time at) const noexcept { chip_->drive(line_, active != active_low_, at).ignore(); }
  // Whether the line's electrical level now means active.
  [[nodiscard]] bool active() const noexcept {
    return chip_->level(line_).value_or(active_low_) != active_low_;
  }
  // What an electrical level seen by a LineListener means.
  [[nodiscard]] bool means_active(bool high) const noexcept { return high != active_low_; }
  void watch(LineListener& listener) const noexcept { chip_->watch(line_, listener).ignore(); }

  [[nodiscard]] FakeGpioChip& chip() const noexcept { return *chip_; }
  [[nodiscard]] unsigned line() const noexcept { return line_; }

 private:
  FakeGpioChip* chip_;
  unsigned line_;
  bool active_low_;
};

}  // namespace hubrt::hal::fake
