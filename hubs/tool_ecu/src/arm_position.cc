#include "arm_position.h"

namespace hubrt::tool_ecu {

ArmPosition decode_arm_position(bool home, bool pre_home, bool out_of_range) noexcept {
  const int active = int{home} + int{pre_home} + int{out_of_range};
  if (active == 0) return ArmPosition::kOperating;
  if (active > 1) return ArmPosition::kUnclear;
  if (home) return ArmPosition::kHome;
  return pre_home ? ArmPosition::kPreHome : ArmPosition::kOutOfRange;
}

std::string_view to_string(ArmPosition position) noexcept {
  switch (position) {
    case ArmPosition::kOperating:
      return "operating";
    case ArmPosition::kHome:
      return "home";
    case ArmPosition::kPreHome:
      return "pre_home";
    case ArmPosition::kOutOfRange:
      return "out_of_range";
    case ArmPosition::kUnclear:
      return "unclear";
    case ArmPosition::kUnknown:
      break;
  }
  return "unknown";
}

ArmPosition ArmSensors::read(Time now) noexcept {
  std::array<bool, 3> active{};
  bool all_read = true;
  for (std::size_t i = 0; i < sensors_.size(); ++i) {
    const Result<bool> level = sensors_[i].input.read(now);
    sensors_[i].last_error = level.is_ok() ? ErrorCode::kOk : level.status().code();
    if (level.is_ok()) {
      active[i] = level.value();
    } else {
      all_read = false;
    }
  }
  if (!all_read) return ArmPosition::kUnknown;
  return decode_arm_position(active[0], active[1], active[2]);
}

void ArmSensors::report(runtime::ErrorList& errors) const noexcept {
  for (const Sensor& sensor : sensors_) {
    if (!sensor.input.is_open()) {
      errors.add("arm position sensor {} not available: {}", sensor.input.config().signal,
                 sensor.input.error());
    } else if (sensor.last_error != ErrorCode::kOk) {
      errors.add("arm position sensor {} failed to read: {}", sensor.input.config().signal,
                 to_string(sensor.last_error));
    }
  }
}

}  // namespace hubrt::tool_ecu
