#include <string>
#include <vector>

#include <fmt/format.h>

#include "hubrt/assembly/linux_device_libraries.h"

namespace hubrt::assembly {
namespace {

Expected<void> linked_for(const std::string& hub, const std::vector<std::string>& devices, bool linked,
                          const hal::LinuxDeviceKind& kind) {
  if (linked || devices.empty()) return {};
  return make_error(ErrorCode::kFailedPrecondition,
                    fmt::format("hub {} needs {} '{}' but this hubd links no {}: add {} to DEVICES of "
                                "hubrt_register_hub_type in hubs/{}/CMakeLists.txt",
                                hub, kind.device, devices.front(), kind.library, kind.declared_as, hub));
}

}  // namespace

Expected<void> check_device_libraries(const hal::BoardRequirements& required,
                                      const hal::LinuxDeviceLibraries& libraries) {
  if (auto ok = linked_for(required.hub, required.can_buses, libraries.open_can != nullptr, hal::kLinuxCan);
      !ok)
    return ok;
  if (auto ok = linked_for(required.hub, required.modbus_devices, libraries.open_modbus != nullptr,
                           hal::kLinuxModbus);
      !ok)
    return ok;
  return linked_for(required.hub, required.badge_readers, libraries.open_badge_reader != nullptr,
                    hal::kLinuxBadgeReader);
}

}  // namespace hubrt::assembly
