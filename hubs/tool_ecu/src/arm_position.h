// Where the smart tool's arm is, from its three position sensors (home, pre-home, out-of-range):
// none active = operating position, exactly one = that position, more than one = unclear.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

#include "hubrt/base/time.h"
#include "hubrt/hal/common/supervised_device.h"
#include "hubrt/runtime/error_list.h"

namespace hubrt::tool_ecu {

enum class ArmPosition : std::uint8_t {
  kUnknown,  // a sensor could not be read
  kOperating,
  kHome,
  kPreHome,
  kOutOfRange,
  kUnclear,  // an inconsistent combination
};

// The position the three sensor levels mean. Pure.
ArmPosition decode_arm_position(bool home, bool pre_home, bool out_of_range) noexcept;
// "operating", "home", "pre_home", "out_of_range", "unclear", "unknown".
std::string_view to_string(ArmPosition position) noexcept;

// The three sensors, supervised devices opened again until they work. Not thread-safe: the cycle
// thread owns it. Reading does not allocate (reopening does).
class ArmSensors {
 public:
  // The sensors as the hub type opened them: home, pre-home, out-of-range. One that is not open is
  // reported and retried.
  explicit ArmSensors(std::array<hal::SupervisedInput, 3> sensors) noexcept
      : sensors_{Sensor{std::move(sensors[0])}, Sensor{std::move(sensors[1])},
                 Sensor{std::move(sensors[2])}} {}

  // Samples all three; kUnknown when any read fails.
  ArmPosition read(Time now) noexcept;
  // Adds what is wrong with the sensors (not available, read failed) to `errors`.
  void report(runtime::ErrorList& errors) const noexcept;
  // All three sensors open.
  [[nodiscard]] bool all_open() const noexcept {
    return sensors_[0].input.is_open() && sensors_[1].input.is_open() && sensors_[2].input.is_open();
  }

 private:
  struct Sensor {
    hal::SupervisedInput input;
    ErrorCode last_error = ErrorCode::kOk;  // of the last read
  };

  std::array<Sensor, 3> sensors_;  // home, pre-home, out-of-range
};

}  // namespace hubrt::tool_ecu
