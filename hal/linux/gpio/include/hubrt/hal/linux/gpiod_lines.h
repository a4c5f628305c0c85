// Digital inputs and outputs on Linux GPIO character devices, through libgpiod 1.6 (v1 API).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/hal/digital_io.h"

namespace hubrt::hal {

// The consumer name our line requests carry (what `gpioinfo` shows as the holder).
inline constexpr const char* kGpioConsumer = "hubrt";

// Requests `config.line` of `config.chip` (a path, kernel name or label: see gpio_chip_selector.h)
// as an input with the configured polarity (active-low flag) and bias. When `config.catch_pulses`
// is set the line is requested for both-edge events and read() reports a pulse that came and went
// between two reads for one read (pulse_catcher.h). Debouncing is not applied here: wrap the
// result in DebouncedInput (LinuxBackend does).
// Errors (message starts with the signal name and names the chip and line):
//   kNotFound — no such chip (the message lists the chips that exist) or path absent;
//   kInvalidArgument — the path is not a GPIO character device, or the kernel refused the flags;
//   kOutOfRange — the line offset is beyond the chip's lines;
//   kBusy — the line is held (the message names the holder's consumer label);
//   kPermissionDenied — no access to the chip's device; kIo — anything else.
// The returned input's read() never blocks; it fails with kUnavailable once the chip is gone
// (ENODEV) and kIo on other errors. Thread-safety: may be called from any thread; each returned
// object is independent and owned by one thread.
Expected<std::unique_ptr<DigitalInput>> open_gpiod_input(const DigitalInputConfig& config);

// Requests the line as an output driving `config.initial` (logical) from the moment of the
// request, with a bias toward the safe level when `config.bias_toward_safe` is set. The request
// is entered in the crash-safe table (crash_safe_outputs.h) until the output is destroyed.
// write() and write_safe() never block. Errors as open_gpiod_input.
Expected<std::unique_ptr<DigitalOutput>> open_gpiod_output(const DigitalOutputConfig& config);

struct GpioChipInfo {
  std::string name;   // "gpiochip0"
  std::string label;  // "pinctrl-bcm2711"
  unsigned num_lines = 0;
};

// The GPIO chips of this system, in /dev order; empty when there are none.
// Errors: kPermissionDenied / kIo when a chip cannot be opened to read its label.
Expected<std::vector<GpioChipInfo>> list_gpio_chips();

}  // namespace hubrt::hal
