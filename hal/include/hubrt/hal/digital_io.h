// Digital input and output lines, one object per line, polarity already applied: code above the
// HAL deals in "active / inactive", never in electrical levels.
#pragma once

#include <string>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"

namespace hubrt::hal {

enum class Polarity : std::uint8_t { kActiveHigh, kActiveLow };
enum class Bias : std::uint8_t { kAsIs, kDisabled, kPullUp, kPullDown };

struct DigitalInputConfig {
  std::string signal;  // logical name used in error messages, e.g. "dock.slot.smart_tool"
  std::string chip;    // chip name ("gpiochip0"), label ("pinctrl-bcm2711") or path ("/dev/gpiochip0")
  unsigned line = 0;   // line offset on the chip
  Polarity polarity = Polarity::kActiveHigh;
  Bias bias = Bias::kAsIs;
  Duration debounce{0};  // a level must hold this long before read() reports it; 0 = off
  // A pulse that starts and ends between two reads is reported for one read instead of being lost
  // (Linux: edge events; rule in hubrt/hal/common/pulse_catcher.h). Pointless with debounce > 0.
  bool catch_pulses = false;
};

struct DigitalOutputConfig {
  std::string signal;
  std::string chip;
  unsigned line = 0;
  Polarity polarity = Polarity::kActiveHigh;
  bool initial = false;  // logical level driven when the line is opened
  bool safe = false;     // logical level driven by write_safe() (fault, shutdown)
  // Also pull the line toward its safe level (Linux: the request's bias flag, ignored by a chip
  // without bias support), so that it falls there once this process releases it — killed, crashed
  // — on drivers that keep a released line's bias (gpio-sim; the Raspberry Pi's pinctrl turns a
  // released line into an input with its pull), before `hubd --safe-outputs` runs. Every output a
  // hub opens from its board asks for it (hubs/common/board_devices.h), and --safe-outputs does.
  // The fake backend models it: a released output keeps the pull and settles to it.
  bool bias_toward_safe = false;
};

// One input line. Not thread-safe: owned and read by one cycle.
class DigitalInput {
 public:
  virtual ~DigitalInput() = default;
  DigitalInput(const DigitalInput&) = delete;
  DigitalInput& operator=(const DigitalInput&) = delete;

  // The logical level at `now` (true = active), after debouncing.
  // Errors: kIo (the read failed), kUnavailable (the chip went away). Never blocks.
  Result<bool> read(Time now) noexcept { return do_read(now); }

 protected:
  DigitalInput() = default;

 private:
  virtual Result<bool> do_read(Time now) noexcept = 0;
};

// One output line. Not thread-safe: owned and written by one cycle.
class DigitalOutput {
 public:
  virtual ~DigitalOutput() = default;
  DigitalOutput(const DigitalOutput&) = delete;
  DigitalOutput& operator=(const DigitalOutput&) = delete;

  // Drives the logical level (true = active). Errors: kIo, kUnavailable. Never blocks.
  Status write(bool active) noexcept { return do_write(active); }
  // Drives the configured safe level.
  Status write_safe() noexcept { return do_write(safe_value()); }
  [[nodiscard]] bool safe_value() const noexcept { return do_safe_value(); }

 protected:
  DigitalOutput() = default;

 private:
  virtual Status do_write(bool active) noexcept = 0;
  [[nodiscard]] virtual bool do_safe_value() const noexcept = 0;
};

}  // namespace hubrt::hal
