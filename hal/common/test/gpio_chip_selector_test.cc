#include "hubrt/hal/common/gpio_chip_selector.h"

#include <gtest/gtest.h>

namespace hubrt::hal {
namespace {

TEST(GpioChipSelector, ClassifiesPathsNamesAndLabels) {
  EXPECT_EQ(classify_gpio_chip("/dev/gpiochip0"), GpioChipSelectorKind::kPath);
  EXPECT_EQ(classify_gpio_chip("gpiochip0"), GpioChipSelectorKind::kName);
  EXPECT_EQ(classify_gpio_chip("gpiochip12"), GpioChipSelectorKind::kName);
  EXPECT_EQ(classify_gpio_chip("pinctrl-bcm2711"), GpioChipSelectorKind::kLabel);
  EXPECT_EQ(classify_gpio_chip("sim-dock"), GpioChipSelectorKind::kLabel);
  // Only "gpiochip" + digits is a kernel name.
  EXPECT_EQ(classify_gpio_chip("gpiochip"), GpioChipSelectorKind::kLabel);
  EXPECT_EQ(classify_gpio_chip("gpiochip0a"), GpioChipSelectorKind::kLabel);
}

}  // namespace
}  // namespace hubrt::hal
