// The device libraries this program links for the Linux backend: those of the hub types it holds
// (their DEVICES, hubs/HubTypes.cmake), defined by the same generated registry as hub_types(). A
// board's program holds one hub type, so a Dock ECU's hubd maps neither libmodbus nor libevdev.
#pragma once

#include "hubrt/base/status.h"
#include "hubrt/hal/board/board_requirements.h"
#include "hubrt/hal/linux/backend.h"

namespace hubrt::assembly {

hal::LinuxDeviceLibraries linux_device_libraries() noexcept;

// Whether `libraries` can open every CAN bus, Modbus device and badge reader `required` names: a
// hub type that opens a kind its DEVICES do not declare would find its device unopenable on a real
// board only. Checked by `hubd --check` and before the Linux backend is made (check_hub), so the
// mistake shows on the first check of a board file instead. kFailedPrecondition naming the hub type,
// the device and the kind.
Expected<void> check_device_libraries(const hal::BoardRequirements& required,
                                      const hal::LinuxDeviceLibraries& libraries);

}  // namespace hubrt::assembly
