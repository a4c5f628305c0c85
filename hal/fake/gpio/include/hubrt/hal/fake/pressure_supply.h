// The compressed-air supply of the tool changer, seen through its pressure switch.
#pragma once

#include <vector>

#include "hubrt/hal/fake/fake_gpio.h"
#include "hubrt/hal/fake/sim_line.h"

namespace hubrt::hal::fake {

// Told when the supply pressure comes or goes (pneumatic valves are).
class PressureListener {
 public:
  virtual void on_pressure_changed(Time at, bool ok) = 0;

 protected:
  PressureListener() = default;
  ~PressureListener() = default;
  PressureListener(const PressureListener&) = default;
  PressureListener& operator=(const PressureListener&) = default;
};

// The switch line is active while pressure is OK. A drop or a return takes effect at once on the
// switch and on the valves fed by the supply. Not thread-safe (as FakeGpio).
class PressureSupply final : public Simulator {
 public:
  PressureSupply(FakeGpio& gpio, SimLine pressure_switch, bool ok_initially) noexcept;

  // Pressure lost now (compressor off, hose burst). No effect when already lost.
  void drop() noexcept { set_ok(false); }
  // Pressure back now.
  void restore() noexcept { set_ok(true); }
  [[nodiscard]] bool ok() const noexcept { return ok_; }
  // `listener` must outlive this supply.
  void attach(PressureListener& listener) { listeners_.push_back(&listener); }

  void advance_to(Time /*now*/) override {}

 private:
  void set_ok(bool ok) noexcept;

  FakeGpio& gpio_;
  SimLine switch_;
  bool ok_;
  std::vector<PressureListener*> listeners_;
};

}  // namespace hubrt::hal::fake
