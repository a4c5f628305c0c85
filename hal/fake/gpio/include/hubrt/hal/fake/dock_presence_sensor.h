// A dock slot's presence sensor (a mechanical contact closed by the docked end-effector).
#pragma once

#include <array>
#include <cstddef>

#include "hubrt/hal/fake/fake_gpio.h"
#include "hubrt/hal/fake/sim_line.h"

namespace hubrt::hal::fake {

// The line is active while the slot is occupied. Each change of occupancy bounces the contact for
// `bounce`: with occupancy changing to v at t the line shows v at t, !v at t+bounce/4, v at
// t+bounce/2, !v at t+3·bounce/4 and v from t+bounce on. A bounce of zero gives one clean edge.
// A new change during a bounce cancels the rest of it. Not thread-safe (as FakeGpio).
class DockPresenceSensor final : public Simulator {
 public:
  DockPresenceSensor(FakeGpio& gpio, SimLine sensor, Duration bounce, bool occupied_initially) noexcept;

  // An end-effector docked (true) or taken (false) now, by the test or a station model.
  void set_occupied(bool occupied) noexcept;
  [[nodiscard]] bool occupied() const noexcept { return occupied_; }
  // True until the contact settles after the last change (as of now).
  [[nodiscard]] bool bouncing() noexcept {
    gpio_.advance();
    return next_ < pending_.size();
  }
  [[nodiscard]] Duration bounce() const noexcept { return bounce_; }

  void advance_to(Time now) override;

 private:
  struct Edge {
    Time at;
    bool active = false;
  };
  static constexpr std::size_t kBounceEdges = 4;  // after the first edge

  FakeGpio& gpio_;
  SimLine sensor_;
  Duration bounce_;
  bool occupied_;
  std::array<Edge, kBounceEdges> pending_{};
  std::size_t next_ = kBounceEdges;  // next pending edge; kBounceEdges = none
};

}  // namespace hubrt::hal::fake
