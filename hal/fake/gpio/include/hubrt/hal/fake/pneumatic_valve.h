// A solenoid valve driving a pneumatic actuator (tool-changer lock, gripper), with its
// end-position confirm sensors.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "hubrt/hal/fake/fake_gpio.h"
#include "hubrt/hal/fake/pressure_supply.h"
#include "hubrt/hal/fake/sim_line.h"

namespace hubrt::hal::fake {

// The actuator follows the solenoid (the output line, active = energised): it reaches the other
// end position `actuation` after it was commanded there, provided supply pressure was OK for that
// whole time. Without pressure it stays where it is; when pressure returns the full actuation time
// starts again (the stroke restarts from rest). A command reversed before the end position is
// reached cancels the stroke. The confirm sensors are active while the actuator is in its
// energised end position, and change exactly at the arrival time.
// Not thread-safe (as FakeGpio). Create through FakeGpio::add_simulator.
class PneumaticValve final : public Simulator, private LineListener, private PressureListener {
 public:
  // `supply` may be null (pressure always OK); it and every line's chip must outlive the valve.
  // Starts at rest in the position the solenoid commands now, confirms driven to match.
  PneumaticValve(FakeGpio& gpio, std::string name, SimLine solenoid, std::vector<SimLine> confirms,
                 PressureSupply* supply, Duration actuation);

  [[nodiscard]] const std::string& name() const noexcept { return name_; }
  [[nodiscard]] Duration actuation() const noexcept { return actuation_; }
  // True while the actuator is in its energised end position (as of now: brings the simulation
  // up to the clock first, as the other queries do).
  [[nodiscard]] bool in_energised_position() noexcept {
    gpio_.advance();
    return energised_position_;
  }
  // When the stroke under way ends, or nothing when none is.
  [[nodiscard]] std::optional<Time> arrival() noexcept {
    gpio_.advance();
    return arrival_;
  }

  // Fault: the valve sticks where it is, whatever the solenoid says; unsticking restarts the
  // stroke (full actuation time) if the solenoid commands the other position.
  void stick(bool stuck) noexcept;
  // Fault: confirm sensor `index` reads `active` from now on, whatever the actuator does, so the
  // sensors disagree. Precondition: index < confirm count.
  void fail_confirm(std::size_t index, bool active) noexcept;
  // The sensor works again and shows the actuator's position now.
  void repair_confirm(std::size_t index) noexcept;

  void advance_to(Time now) override;

 private:
  void on_line_changed(Time at, bool high) override;
  void on_pressure_changed(Time at, bool ok) override;
  [[nodiscard]] bool pressure_ok() const noexcept { return supply_ == nullptr || supply_->ok(); }
  void reschedule(Time at) noexcept;
  void drive_confirms(Time at) noexcept;

  FakeGpio& gpio_;
  std::string name_;
  SimLine solenoid_;
  std::vector<SimLine> confirms_;
  std::vector<std::optional<bool>> failed_confirms_;
  PressureSupply* supply_;
  Duration actuation_;
  bool commanded_energised_;
  bool energised_position_;
  bool stuck_ = false;
  std::optional<Time> arrival_;
};

}  // namespace hubrt::hal::fake
