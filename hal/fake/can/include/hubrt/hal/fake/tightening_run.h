// The physics of one simulated tightening run, as pure arithmetic on time: torque builds at a
// constant rate toward the program's target, the spindle turns at a constant speed, and the run
// ends at the first of: torque reached, angle past the window's maximum, maximum run time.
// Exact to the nanosecond so that ManualClock tests can hit the end of a run precisely.
#pragma once

#include <cstdint>

#include "hubrt/base/time.h"
#include "hubrt/protocol/smart_tool_can.h"

namespace hubrt::hal::fake {

struct RunPhysics {
  double torque_rate_nm_per_s = 20.0;   // torque build-up during a forward run
  double angle_rate_deg_per_s = 360.0;  // spindle speed, both directions
  Duration max_run_time = std::chrono::seconds(5);
  double slip_torque_fraction = 0.3;  // with joint slip, torque stalls at this fraction of the target
};

// Why a run ended.
enum class RunEnd : std::uint8_t { kTorqueReached, kAngleHigh, kTimeout, kStopped, kAlarm, kLinkLost };

class TighteningRun {
 public:
  // A forward run of `program` (precondition: valid_program(program)); `slipping` caps the torque
  // at the slip fraction of the target, as a stripped thread or a missing screw does.
  static TighteningRun forward(const protocol::smart_tool::Program& program, const RunPhysics& physics,
                               bool slipping, Time start) noexcept;
  // A reverse (loosening) run: no target, no torque build-up, ends only when told to.
  static TighteningRun reverse(const RunPhysics& physics, Time start) noexcept;

  [[nodiscard]] bool is_reverse() const noexcept { return reverse_; }
  // When the run ends by itself, and why; Time::max() for a reverse run.
  [[nodiscard]] Time natural_end() const noexcept { return end_; }
  [[nodiscard]] RunEnd natural_cause() const noexcept { return cause_; }

  // Measured values at `t` (clamped to [start, natural end]), in wire units.
  [[nodiscard]] std::uint16_t torque_cnm(Time t) const noexcept;
  [[nodiscard]] std::uint16_t angle_ddeg(Time t) const noexcept;

  // The result of a forward run that ended at `t` for `cause`.
  [[nodiscard]] protocol::smart_tool::RunResult result(Time t, RunEnd cause,
                                                       std::uint8_t run_counter) const noexcept;

 private:
  TighteningRun() = default;
  [[nodiscard]] Duration elapsed(Time t) const noexcept;

  protocol::smart_tool::Program program_{};
  RunPhysics physics_{};
  bool reverse_ = false;
  std::uint16_t torque_cap_cnm_ = 0;
  Time start_{};
  Time end_ = Time::max();
  RunEnd cause_ = RunEnd::kStopped;
};

}  // namespace hubrt::hal::fake
