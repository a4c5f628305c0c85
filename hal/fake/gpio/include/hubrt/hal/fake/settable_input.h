// A plain input the test sets: tool-ID lines, buttons, anything without behaviour of its own.
#pragma once

#include <optional>

#include "hubrt/hal/fake/fake_gpio.h"
#include "hubrt/hal/fake/sim_line.h"

namespace hubrt::hal::fake {

// Not thread-safe (as FakeGpio). Create through FakeGpio::add_simulator.
class SettableInput final : public Simulator {
 public:
  // Drives the line to `initially_active` at the clock's now.
  SettableInput(FakeGpio& gpio, SimLine line, bool initially_active) noexcept;

  // Drives the line now; cancels a pulse in progress.
  void set(bool active) noexcept;
  // Active now, inactive again exactly `width` later (a button press, a sensor blip).
  void pulse(Duration width) noexcept;
  // Whether it is active now (brings the simulation up to now first).
  [[nodiscard]] bool active() noexcept {
    gpio_.advance();
    return active_;
  }

  void advance_to(Time now) override;

 private:
  FakeGpio& gpio_;
  SimLine line_;
  bool active_;
  std::optional<Time> pulse_ends_;
};

}  // namespace hubrt::hal::fake
