#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "hubrt/assembly/linux_device_libraries.h"

namespace hubrt::assembly {
namespace {

// `what`: the device kind in the message; `library`: what the program would link; `kind`: its name
// in DEVICES.
struct Kind {
  std::string_view what;
  std::string_view library;
  std::string_view kind;
};

Expected<void> linked_for(const std::string& hub, const std::vector<std::string>& devices, bool linked,
                          const Kind& kind) {
  if (linked || devices.empty()) return {};
  return make_error(ErrorCode::kFailedPrecondition,
                    fmt::format("hub {} needs {} '{}' but this hubd links no {}: add {} to DEVICES of "
                                "hubrt_register_hub_type in hubs/{}/CMakeLists.txt",
                                hub, kind.what, devices.front(), kind.library, kind.kind, hub));
}

}  // namespace

Expected<void> check_device_libraries(const hal::BoardRequirements& required,
                                      const hal::LinuxDeviceLibraries& libraries) {
  static constexpr Kind kCan{"CAN bus", "SocketCAN (libsocketcan)", "can"};
  static constexpr Kind kModbus{"Modbus device", "libmodbus", "modbus"};
  static constexpr Kind kBadgeReader{"badge reader", "badge reader library (libevdev, termios)",
                                     "badge_reader"};
  if (auto ok = linked_for(required.hub, required.can_buses, libraries.open_can != nullptr, kCan); !ok)
    return ok;
  if (auto ok = linked_for(required.hub, required.modbus_devices, libraries.open_modbus != nullptr, kModbus);
      !ok)
    return ok;
  return linked_for(required.hub, required.badge_readers, libraries.open_badge_reader != nullptr,
                    kBadgeReader);
}

}  // namespace hubrt::assembly
