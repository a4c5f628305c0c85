#include "hubrt/hal/fake/tightening_run.h"

#include <algorithm>
#include <cmath>

namespace hubrt::hal::fake {
namespace {

namespace st = protocol::smart_tool;

// Absorbs floating-point rounding so that a value computed exactly at a crossing time lands on
// the crossed side (the crossing times are rounded up to whole nanoseconds).
constexpr double kRoundingSlack = 1e-6;

Duration ceil_to_ns(double seconds) noexcept {
  return Duration(static_cast<std::int64_t>(std::ceil(seconds * 1e9)));
}

std::uint16_t to_wire(double value) noexcept {
  return static_cast<std::uint16_t>(std::clamp(std::floor(value + kRoundingSlack), 0.0, 65535.0));
}

}  // namespace

TighteningRun TighteningRun::forward(const st::Program& program, const RunPhysics& physics, bool slipping,
                                     Time start) noexcept {
  TighteningRun run;
  run.program_ = program;
  run.physics_ = physics;
  run.start_ = start;
  run.torque_cap_cnm_ = slipping ? to_wire(program.torque_target_cnm * physics.slip_torque_fraction)
                                 : program.torque_target_cnm;

  // Candidates in priority order; a later one replaces an earlier only when strictly sooner.
  Duration to_end = Duration::max();
  if (!slipping) {
    to_end = ceil_to_ns(program.torque_target_cnm / (physics.torque_rate_nm_per_s * 100.0));
    run.cause_ = RunEnd::kTorqueReached;
  }
  // The controller aborts as soon as the measured angle exceeds the window: at max + 0.1°.
  const Duration to_angle_high =
      ceil_to_ns((program.angle_max_ddeg + 1.0) / (physics.angle_rate_deg_per_s * 10.0));
  if (to_angle_high < to_end) {
    to_end = to_angle_high;
    run.cause_ = RunEnd::kAngleHigh;
  }
  if (physics.max_run_time < to_end) {
    to_end = physics.max_run_time;
    run.cause_ = RunEnd::kTimeout;
  }
  run.end_ = start + to_end;
  return run;
}

TighteningRun TighteningRun::reverse(const RunPhysics& physics, Time start) noexcept {
  TighteningRun run;
  run.physics_ = physics;
  run.reverse_ = true;
  run.start_ = start;
  return run;
}

Duration TighteningRun::elapsed(Time t) const noexcept {
  if (t <= start_) return Duration::zero();
  if (end_ != Time::max() && t > end_) return end_ - start_;
  return t - start_;
}

std::uint16_t TighteningRun::torque_cnm(Time t) const noexcept {
  if (reverse_) return 0;
  const double built = physics_.torque_rate_nm_per_s * 100.0 * to_seconds(elapsed(t));
  return std::min(to_wire(built), torque_cap_cnm_);
}

std::uint16_t TighteningRun::angle_ddeg(Time t) const noexcept {
  return to_wire(physics_.angle_rate_deg_per_s * 10.0 * to_seconds(elapsed(t)));
}

st::RunResult TighteningRun::result(Time t, RunEnd cause, std::uint8_t run_counter) const noexcept {
  st::RunResult result;
  result.program = program_.number;
  result.torque_cnm = torque_cnm(t);
  result.angle_ddeg = angle_ddeg(t);
  result.run_counter = run_counter;
  switch (cause) {
    case RunEnd::kTorqueReached:
      if (result.angle_ddeg < program_.angle_min_ddeg) result.nok_reasons |= st::nok_reason::kAngleLow;
      if (result.angle_ddeg > program_.angle_max_ddeg) result.nok_reasons |= st::nok_reason::kAngleHigh;
      break;
    case RunEnd::kAngleHigh:
      result.nok_reasons = st::nok_reason::kAngleHigh | st::nok_reason::kTorqueLow;
      break;
    case RunEnd::kTimeout:
      result.nok_reasons = st::nok_reason::kRunTimeout | st::nok_reason::kTorqueLow;
      break;
    case RunEnd::kStopped:
      result.nok_reasons = st::nok_reason::kStoppedByCommand | st::nok_reason::kTorqueLow;
      break;
    case RunEnd::kAlarm:
      result.nok_reasons = st::nok_reason::kAlarm | st::nok_reason::kTorqueLow;
      break;
    case RunEnd::kLinkLost:
      result.nok_reasons = st::nok_reason::kLinkLost | st::nok_reason::kTorqueLow;
      break;
  }
  result.ok = result.nok_reasons == 0;
  return result;
}

}  // namespace hubrt::hal::fake
