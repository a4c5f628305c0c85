#include "hubrt/hal/common/gpio_chip_selector.h"

#include <algorithm>

namespace hubrt::hal {

GpioChipSelectorKind classify_gpio_chip(std::string_view selector) noexcept {
  if (selector.starts_with('/')) return GpioChipSelectorKind::kPath;
  constexpr std::string_view kPrefix = "gpiochip";
  if (selector.size() > kPrefix.size() && selector.starts_with(kPrefix) &&
      std::all_of(selector.begin() + kPrefix.size(), selector.end(),
                  [](char c) { return c >= '0' && c <= '9'; })) {
    return GpioChipSelectorKind::kName;
  }
  return GpioChipSelectorKind::kLabel;
}

std::string_view to_string(GpioChipSelectorKind kind) noexcept {
  switch (kind) {
    case GpioChipSelectorKind::kPath:
      return "path";
    case GpioChipSelectorKind::kName:
      return "name";
    case GpioChipSelectorKind::kLabel:
      return "label";
  }
  return "label";
}

}  // namespace hubrt::hal
