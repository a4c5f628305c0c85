#include "hubrt/hubs/reopening_input.h"

#include <gtest/gtest.h>

namespace hubrt::hubs {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;

// A backend whose GPIO chip can be plugged in and out by the test.
class PluggableBackend final : public hal::Backend {
 public:
  struct Line final : hal::DigitalInput {
    explicit Line(PluggableBackend& owner) : owner_(owner) {}
    Result<bool> do_read(Time /*now*/) noexcept override {
      if (!owner_.plugged) return Status(ErrorCode::kUnavailable);
      return owner_.level;
    }
    PluggableBackend& owner_;
  };

  Expected<std::unique_ptr<hal::DigitalInput>> open_input(const hal::DigitalInputConfig& config) override {
    ++open_attempts;
    if (!plugged)
      return make_error(ErrorCode::kNotFound, config.signal + ": GPIO chip 'gpiochip9' not found");
    return std::unique_ptr<hal::DigitalInput>(std::make_unique<Line>(*this));
  }
  Expected<std::unique_ptr<hal::DigitalOutput>> open_output(const hal::DigitalOutputConfig&) override {
    return make_error(ErrorCode::kNotFound, "no outputs");
  }
  Expected<std::unique_ptr<hal::CanBus>> open_can(const hal::CanConfig&) override {
    return make_error(ErrorCode::kNotFound, "no CAN");
  }
  Expected<std::unique_ptr<hal::ModbusClient>> open_modbus(const hal::ModbusConfig&) override {
    return make_error(ErrorCode::kNotFound, "no Modbus");
  }

  bool plugged = false;
  bool level = true;
  int open_attempts = 0;
};

class ReopeningInputTest : public ::testing::Test {
 protected:
  Time now() const { return clock_.now().mono; }
  hal::DigitalInputConfig config() const {
    hal::DigitalInputConfig c;
    c.signal = "dock.slot.smart_tool";
    c.chip = "gpiochip9";
    c.line = 12;
    return c;
  }
  ManualClock clock_;
  PluggableBackend backend_;
};

TEST_F(ReopeningInputTest, AMissingDeviceIsReportedAndRetriedAtTheInterval) {
  ReopeningInput input(backend_, config(), seconds(2));
  input.open_now(now());
  EXPECT_FALSE(input.is_open());
  EXPECT_EQ(input.open_error(), "dock.slot.smart_tool: GPIO chip 'gpiochip9' not found");
  EXPECT_EQ(input.read(now()).status().code(), ErrorCode::kUnavailable);
  clock_.advance(milliseconds(1999));
  EXPECT_FALSE(input.read(now()).is_ok());
  EXPECT_EQ(backend_.open_attempts, 1) << "no retry before the interval: opening is not free";
  backend_.plugged = true;
  clock_.advance(milliseconds(1));
  const Result<bool> level = input.read(now());
  ASSERT_TRUE(level.is_ok());
  EXPECT_TRUE(level.value());
  EXPECT_EQ(backend_.open_attempts, 2);
  EXPECT_TRUE(input.is_open());
  EXPECT_TRUE(input.open_error().empty());
}

TEST_F(ReopeningInputTest, ADeviceThatGoesAwayIsOpenedAgainLater) {
  backend_.plugged = true;
  ReopeningInput input(backend_, config(), seconds(2));
  input.open_now(now());
  ASSERT_TRUE(input.read(now()).is_ok());
  backend_.plugged = false;
  EXPECT_EQ(input.read(now()).status().code(), ErrorCode::kUnavailable);
  EXPECT_FALSE(input.is_open());
  EXPECT_EQ(input.open_error(), "device went away");
  backend_.plugged = true;
  clock_.advance(seconds(2));
  EXPECT_TRUE(input.read(now()).is_ok());
  EXPECT_TRUE(input.is_open());
}

}  // namespace
}  // namespace hubrt::hubs
