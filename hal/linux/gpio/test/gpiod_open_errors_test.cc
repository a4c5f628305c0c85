// This machine's kernel has no GPIO: every open must fail at once with an error that says so, and
// never crash or hang. (The success paths run against gpio-sim in a VM: hal/contract.)
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "hubrt/hal/linux/gpiod_lines.h"

namespace hubrt::hal {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

bool machine_has_gpio() {
  auto chips = list_gpio_chips();
  return !chips || !chips->empty();
}

class GpiodOpenErrors : public ::testing::Test {
 protected:
  void SetUp() override {
    if (machine_has_gpio())
      GTEST_SKIP() << "this machine has GPIO chips: the no-GPIO expectations do not apply";
  }
  static DigitalInputConfig input(std::string chip) {
    DigitalInputConfig config;
    config.signal = "dock.slot.smart_tool";
    config.chip = std::move(chip);
    config.line = 5;
    return config;
  }
};

TEST_F(GpiodOpenErrors, ListingChipsFindsNone) {
  auto chips = list_gpio_chips();
  ASSERT_TRUE(chips.is_ok()) << chips.error().message;
  EXPECT_TRUE(chips->empty());
}

TEST_F(GpiodOpenErrors, ChipByNameIsNotFoundAndTheMessageSaysThereIsNoGpio) {
  auto opened = open_gpiod_input(input("gpiochip0"));
  ASSERT_FALSE(opened.is_ok());
  EXPECT_EQ(opened.error().code, ErrorCode::kNotFound);
  EXPECT_THAT(opened.error().message,
              StartsWith("dock.slot.smart_tool: GPIO chip with name 'gpiochip0' not found"));
  EXPECT_THAT(opened.error().message, HasSubstr("no GPIO chips present"));
  EXPECT_THAT(opened.error().message, HasSubstr("CONFIG_GPIOLIB"));
}

TEST_F(GpiodOpenErrors, ChipByLabelIsNotFound) {
  auto opened = open_gpiod_input(input("pinctrl-bcm2711"));
  ASSERT_FALSE(opened.is_ok());
  EXPECT_EQ(opened.error().code, ErrorCode::kNotFound);
  EXPECT_THAT(opened.error().message, HasSubstr("GPIO chip with label 'pinctrl-bcm2711' not found"));
}

TEST_F(GpiodOpenErrors, ChipByMissingPathIsNotFound) {
  auto opened = open_gpiod_input(input("/dev/gpiochip7"));
  ASSERT_FALSE(opened.is_ok());
  EXPECT_EQ(opened.error().code, ErrorCode::kNotFound);
  EXPECT_THAT(opened.error().message, HasSubstr("GPIO chip with path '/dev/gpiochip7' not found"));
}

TEST_F(GpiodOpenErrors, APathThatIsNoGpioChipIsRejected) {
  auto opened = open_gpiod_input(input("/dev/null"));
  ASSERT_FALSE(opened.is_ok());
  EXPECT_EQ(opened.error().code, ErrorCode::kInvalidArgument);
  EXPECT_EQ(opened.error().message, "dock.slot.smart_tool: '/dev/null' is not a GPIO character device");
}

TEST_F(GpiodOpenErrors, EmptyChipIsRejected) {
  auto opened = open_gpiod_input(input(""));
  ASSERT_FALSE(opened.is_ok());
  EXPECT_EQ(opened.error().code, ErrorCode::kInvalidArgument);
}

TEST_F(GpiodOpenErrors, OutputsFailTheSameWay) {
  DigitalOutputConfig config;
  config.signal = "rsp.lock_valve";
  config.chip = "gpiochip0";
  config.line = 4;
  auto opened = open_gpiod_output(config);
  ASSERT_FALSE(opened.is_ok());
  EXPECT_EQ(opened.error().code, ErrorCode::kNotFound);
  EXPECT_THAT(opened.error().message,
              StartsWith("rsp.lock_valve: GPIO chip with name 'gpiochip0' not found"));
}

TEST_F(GpiodOpenErrors, EdgeEventInputsFailTheSameWay) {
  DigitalInputConfig config = input("gpiochip0");
  config.catch_pulses = true;
  auto opened = open_gpiod_input(config);
  ASSERT_FALSE(opened.is_ok());
  EXPECT_EQ(opened.error().code, ErrorCode::kNotFound);
}

}  // namespace
}  // namespace hubrt::hal
