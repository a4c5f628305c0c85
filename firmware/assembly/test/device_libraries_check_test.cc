// A hub type that opens a device kind its DEVICES do not declare must be caught by `hubd --check`
// on its board, not by a device that never opens on a real board.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "hubrt/assembly/linux_device_libraries.h"

namespace hubrt::assembly {
namespace {

using ::testing::HasSubstr;

hal::BoardRequirements tool_ecu_needs() {
  hal::BoardRequirements required;
  required.hub = "tool_ecu";
  required.inputs = {"tool.button"};
  required.can_buses = {"tool_bus"};
  required.modbus_devices = {"lift_drive"};
  return required;
}

// Stand-ins: the check only asks whether a kind is linked.
Expected<std::unique_ptr<hal::CanBus>> open_no_can(const hal::CanConfig& /*config*/) {
  return make_error(ErrorCode::kUnavailable, "not opened in this test");
}
Expected<std::unique_ptr<hal::ModbusClient>> open_no_modbus(const hal::ModbusConfig& /*config*/) {
  return make_error(ErrorCode::kUnavailable, "not opened in this test");
}

TEST(DeviceLibrariesCheck, EveryRequiredKindLinkedPasses) {
  EXPECT_TRUE(check_device_libraries(
      tool_ecu_needs(),
      {.open_can = &open_no_can, .open_modbus = &open_no_modbus, .open_badge_reader = nullptr}));
}

TEST(DeviceLibrariesCheck, ARequiredKindNotLinkedNamesTheHubTheDeviceAndWhereToDeclareIt) {
  auto no_modbus = check_device_libraries(
      tool_ecu_needs(), {.open_can = &open_no_can, .open_modbus = nullptr, .open_badge_reader = nullptr});
  ASSERT_FALSE(no_modbus);
  EXPECT_EQ(no_modbus.error().code, ErrorCode::kFailedPrecondition);
  EXPECT_THAT(no_modbus.error().message,
              HasSubstr("hub tool_ecu needs Modbus device 'lift_drive' but this hubd links no libmodbus: add "
                        "modbus to DEVICES"));
  EXPECT_THAT(no_modbus.error().message, HasSubstr("hubs/tool_ecu/CMakeLists.txt"));

  auto nothing = check_device_libraries(tool_ecu_needs(), {});
  ASSERT_FALSE(nothing);
  EXPECT_THAT(nothing.error().message, HasSubstr("CAN bus 'tool_bus'"));
}

TEST(DeviceLibrariesCheck, AHubOnGpioAloneNeedsNoDeviceLibrary) {
  hal::BoardRequirements dock;
  dock.hub = "dock_ecu";
  dock.inputs = {"dock.slot.filter_tool"};
  EXPECT_TRUE(check_device_libraries(dock, {}));
  dock.badge_readers = {"operator_rfid"};
  auto reader = check_device_libraries(dock, {});
  ASSERT_FALSE(reader);
  EXPECT_THAT(reader.error().message, HasSubstr("badge reader 'operator_rfid'"));
}

}  // namespace
}  // namespace hubrt::assembly
