// An output requested with a pull toward its safe level (DigitalOutputConfig::bias_toward_safe)
// falls to that level when it is released — its process killed, the kernel freeing the line — as
// on gpio-sim and the Raspberry Pi; without the pull it keeps the level it was last driven to.
#include <gtest/gtest.h>

#include "hubrt/hal/fake/fake_gpio.h"

namespace hubrt::hal::fake {
namespace {

struct Case {
  Polarity polarity;
  bool safe;
  bool safe_level_high;  // the electrical level of `safe`
};

class ReleasedOutputBiasTest : public ::testing::TestWithParam<Case> {
 protected:
  DigitalOutputConfig output(bool bias_toward_safe) const {
    DigitalOutputConfig config;
    config.signal = "rsp.lock_valve";
    config.chip = "sim-rsp";
    config.line = 4;
    config.polarity = GetParam().polarity;
    config.initial = GetParam().safe;
    config.safe = GetParam().safe;
    config.bias_toward_safe = bias_toward_safe;
    return config;
  }
  // Opens the output, drives it away from its safe level, then releases it; returns the level.
  bool level_after_release(bool bias_toward_safe) {
    {
      auto opened = gpio_.open_output(output(bias_toward_safe));
      EXPECT_TRUE(opened) << opened.error().message;
      EXPECT_TRUE((*opened)->write(!GetParam().safe).is_ok());
      EXPECT_EQ(chip_.level(4).value(), !GetParam().safe_level_high) << "driven away from safe";
    }
    return chip_.level(4).value();
  }

  ManualClock clock_;
  FakeGpio gpio_{clock_};
  FakeGpioChip& chip_ = gpio_.add_chip("sim-rsp", 8);
};

TEST_P(ReleasedOutputBiasTest, WithThePullTheReleasedLineFallsSafe) {
  EXPECT_EQ(level_after_release(true), GetParam().safe_level_high);
}

TEST_P(ReleasedOutputBiasTest, WithoutThePullTheReleasedLineKeepsItsLastLevel) {
  EXPECT_EQ(level_after_release(false), !GetParam().safe_level_high);
}

INSTANTIATE_TEST_SUITE_P(Polarities, ReleasedOutputBiasTest,
                         ::testing::Values(Case{Polarity::kActiveHigh, false, false},
                                           Case{Polarity::kActiveHigh, true, true},
                                           Case{Polarity::kActiveLow, false, true},
                                           Case{Polarity::kActiveLow, true, false}));

}  // namespace
}  // namespace hubrt::hal::fake
