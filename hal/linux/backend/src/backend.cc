#include "hubrt/hal/linux/backend.h"

#include <utility>

#include "hubrt/hal/common/debounced_input.h"
#include "hubrt/hal/httplib/open_http_module.h"
#include "hubrt/hal/libmodbus/open_libmodbus.h"
#include "hubrt/hal/linux/gpiod_lines.h"
#include "hubrt/hal/rfid/open_badge_reader.h"
#include "hubrt/hal/socketcan/open_socketcan.h"

namespace hubrt::hal {

LinuxBackend::LinuxBackend() : LinuxBackend(httplib_client::default_http_module_paths()) {}

LinuxBackend::LinuxBackend(std::vector<std::string> http_module_paths)
    : http_module_paths_(std::move(http_module_paths)) {}

Expected<std::unique_ptr<DigitalInput>> LinuxBackend::open_input(const DigitalInputConfig& config) {
  auto input = open_gpiod_input(config);
  if (!input) return input;
  return debounce(std::move(*input), config.debounce);
}

Expected<std::unique_ptr<DigitalOutput>> LinuxBackend::open_output(const DigitalOutputConfig& config) {
  return open_gpiod_output(config);
}

Expected<std::unique_ptr<CanBus>> LinuxBackend::open_can(const CanConfig& config) {
  return socketcan::open_socketcan(config);
}

Expected<std::unique_ptr<ModbusClient>> LinuxBackend::open_modbus(const ModbusConfig& config) {
  return libmodbus::open_libmodbus(config);
}

Expected<std::unique_ptr<HttpClient>> LinuxBackend::open_http(const HttpConfig& config) {
  return httplib_client::open_http_module_client(http_module_paths_, config);
}

Expected<std::unique_ptr<BadgeReader>> LinuxBackend::open_badge_reader(const BadgeReaderConfig& config) {
  return rfid::open_badge_reader(config);
}

}  // namespace hubrt::hal
