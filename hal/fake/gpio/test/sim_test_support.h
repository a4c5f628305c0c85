// A fake GPIO world with one chip and helpers to open its lines, shared by the simulator tests.
#pragma once

#include <gtest/gtest.h>

#include "hubrt/hal/fake/fake_gpio.h"
#include "hubrt/hal/fake/sim_line.h"

namespace hubrt::hal::fake {

class SimTest : public ::testing::Test {
 protected:
  SimTest() : chip_(gpio_.add_chip("sim", 16)) {}

  SimLine line(unsigned n, Polarity polarity = Polarity::kActiveHigh) { return SimLine(chip_, n, polarity); }
  std::unique_ptr<DigitalInput> input(unsigned n, Polarity polarity = Polarity::kActiveHigh) {
    DigitalInputConfig config;
    config.signal = "in" + std::to_string(n);
    config.chip = "sim";
    config.line = n;
    config.polarity = polarity;
    auto opened = gpio_.open_input(config);
    EXPECT_TRUE(opened.is_ok()) << opened.error().message;
    return opened ? std::move(*opened) : nullptr;
  }
  std::unique_ptr<DigitalOutput> output(unsigned n, Polarity polarity = Polarity::kActiveHigh) {
    DigitalOutputConfig config;
    config.signal = "out" + std::to_string(n);
    config.chip = "sim";
    config.line = n;
    config.polarity = polarity;
    auto opened = gpio_.open_output(config);
    EXPECT_TRUE(opened.is_ok()) << opened.error().message;
    return opened ? std::move(*opened) : nullptr;
  }
  Time now() const { return clock_.now().mono; }
  bool read(DigitalInput& in) {
    const Result<bool> level = in.read(now());
    EXPECT_TRUE(level.is_ok());
    return level.value_or(false);
  }

  ManualClock clock_;
  FakeGpio gpio_{clock_};
  FakeGpioChip& chip_;
};

}  // namespace hubrt::hal::fake
