// The Backend for real hardware: GPIO through libgpiod v1, CAN through SocketCAN raw sockets,
// Modbus through libmodbus, HTTP (REST devices) through cpp-httplib.
#pragma once

#include "hubrt/hal/backend.h"

namespace hubrt::hal {

// Stateless: every open_* call opens its device on its own; devices may outlive nothing but the
// backend (they do not use it, but the Backend contract says so). Inputs with a debounce window
// come wrapped in DebouncedInput. Errors are those of open_gpiod_input / open_gpiod_output
// (gpiod_lines.h), socketcan::open_socketcan (can/) and libmodbus::open_libmodbus (modbus/: a
// TCP drive that does not answer yet still gives a client, which reconnects); see backend.h.
// Thread-safety: as Backend.
class LinuxBackend final : public Backend {
 public:
  LinuxBackend() = default;

  Expected<std::unique_ptr<DigitalInput>> open_input(const DigitalInputConfig& config) override;
  Expected<std::unique_ptr<DigitalOutput>> open_output(const DigitalOutputConfig& config) override;
  Expected<std::unique_ptr<CanBus>> open_can(const CanConfig& config) override;
  Expected<std::unique_ptr<ModbusClient>> open_modbus(const ModbusConfig& config) override;
  // cpp-httplib (http/): errors of httplib_client::open_httplib.
  Expected<std::unique_ptr<HttpClient>> open_http(const HttpConfig& config) override;
  // libevdev or termios, as config.kind says: rfid::open_badge_reader (rfid/).
  Expected<std::unique_ptr<BadgeReader>> open_badge_reader(const BadgeReaderConfig& config) override;
};

}  // namespace hubrt::hal
