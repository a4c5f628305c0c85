#include "hubrt/hal/fake/lift_drive.h"

#include <algorithm>
#include <cmath>

namespace hubrt::hal::fake {
namespace {

namespace ld = protocol::lift_drive;

std::uint16_t to_tenth_mm(double mm) noexcept {
  return static_cast<std::uint16_t>(std::clamp(std::lround(mm * 10.0), 0L, 65535L));
}

}  // namespace

LiftDrive::LiftDrive(LiftDriveConfig config, Time now)
    : config_(config),
      last_update_(now),
      last_request_(now),
      target_(config.initial_position_tenth_mm),
      speed_(config.default_speed_mm_s),
      position_mm_(ld::to_mm(config.initial_position_tenth_mm)) {}

LiftDriveRegisters LiftDrive::read(Time now) {
  const std::lock_guard lock(mutex_);
  update_locked(now);
  last_request_ = last_update_;
  return registers_locked();
}

ModbusException LiftDrive::write_holding(std::uint16_t address, std::span<const std::uint16_t> values,
                                         Time now) {
  const std::lock_guard lock(mutex_);
  update_locked(now);
  last_request_ = last_update_;
  return write_holding_locked(address, values);
}

ModbusException LiftDrive::write_coils(std::uint16_t address, std::span<const bool> values, Time now) {
  const std::lock_guard lock(mutex_);
  update_locked(now);
  last_request_ = last_update_;
  if (values.empty() || address >= ld::control::kCoilCount ||
      values.size() > static_cast<std::size_t>(ld::control::kCoilCount - address)) {
    return ModbusException::kIllegalDataAddress;
  }
  std::uint16_t control = control_;
  for (std::size_t i = 0; i < values.size(); ++i) {
    const auto bit = static_cast<std::uint16_t>(1U << (address + i));
    control =
        values[i] ? static_cast<std::uint16_t>(control | bit) : static_cast<std::uint16_t>(control & ~bit);
  }
  apply_control_locked(control);
  return ModbusException::kNone;
}

void LiftDrive::inject_overcurrent(Time now) {
  const std::lock_guard lock(mutex_);
  update_locked(now);
  trip_locked(ld::FaultCode::kOvercurrent);
}

void LiftDrive::set_overtemperature(bool hot, Time now) {
  const std::lock_guard lock(mutex_);
  update_locked(now);
  hot_ = hot;
  if (hot) trip_locked(ld::FaultCode::kOvertemperature);
}

void LiftDrive::set_blocked(bool blocked, Time now) {
  const std::lock_guard lock(mutex_);
  update_locked(now);
  blocked_ = blocked;
  if (!blocked) lag_mm_ = 0.0;
}

double LiftDrive::position_mm(Time now) {
  const std::lock_guard lock(mutex_);
  update_locked(now);
  return position_mm_;
}

void LiftDrive::update_locked(Time now) noexcept {
  now = std::max(now, last_update_);
  if (enabled_ && watchdog_ms_ > 0) {
    const Time expiry = last_request_ + std::chrono::milliseconds(watchdog_ms_);
    if (expiry < now) {
      // Motion up to the expiry happened; from then on the drive is off.
      integrate_locked(std::max(expiry, last_update_));
      trip_locked(ld::FaultCode::kWatchdog);
    }
  }
  integrate_locked(now);
}

void LiftDrive::integrate_locked(Time to) noexcept {
  if (to <= last_update_) return;
  const double dt = to_seconds(to - last_update_);
  last_update_ = to;
  if (!motion_commanded_locked()) {
    lag_mm_ = 0.0;
    return;
  }
  const double target = target_mm_locked();
  const double distance = std::abs(target - position_mm_);
  const double travel = speed_ * dt;
  if (blocked_) {
    // The commanded motion runs ahead of a load that does not move (never past the target).
    lag_mm_ = std::min(lag_mm_ + travel, distance);
    if (lag_mm_ > config_.following_error_limit_mm) trip_locked(ld::FaultCode::kFollowingError);
    return;
  }
  position_mm_ = travel >= distance ? target : position_mm_ + std::copysign(travel, target - position_mm_);
}

void LiftDrive::trip_locked(ld::FaultCode code) noexcept {
  fault_ = code;
  enabled_ = false;
  lag_mm_ = 0.0;
}

void LiftDrive::apply_control_locked(std::uint16_t control) noexcept {
  const std::uint16_t previous = control_;
  control_ = control;
  const auto rising = [&](std::uint16_t bit) { return (control & bit) != 0 && (previous & bit) == 0; };
  // Reset before enable, so that one write of "reset" followed by one of "enable" recovers.
  if (rising(ld::control::kResetFault) && fault_ != ld::FaultCode::kNone) {
    const bool cause_persists = fault_ == ld::FaultCode::kOvertemperature && hot_;
    if (!cause_persists) {
      fault_ = ld::FaultCode::kNone;
      lag_mm_ = 0.0;
    }
  }
  if ((control & ld::control::kEnable) == 0) {
    enabled_ = false;
  } else if (rising(ld::control::kEnable) && fault_ == ld::FaultCode::kNone) {
    // Only an edge powers the stage: after a fault the master must write enable 0 then 1.
    enabled_ = true;
  }
}

ModbusException LiftDrive::write_holding_locked(std::uint16_t address,
                                                std::span<const std::uint16_t> values) noexcept {
  if (values.empty() || address >= ld::holding::kCount ||
      values.size() > static_cast<std::size_t>(ld::holding::kCount - address)) {
    return ModbusException::kIllegalDataAddress;
  }
  for (std::size_t i = 0; i < values.size(); ++i) {
    const std::uint16_t value = values[i];
    bool ok = true;
    switch (address + i) {
      case ld::holding::kControlWord:
        ok = (value & ~ld::control::kAll) == 0;
        break;
      case ld::holding::kTargetPosition:
        ok = value <= config_.travel_tenth_mm;
        break;
      case ld::holding::kSpeed:
        ok = value >= 1 && value <= config_.max_speed_mm_s;
        break;
      case ld::holding::kWatchdogMs:
        ok = value <= ld::kMaxWatchdogMs;
        break;
      default:
        break;
    }
    if (!ok) return ModbusException::kIllegalDataValue;
  }
  for (std::size_t i = 0; i < values.size(); ++i) {
    const std::uint16_t value = values[i];
    switch (address + i) {
      case ld::holding::kControlWord:
        apply_control_locked(value);
        break;
      case ld::holding::kTargetPosition:
        target_ = value;
        break;
      case ld::holding::kSpeed:
        speed_ = value;
        break;
      case ld::holding::kWatchdogMs:
        watchdog_ms_ = value;
        break;
      default:
        break;
    }
  }
  return ModbusException::kNone;
}

bool LiftDrive::motion_commanded_locked() const noexcept {
  return enabled_ && (control_ & ld::control::kMove) != 0 && (control_ & ld::control::kStop) == 0 &&
         fault_ == ld::FaultCode::kNone && position_mm_ != target_mm_locked();
}

double LiftDrive::target_mm_locked() const noexcept {
  return ld::to_mm(target_);
}

LiftDriveRegisters LiftDrive::registers_locked() const noexcept {
  LiftDriveRegisters r;
  r.holding[ld::holding::kControlWord] = control_;
  r.holding[ld::holding::kTargetPosition] = target_;
  r.holding[ld::holding::kSpeed] = speed_;
  r.holding[ld::holding::kWatchdogMs] = watchdog_ms_;

  const bool moving = motion_commanded_locked();
  const double window = config_.in_position_window_mm;
  std::uint16_t status = 0;
  if (enabled_) status |= ld::status::kEnabled;
  if (moving) status |= ld::status::kMoving;
  if (!moving && std::abs(position_mm_ - target_mm_locked()) <= window) status |= ld::status::kInPosition;
  if (position_mm_ >= ld::to_mm(config_.travel_tenth_mm) - window) status |= ld::status::kLimitUp;
  if (position_mm_ <= window) status |= ld::status::kLimitDown;
  if (fault_ != ld::FaultCode::kNone) status |= ld::status::kFault;

  int speed = 0;
  if (moving && !blocked_) speed = target_mm_locked() > position_mm_ ? speed_ : -speed_;
  r.input[ld::input::kActualPosition] = to_tenth_mm(position_mm_);
  r.input[ld::input::kStatusWord] = status;
  r.input[ld::input::kFaultCode] = static_cast<std::uint16_t>(fault_);
  // Two's complement on the wire, as the register map says.
  r.input[ld::input::kActualSpeed] = static_cast<std::uint16_t>(static_cast<std::int16_t>(speed));
  return r;
}

}  // namespace hubrt::hal::fake
