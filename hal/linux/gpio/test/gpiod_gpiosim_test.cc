// The libgpiod v1 backend against the kernel tier's gpio-sim chip (tests/kernel/run): what the
// digital I/O contract does not cover. Skips outside the tier.
#include <chrono>

#include <gmock/gmock.h>
#include <gpiod.h>
#include <gtest/gtest.h>

#include "hubrt/hal/linux/gpiod_lines.h"
#include "hubrt/kernel_test/environment.h"
#include "hubrt/kernel_test/gpio_sim.h"

namespace hubrt::hal {
namespace {

using ::testing::HasSubstr;

class GpiodOnGpioSim : public ::testing::Test {
 protected:
  void SetUp() override {
    HUBRT_SKIP_OUTSIDE_KERNEL_TIER();
    auto chip = kernel_test::gpiosim_chip_from_env();
    ASSERT_TRUE(chip.has_value()) << "the tier did not describe its gpio-sim chip";
    chip_ = *chip;
  }
  DigitalInputConfig input(std::string chip, unsigned line) const {
    DigitalInputConfig config;
    config.signal = "test.input";
    config.chip = std::move(chip);
    config.line = line;
    return config;
  }
  void pull(unsigned line, bool up) {
    const auto done =
        kernel_test::set_pull(chip_, line, up ? kernel_test::Pull::kUp : kernel_test::Pull::kDown);
    ASSERT_TRUE(done.is_ok()) << done.error().message;
  }

  kernel_test::GpioSimChip chip_;
  ManualClock clock_;
};

TEST_F(GpiodOnGpioSim, FindsTheChipByNamePathAndLabel) {
  for (const std::string& selector : {chip_.name, chip_.dev_path, chip_.label}) {
    pull(3, true);
    auto opened = open_gpiod_input(input(selector, 3));
    ASSERT_TRUE(opened.is_ok()) << selector << ": " << opened.error().message;
    EXPECT_TRUE((*opened)->read(clock_.now().mono).value_or(false)) << selector;
  }
}

TEST_F(GpiodOnGpioSim, MissingChipListsTheChipsThatExist) {
  auto opened = open_gpiod_input(input("pinctrl-bcm2711", 0));
  ASSERT_FALSE(opened.is_ok());
  EXPECT_EQ(opened.error().code, ErrorCode::kNotFound);
  EXPECT_THAT(opened.error().message, HasSubstr(chip_.name + " [" + chip_.label + "] (" +
                                                std::to_string(chip_.num_lines) + " lines)"));
}

TEST_F(GpiodOnGpioSim, LineBeyondTheChipSaysHowManyLinesItHas) {
  auto opened = open_gpiod_input(input(chip_.label, chip_.num_lines));
  ASSERT_FALSE(opened.is_ok());
  EXPECT_EQ(opened.error().code, ErrorCode::kOutOfRange);
  EXPECT_THAT(opened.error().message, HasSubstr("which has " + std::to_string(chip_.num_lines) + " lines"));
}

TEST_F(GpiodOnGpioSim, BusyLineNamesTheOtherConsumer) {
  gpiod_chip* chip = gpiod_chip_open(chip_.dev_path.c_str());
  ASSERT_NE(chip, nullptr);
  gpiod_line* line = gpiod_chip_get_line(chip, 2);
  ASSERT_NE(line, nullptr);
  ASSERT_EQ(gpiod_line_request_input(line, "other-app"), 0);
  DigitalOutputConfig config;
  config.signal = "rsp.lock_valve";
  config.chip = chip_.name;
  config.line = 2;
  auto opened = open_gpiod_output(config);
  gpiod_chip_close(chip);
  ASSERT_FALSE(opened.is_ok());
  EXPECT_EQ(opened.error().code, ErrorCode::kBusy);
  EXPECT_THAT(opened.error().message, HasSubstr("rsp.lock_valve: line 2 of " + chip_.name));
  EXPECT_THAT(opened.error().message, HasSubstr("held by 'other-app'"));
}

TEST_F(GpiodOnGpioSim, AFloodOfEdgesIsDrainedWithoutBlockingAndReportedAsOnePulse) {
  pull(5, false);
  DigitalInputConfig config = input(chip_.dev_path, 5);
  config.catch_pulses = true;
  auto opened = open_gpiod_input(config);
  ASSERT_TRUE(opened.is_ok()) << opened.error().message;
  DigitalInput& in = **opened;
  EXPECT_FALSE(in.read(clock_.now().mono).value_or(true));
  for (int i = 0; i < 40; ++i) {  // more edges than the kernel queues per line (16)
    pull(5, true);
    pull(5, false);
  }
  // Events arrive through the interrupt thread: poll for the pulse. 2 s absorbs emulation noise.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(2);
  bool caught = false;
  while (!caught && std::chrono::steady_clock::now() < deadline) {
    const auto before = std::chrono::steady_clock::now();
    const Result<bool> level = in.read(clock_.now().mono);
    ASSERT_TRUE(level.is_ok()) << to_string(level.status().code());
    // A read never waits for events; 100 ms only absorbs scheduling noise under emulation.
    EXPECT_LT(std::chrono::steady_clock::now() - before, std::chrono::milliseconds(100));
    caught = level.value();
  }
  EXPECT_TRUE(caught);
  // Whatever edges were still queued belong to the same burst: the line is low and stays so.
  bool low_again = false;
  for (int i = 0; i < 200 && !low_again; ++i) low_again = !in.read(clock_.now().mono).value_or(true);
  EXPECT_TRUE(low_again);
}

}  // namespace
}  // namespace hubrt::hal
