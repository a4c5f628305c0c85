#include "hubrt/hal/fake/pneumatic_valve.h"

#include <cassert>

namespace hubrt::hal::fake {

PneumaticValve::PneumaticValve(FakeGpio& gpio, std::string name, SimLine solenoid,
                               std::vector<SimLine> confirms, PressureSupply* supply, Duration actuation)
    : gpio_(gpio),
      name_(std::move(name)),
      solenoid_(solenoid),
      confirms_(std::move(confirms)),
      failed_confirms_(confirms_.size()),
      supply_(supply),
      actuation_(actuation),
      commanded_energised_(solenoid_.active()),
      energised_position_(commanded_energised_) {
  solenoid_.watch(*this);
  if (supply_ != nullptr) supply_->attach(*this);
  drive_confirms(gpio_.now());
}

void PneumaticValve::reschedule(Time at) noexcept {
  if (stuck_ || !pressure_ok() || commanded_energised_ == energised_position_) {
    arrival_.reset();
  } else if (!arrival_) {
    arrival_ = at + actuation_;
  }
}

void PneumaticValve::drive_confirms(Time at) noexcept {
  for (std::size_t i = 0; i < confirms_.size(); ++i) {
    confirms_[i].drive(failed_confirms_[i].value_or(energised_position_), at);
  }
}

void PneumaticValve::advance_to(Time now) {
  if (!arrival_ || *arrival_ > now) return;
  const Time arrived = *arrival_;
  arrival_.reset();
  energised_position_ = commanded_energised_;
  drive_confirms(arrived);
}

void PneumaticValve::on_line_changed(Time at, bool high) {
  advance_to(at);
  commanded_energised_ = solenoid_.means_active(high);
  reschedule(at);
}

void PneumaticValve::on_pressure_changed(Time at, bool /*ok*/) {
  advance_to(at);
  // A stroke needs pressure all the way: losing it cancels the stroke, regaining it starts anew.
  arrival_.reset();
  reschedule(at);
}

void PneumaticValve::stick(bool stuck) noexcept {
  gpio_.advance();
  stuck_ = stuck;
  reschedule(gpio_.now());
}

void PneumaticValve::fail_confirm(std::size_t index, bool active) noexcept {
  assert(index < confirms_.size());
  gpio_.advance();
  failed_confirms_[index] = active;
  confirms_[index].drive(active, gpio_.now());
}

void PneumaticValve::repair_confirm(std::size_t index) noexcept {
  assert(index < confirms_.size());
  gpio_.advance();
  failed_confirms_[index].reset();
  confirms_[index].drive(energised_position_, gpio_.now());
}

}  // namespace hubrt::hal::fake
