// On this machine (no GPIO in the kernel) the backend must fail cleanly and at once.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "hubrt/hal/linux/backend.h"

namespace hubrt::hal {
namespace {

using ::testing::HasSubstr;

TEST(LinuxBackend, MissingGpioChipIsAClearErrorForDebouncedInputs) {
  LinuxBackend backend;
  DigitalInputConfig config;
  config.signal = "dock.slot.filter_tool";
  config.chip = "pinctrl-bcm2711";
  config.line = 6;
  config.debounce = std::chrono::milliseconds(20);
  auto input = backend.open_input(config);
  ASSERT_FALSE(input.is_ok());
  EXPECT_THAT(input.error().message,
              HasSubstr("dock.slot.filter_tool: GPIO chip with label 'pinctrl-bcm2711'"));
}

TEST(LinuxBackend, MissingGpioChipIsAClearErrorForOutputs) {
  LinuxBackend backend;
  DigitalOutputConfig config;
  config.signal = "tool.run_forward";
  config.chip = "/dev/gpiochip0";
  config.line = 17;
  auto output = backend.open_output(config);
  ASSERT_FALSE(output.is_ok());
  EXPECT_THAT(output.error().message, HasSubstr("tool.run_forward: GPIO chip with path '/dev/gpiochip0'"));
}

TEST(LinuxBackend, CanGoesToSocketCan) {
  LinuxBackend backend;
  CanConfig config;
  config.bus = "tool_bus";
  config.interface = "can0";
  auto bus = backend.open_can(config);
  if (bus.is_ok()) GTEST_SKIP() << "this machine has a can0 interface";
  // Without AF_CAN in the kernel: kUnavailable; with it but without can0: kNotFound.
  EXPECT_TRUE(bus.error().code == ErrorCode::kUnavailable || bus.error().code == ErrorCode::kNotFound)
      << bus.error().message;
  EXPECT_THAT(bus.error().message, HasSubstr("tool_bus"));
}

TEST(LinuxBackend, ModbusGoesToLibmodbus) {
  LinuxBackend backend;
  ModbusConfig config;
  config.device = "lift_drive";
  config.endpoint = ModbusTcpEndpoint{"lift-drive.local", 502};  // not IPv4: refused before any I/O
  auto client = backend.open_modbus(config);
  ASSERT_FALSE(client.is_ok());
  EXPECT_EQ(client.error().code, ErrorCode::kInvalidArgument);
  EXPECT_THAT(client.error().message, HasSubstr("lift_drive"));
}

}  // namespace
}  // namespace hubrt::hal
