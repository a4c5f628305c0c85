// How the `chip` string of a Digital{Input,Output}Config names a GPIO chip. Every backend and the
// board loader read it the same way.
#pragma once

#include <cstdint>
#include <string_view>

namespace hubrt::hal {

enum class GpioChipSelectorKind : std::uint8_t {
  kPath,   // starts with '/': a character device, e.g. "/dev/gpiochip0"
  kName,   // "gpiochip" followed by digits: the kernel's name, e.g. "gpiochip0"
  kLabel,  // anything else: the chip's label, e.g. "pinctrl-bcm2711", "sim-dock"
};

// Classifies a non-empty selector. Thread-safe; never allocates.
GpioChipSelectorKind classify_gpio_chip(std::string_view selector) noexcept;

// "path", "name" or "label".
std::string_view to_string(GpioChipSelectorKind kind) noexcept;

}  // namespace hubrt::hal
