#include "hubrt/hal/fake/settable_input.h"

namespace hubrt::hal::fake {

SettableInput::SettableInput(FakeGpio& gpio, SimLine line, bool initially_active) noexcept
    : gpio_(gpio), line_(line), active_(initially_active) {
  line_.drive(active_, gpio_.now());
}

void SettableInput::set(bool active) noexcept {
  gpio_.advance();
  pulse_ends_.reset();
  active_ = active;
  line_.drive(active_, gpio_.now());
}

void SettableInput::pulse(Duration width) noexcept {
  set(true);
  pulse_ends_ = gpio_.now() + width;
}

void SettableInput::advance_to(Time now) {
  if (!pulse_ends_ || *pulse_ends_ > now) return;
  active_ = false;
  line_.drive(false, *pulse_ends_);
  pulse_ends_.reset();
}

}  // namespace hubrt::hal::fake
