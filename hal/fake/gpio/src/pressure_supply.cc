#include "hubrt/hal/fake/pressure_supply.h"

namespace hubrt::hal::fake {

PressureSupply::PressureSupply(FakeGpio& gpio, SimLine pressure_switch, bool ok_initially) noexcept
    : gpio_(gpio), switch_(pressure_switch), ok_(ok_initially) {
  switch_.drive(ok_, gpio_.now());
}

void PressureSupply::set_ok(bool ok) noexcept {
  // Everything scheduled before this moment happened with the old pressure.
  gpio_.advance();
  if (ok == ok_) return;
  ok_ = ok;
  const Time now = gpio_.now();
  switch_.drive(ok_, now);
  for (PressureListener* listener : listeners_) listener->on_pressure_changed(now, ok_);
}

}  // namespace hubrt::hal::fake
