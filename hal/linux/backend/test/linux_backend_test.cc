// On this machine (no GPIO in the kernel) the backend must fail cleanly and at once.
#include <fstream>
#include <sstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "hubrt/hal/libmodbus/open_libmodbus.h"
#include "hubrt/hal/linux/backend.h"
#include "hubrt/hal/rfid/open_badge_reader.h"
#include "hubrt/hal/socketcan/open_socketcan.h"

namespace hubrt::hal {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

std::string own_mappings() {
  std::ifstream maps("/proc/self/maps");
  std::stringstream text;
  text << maps.rdbuf();
  return text.str();
}

// Every device library, as the development hubd's registry links them (hubs/HubTypes.cmake).
LinuxDeviceLibraries every_device_library() {
  return LinuxDeviceLibraries{
      .open_can = &socketcan::open_socketcan,
      .open_modbus = [](const ModbusConfig& config) { return libmodbus::open_libmodbus(config); },
      .open_badge_reader = &rfid::open_badge_reader,
  };
}

// An output on a GPIO chip this machine does not have (its kernel has no GPIO).
DigitalOutputConfig missing_output(const char* signal) {
  DigitalOutputConfig config;
  config.signal = signal;
  config.chip = "/dev/gpiochip0";
  config.line = 17;
  return config;
}

HttpConfig mir_config() {
  HttpConfig config;
  config.device = "mir";
  config.host = "127.0.0.1";
  config.port = 8080;
  return config;
}

TEST(LinuxBackend, MissingGpioChipIsAClearErrorForDebouncedInputs) {
  LinuxBackend backend(every_device_library());
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
  LinuxBackend backend(every_device_library());
  auto output = backend.open_output(missing_output("tool.run_forward"));
  ASSERT_FALSE(output.is_ok());
  EXPECT_THAT(output.error().message, HasSubstr("tool.run_forward: GPIO chip with path '/dev/gpiochip0'"));
}

TEST(LinuxBackend, CanGoesToSocketCan) {
  LinuxBackend backend(every_device_library());
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
  LinuxBackend backend(every_device_library());
  ModbusConfig config;
  config.device = "lift_drive";
  config.endpoint = ModbusTcpEndpoint{"lift-drive.local", 502};  // not IPv4: refused before any I/O
  auto client = backend.open_modbus(config);
  ASSERT_FALSE(client.is_ok());
  EXPECT_EQ(client.error().code, ErrorCode::kInvalidArgument);
  EXPECT_THAT(client.error().message, HasSubstr("lift_drive"));
}

// A board's program links the device libraries of its hub type only (a Dock ECU's: GPIO): a CAN
// bus, a Modbus drive or a badge reader in its board file is a clear error naming the device, not
// a crash through a null opener nor a silent success.
TEST(LinuxBackend, AKindWhoseLibraryIsNotLinkedIsAClearErrorNamingTheDevice) {
  LinuxBackend backend(LinuxDeviceLibraries{});
  CanConfig can;
  can.bus = "tool_bus";
  can.interface = "vcan0";
  auto bus = backend.open_can(can);
  ASSERT_FALSE(bus.is_ok());
  EXPECT_EQ(bus.error().code, ErrorCode::kUnavailable);
  EXPECT_THAT(bus.error().message, HasSubstr("tool_bus: this hubd is built without CAN devices"));
  ModbusConfig modbus;
  modbus.device = "lift_drive";
  modbus.endpoint = ModbusTcpEndpoint{"127.0.0.1", 502};
  auto client = backend.open_modbus(modbus);
  ASSERT_FALSE(client.is_ok());
  EXPECT_EQ(client.error().code, ErrorCode::kUnavailable);
  EXPECT_THAT(client.error().message, HasSubstr("lift_drive: this hubd is built without Modbus devices"));
  BadgeReaderConfig reader;
  reader.reader = "operator.rfid";
  auto badges = backend.open_badge_reader(reader);
  ASSERT_FALSE(badges.is_ok());
  EXPECT_EQ(badges.error().code, ErrorCode::kUnavailable);
  EXPECT_THAT(badges.error().message,
              HasSubstr("operator.rfid: this hubd is built without badge reader devices"));
  // GPIO is in every program: the GPIO error, not a missing library.
  auto line = backend.open_output(missing_output("lamp.red"));
  ASSERT_FALSE(line.is_ok());
  EXPECT_THAT(line.error().message, HasSubstr("lamp.red: GPIO chip with path '/dev/gpiochip0'"));
}

// cpp-httplib (and the OpenSSL initialisation Debian's build of it does) is not in a process that
// opens no HTTP device: the module hubrt-http.so brings it in with the first open_http. Before the
// module, every program linking the Linux backend had libcpp-httplib among its ELF NEEDED.
// One test for both halves: the order matters and a process cannot unload the module again.
TEST(LinuxBackend, HttpClientLibraryIsLoadedOnlyWhenAnHttpDeviceIsOpened) {
  if (HUBRT_HTTP_MODULE_IN_BUILD_TREE == 0) {
    GTEST_SKIP() << "cross build: hubrt-http.so is found only where a board package installs it";
  }
  LinuxBackend backend(every_device_library());
  EXPECT_THAT(own_mappings(), Not(HasSubstr("libcpp-httplib"))) << "linked in, not loaded on demand";
  auto client = backend.open_http(mir_config());  // connects nothing until a request is sent
  ASSERT_TRUE(client.is_ok()) << client.error().message;
  EXPECT_THAT(own_mappings(), HasSubstr("libcpp-httplib"));
  EXPECT_THAT(own_mappings(), HasSubstr("hubrt-http.so"));
  // The module's own checks still apply.
  HttpConfig no_host = mir_config();
  no_host.host.clear();
  auto refused = backend.open_http(no_host);
  ASSERT_FALSE(refused.is_ok());
  EXPECT_EQ(refused.error().code, ErrorCode::kInvalidArgument);
  EXPECT_THAT(refused.error().message, HasSubstr("no host"));
}

TEST(LinuxBackend, MissingHttpModuleIsAClearErrorNamingTheDeviceAndThePaths) {
  LinuxBackend backend(every_device_library(), {"/nonexistent/lib/hubrt/hubrt-http.so"});
  auto client = backend.open_http(mir_config());
  ASSERT_FALSE(client.is_ok());
  EXPECT_EQ(client.error().code, ErrorCode::kUnavailable);
  EXPECT_THAT(client.error().message, HasSubstr("mir (http://127.0.0.1:8080)"));
  EXPECT_THAT(client.error().message, HasSubstr("the module hubrt-http.so is not installed"));
  EXPECT_THAT(client.error().message, HasSubstr("/nonexistent/lib/hubrt/hubrt-http.so"));
}

TEST(LinuxBackend, AFileWithoutTheEntryPointIsNotTakenForTheHttpModule) {
  // libm is a shared object that loads but is no hubrt module.
  LinuxBackend backend(every_device_library(), {"libm.so.6"});
  auto client = backend.open_http(mir_config());
  ASSERT_FALSE(client.is_ok());
  EXPECT_EQ(client.error().code, ErrorCode::kInternal);
  EXPECT_THAT(client.error().message, HasSubstr("hubrt_http_module_open_v1"));
}

}  // namespace
}  // namespace hubrt::hal
