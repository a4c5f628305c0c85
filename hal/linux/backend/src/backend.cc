#include "hubrt/hal/linux/backend.h"

#include <string_view>
#include <utility>

#include <fmt/format.h>

#include "hubrt/hal/common/debounced_input.h"
#include "hubrt/hal/httplib/open_http_module.h"
#include "hubrt/hal/linux/gpiod_lines.h"

namespace hubrt::hal {
namespace {

// What opening a device of a kind the program does not link says: which device, and why a board's
// program may lack its library (docs/board-size.md, "Device libraries per hub type").
Error not_linked(std::string_view device, const LinuxDeviceKind& kind) {
  return make_error(ErrorCode::kUnavailable,
                    fmt::format("{}: this hubd is built without {} devices ({}): none of the hub types it "
                                "holds opens one (a board's program links the device libraries of its hub "
                                "type's DEVICES, hubs/<hub type>/CMakeLists.txt)",
                                device, kind.noun, kind.library));
}

}  // namespace

LinuxBackend::LinuxBackend(LinuxDeviceLibraries libraries)
    : LinuxBackend(libraries, httplib_client::default_http_module_paths()) {}

LinuxBackend::LinuxBackend(LinuxDeviceLibraries libraries, std::vector<std::string> http_module_paths)
    : libraries_(libraries), http_module_paths_(std::move(http_module_paths)) {}

Expected<std::unique_ptr<DigitalInput>> LinuxBackend::open_input(const DigitalInputConfig& config) {
  auto input = open_gpiod_input(config);
  if (!input) return input;
  return debounce(std::move(*input), config.debounce);
}

Expected<std::unique_ptr<DigitalOutput>> LinuxBackend::open_output(const DigitalOutputConfig& config) {
  return open_gpiod_output(config);
}

Expected<std::unique_ptr<CanBus>> LinuxBackend::open_can(const CanConfig& config) {
  if (libraries_.open_can == nullptr) return not_linked(config.bus, kLinuxCan);
  return libraries_.open_can(config);
}

Expected<std::unique_ptr<ModbusClient>> LinuxBackend::open_modbus(const ModbusConfig& config) {
  if (libraries_.open_modbus == nullptr) return not_linked(config.device, kLinuxModbus);
  return libraries_.open_modbus(config);
}

Expected<std::unique_ptr<HttpClient>> LinuxBackend::open_http(const HttpConfig& config) {
  return httplib_client::open_http_module_client(http_module_paths_, config);
}

Expected<std::unique_ptr<BadgeReader>> LinuxBackend::open_badge_reader(const BadgeReaderConfig& config) {
  if (libraries_.open_badge_reader == nullptr) return not_linked(config.reader, kLinuxBadgeReader);
  return libraries_.open_badge_reader(config);
}

}  // namespace hubrt::hal
