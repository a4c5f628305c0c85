// The crash-time walk against the kernel tier's gpio-sim chip: an output left at its active level
// is written back to its safe level, and the bias set with it is what the line shows once the
// output is released (gpio-sim gives a released line the level of its pull). Skips outside the
// tier.
#include <gtest/gtest.h>

#include "hubrt/hal/linux/crash_safe_outputs.h"
#include "hubrt/hal/linux/gpiod_lines.h"
#include "hubrt/kernel_test/environment.h"
#include "hubrt/kernel_test/gpio_sim.h"

namespace hubrt::hal {
namespace {

class CrashSafeOnGpioSim : public ::testing::Test {
 protected:
  void SetUp() override {
    HUBRT_SKIP_OUTSIDE_KERNEL_TIER();
    auto chip = kernel_test::gpiosim_chip_from_env();
    ASSERT_TRUE(chip.has_value()) << "the tier did not describe its gpio-sim chip";
    chip_ = *chip;
  }
  DigitalOutputConfig output(unsigned line, Polarity polarity, bool safe) const {
    DigitalOutputConfig config;
    config.signal = "test.output";
    config.chip = chip_.dev_path;
    config.line = line;
    config.polarity = polarity;
    config.initial = !safe;
    config.safe = safe;
    return config;
  }
  int value(unsigned line) const {
    auto v = kernel_test::read_value(chip_, line);
    EXPECT_TRUE(v) << v.error().message;
    return v ? *v : -1;
  }

  kernel_test::GpioSimChip chip_;
};

TEST_F(CrashSafeOnGpioSim, WritesEveryOpenOutputBackToItsSafeLevelAndPullsItThere) {
  // Electrical safe levels: line 1 low (active high, safe inactive), line 2 high (active high,
  // safe active), line 3 high (active low, safe inactive).
  ASSERT_TRUE(kernel_test::set_pull(chip_, 2, kernel_test::Pull::kDown));
  ASSERT_TRUE(kernel_test::set_pull(chip_, 1, kernel_test::Pull::kUp));
  ASSERT_TRUE(kernel_test::set_pull(chip_, 3, kernel_test::Pull::kDown));
  {
    auto a = open_gpiod_output(output(1, Polarity::kActiveHigh, false));
    auto b = open_gpiod_output(output(2, Polarity::kActiveHigh, true));
    auto c = open_gpiod_output(output(3, Polarity::kActiveLow, false));
    ASSERT_TRUE(a && b && c);
    EXPECT_EQ(crash_safe_output_count(), 3U);
    EXPECT_EQ(value(1), 1);  // opened at their unsafe levels
    EXPECT_EQ(value(2), 0);
    EXPECT_EQ(value(3), 0);

    const CrashSafeResult result = drive_outputs_safe_from_crash();
    EXPECT_EQ(result.driven, 3);
    EXPECT_EQ(result.failed, 0);
    EXPECT_EQ(value(1), 0);
    EXPECT_EQ(value(2), 1);
    EXPECT_EQ(value(3), 1);
  }
  EXPECT_EQ(crash_safe_output_count(), 0U) << "closed outputs leave the table";
  // Released: each line keeps the pull the walk set toward its safe level.
  EXPECT_EQ(value(1), 0);
  EXPECT_EQ(value(2), 1);
  EXPECT_EQ(value(3), 1);
}

TEST_F(CrashSafeOnGpioSim, BiasTowardSafeKeepsAReleasedLineAtItsSafeLevel) {
  ASSERT_TRUE(kernel_test::set_pull(chip_, 4, kernel_test::Pull::kDown));
  DigitalOutputConfig config = output(4, Polarity::kActiveHigh, true);
  config.initial = true;
  config.bias_toward_safe = true;
  {
    auto opened = open_gpiod_output(config);
    ASSERT_TRUE(opened) << opened.error().message;
    EXPECT_EQ(value(4), 1);
  }
  EXPECT_EQ(value(4), 1) << "released, the line kept the pull-up the request set";
  config.bias_toward_safe = false;
  config.safe = false;
  config.initial = false;
  ASSERT_TRUE(kernel_test::set_pull(chip_, 4, kernel_test::Pull::kUp));
  {
    auto opened = open_gpiod_output(config);  // no bias: the pull stays up
    ASSERT_TRUE(opened) << opened.error().message;
    EXPECT_EQ(value(4), 0);
  }
  EXPECT_EQ(value(4), 1) << "without the bias the released line falls back to the old pull";
}

}  // namespace
}  // namespace hubrt::hal
