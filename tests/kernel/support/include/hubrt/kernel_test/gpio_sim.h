// Driving and observing gpio-sim lines from a test, the way real wiring would: the simulator's
// `pull` file plays the outside world driving an input, its `value` file shows what an output is
// driven to. Guest only (gpio-sim exists in the kernel tier's kernel).
#pragma once

#include <chrono>
#include <map>
#include <string>

#include "hubrt/base/status.h"
#include "hubrt/kernel_test/environment.h"

namespace hubrt::kernel_test {

enum class Pull { kDown, kUp };

// Writes "pull-up"/"pull-down" to sim_gpio<offset>/pull: an input line then reads 1/0 (edge
// events fire). Errors: kOutOfRange for an offset past the chip, kIo naming the file otherwise.
// Thread-safe.
Expected<void> set_pull(const GpioSimChip& chip, unsigned offset, Pull pull);

// Reads sim_gpio<offset>/value: 1 or 0, what the line is driven to (by an output's consumer, or by
// the pull for an input). Errors: kOutOfRange, kIo naming the file, kProtocol for other contents.
// Thread-safe.
Expected<int> read_value(const GpioSimChip& chip, unsigned offset);

// Polls read_value() until it equals `expected`; kTimeout (with the last value seen) after
// `timeout`. For outputs driven from another thread or process. Thread-safe.
Expected<void> wait_for_value(const GpioSimChip& chip, unsigned offset, int expected,
                              std::chrono::milliseconds timeout);

// One more gpio-sim chip, made with the tier's helper (HUBRT_GPIOSIM_HELPER, guest/gpiosim) and
// removed when this object goes away. For tests that need named lines or several chips.
// Not thread-safe: one owner.
class ScopedGpioSimChip {
 public:
  // `name` must be unique in the guest (it is the configfs directory and the chip label);
  // `line_names` maps offsets to line names. Errors: kFailedPrecondition outside the tier,
  // kIo with the helper's message when the chip cannot be made.
  static Expected<ScopedGpioSimChip> create(const std::string& name, unsigned num_lines,
                                            const std::map<unsigned, std::string>& line_names = {});

  ScopedGpioSimChip(ScopedGpioSimChip&& other) noexcept;
  ScopedGpioSimChip& operator=(ScopedGpioSimChip&& other) noexcept;
  ScopedGpioSimChip(const ScopedGpioSimChip&) = delete;
  ScopedGpioSimChip& operator=(const ScopedGpioSimChip&) = delete;
  // Removes the chip (its lines must be released by then); a failure is reported on stderr.
  ~ScopedGpioSimChip();

  [[nodiscard]] const GpioSimChip& chip() const { return chip_; }

 private:
  ScopedGpioSimChip(std::string configfs_name, GpioSimChip chip)
      : configfs_name_(std::move(configfs_name)), chip_(std::move(chip)) {}

  std::string configfs_name_;  // empty once moved from
  GpioSimChip chip_;
};

}  // namespace hubrt::kernel_test
