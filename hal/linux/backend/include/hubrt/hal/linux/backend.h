// The Backend for real hardware: GPIO through libgpiod v1, CAN through SocketCAN raw sockets,
// Modbus through libmodbus, HTTP (REST devices) through cpp-httplib in a module loaded on demand.
#pragma once

#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "hubrt/hal/backend.h"

namespace hubrt::hal {

// The device libraries a program links beyond GPIO, which every hubd needs (--safe-outputs drives
// GPIO outputs whatever its hub types): SocketCAN, libmodbus and the badge readers (libevdev). A
// board's program links those its hub types open and no other (hubs/HubTypes.cmake, DEVICES; the
// registry defines assembly::linux_device_libraries()), so a Dock ECU does not map libmodbus. Null:
// not linked; opening such a device is a clear error (kUnavailable) naming the device.
struct LinuxDeviceLibraries {
  Expected<std::unique_ptr<CanBus>> (*open_can)(const CanConfig& config) = nullptr;
  Expected<std::unique_ptr<ModbusClient>> (*open_modbus)(const ModbusConfig& config) = nullptr;
  Expected<std::unique_ptr<BadgeReader>> (*open_badge_reader)(const BadgeReaderConfig& config) = nullptr;
};

// Stateless but for the device libraries and where the HTTP module is looked for: every open_* call opens
// its device on its own; devices may outlive nothing but the backend (they do not use it, but the Backend
// contract says so). Inputs with a debounce window come wrapped in DebouncedInput. Errors are those of
// open_gpiod_input / open_gpiod_output (gpiod_lines.h), socketcan::open_socketcan (can/) and
// libmodbus::open_libmodbus (modbus/: a TCP drive that does not answer yet still gives a client, which
// reconnects), or kUnavailable for a kind `libraries` lacks; see backend.h. Thread-safety: as Backend.
// How messages name a device kind that LinuxDeviceLibraries may lack: `noun` (built without CAN
// devices), `device` (needs CAN bus 'x'), `library` (what the program would link) and its name in
// DEVICES. One table for LinuxBackend's errors and assembly::check_device_libraries'.
struct LinuxDeviceKind {
  std::string_view noun;
  std::string_view device;
  std::string_view library;
  std::string_view declared_as;
};
inline constexpr LinuxDeviceKind kLinuxCan{"CAN", "CAN bus", "SocketCAN (libsocketcan)", "can"};
inline constexpr LinuxDeviceKind kLinuxModbus{"Modbus", "Modbus device", "libmodbus", "modbus"};
inline constexpr LinuxDeviceKind kLinuxBadgeReader{
    "badge reader", "badge reader", "badge reader library (libevdev, termios)", "badge_reader"};

class LinuxBackend final : public Backend {
 public:
  // The HTTP client module is looked for where httplib_client::default_http_module_paths() says.
  explicit LinuxBackend(LinuxDeviceLibraries libraries);
  // ... or in `http_module_paths`, in order (tests: a module that is not there).
  LinuxBackend(LinuxDeviceLibraries libraries, std::vector<std::string> http_module_paths);

  Expected<std::unique_ptr<DigitalInput>> open_input(const DigitalInputConfig& config) override;
  Expected<std::unique_ptr<DigitalOutput>> open_output(const DigitalOutputConfig& config) override;
  Expected<std::unique_ptr<CanBus>> open_can(const CanConfig& config) override;
  Expected<std::unique_ptr<ModbusClient>> open_modbus(const ModbusConfig& config) override;
  // cpp-httplib in the module hubrt-http.so, loaded by the first call (http/open_http_module.h):
  // a hub without HTTP devices never maps libcpp-httplib. Errors of
  // httplib_client::open_http_module_client (kUnavailable: the module is not installed).
  Expected<std::unique_ptr<HttpClient>> open_http(const HttpConfig& config) override;
  // libevdev or termios, as config.kind says: rfid::open_badge_reader (rfid/).
  Expected<std::unique_ptr<BadgeReader>> open_badge_reader(const BadgeReaderConfig& config) override;

 private:
  LinuxDeviceLibraries libraries_;
  std::vector<std::string> http_module_paths_;
};

}  // namespace hubrt::hal
