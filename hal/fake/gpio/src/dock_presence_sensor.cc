#include "hubrt/hal/fake/dock_presence_sensor.h"

namespace hubrt::hal::fake {

DockPresenceSensor::DockPresenceSensor(FakeGpio& gpio, SimLine sensor, Duration bounce,
                                       bool occupied_initially) noexcept
    : gpio_(gpio), sensor_(sensor), bounce_(bounce), occupied_(occupied_initially) {
  sensor_.drive(occupied_, gpio_.now());
}

void DockPresenceSensor::set_occupied(bool occupied) noexcept {
  gpio_.advance();
  if (occupied == occupied_) return;
  occupied_ = occupied;
  const Time now = gpio_.now();
  sensor_.drive(occupied_, now);
  next_ = kBounceEdges;
  if (bounce_ <= Duration::zero()) return;
  for (std::size_t i = 0; i < kBounceEdges; ++i) {
    // Edges 1..4 at quarters of the bounce time, alternating, ending on the new level.
    pending_[i] =
        Edge{now + bounce_ * static_cast<Duration::rep>(i + 1) / 4, (i % 2 == 0) ? !occupied_ : occupied_};
  }
  next_ = 0;
}

void DockPresenceSensor::advance_to(Time now) {
  while (next_ < kBounceEdges && pending_[next_].at <= now) {
    sensor_.drive(pending_[next_].active, pending_[next_].at);
    ++next_;
  }
}

}  // namespace hubrt::hal::fake
