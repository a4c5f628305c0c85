// A HAL backend opens devices (GPIO lines, CAN buses, Modbus clients, RFID badge readers). The hub never
// names a backend: hubd picks one (fake or linux) and passes it in, the board file says which chip, line,
// interface or endpoint each device is.
#pragma once

#include <memory>

#include "hubrt/base/status.h"
#include "hubrt/hal/badge_reader.h"
#include "hubrt/hal/can_bus.h"
#include "hubrt/hal/digital_io.h"
#include "hubrt/hal/http_client.h"
#include "hubrt/hal/modbus_client.h"

namespace hubrt::hal {

// Factories fail with an Error whose message names the device (logical name and wiring) and says
// what went wrong, e.g. "dock.slot.smart_tool: GPIO chip 'gpiochip0' not found (no /dev/gpiochip0)".
// Thread-safety: open_* may be called from one thread at a time; the returned devices are
// independent of each other and may outlive nothing but the backend.
class Backend {
 public:
  virtual ~Backend() = default;
  Backend(const Backend&) = delete;
  Backend& operator=(const Backend&) = delete;

  virtual Expected<std::unique_ptr<DigitalInput>> open_input(const DigitalInputConfig& config) = 0;
  virtual Expected<std::unique_ptr<DigitalOutput>> open_output(const DigitalOutputConfig& config) = 0;
  virtual Expected<std::unique_ptr<CanBus>> open_can(const CanConfig& config) = 0;
  virtual Expected<std::unique_ptr<ModbusClient>> open_modbus(const ModbusConfig& config) = 0;
  // An HTTP client for a REST device (a MiR100). Not pure: a backend without HTTP devices (the
  // test doubles) says so. Errors: kNotFound (this backend has none), the backend's own.
  virtual Expected<std::unique_ptr<HttpClient>> open_http(const HttpConfig& config) {
    return make_error(ErrorCode::kNotFound, config.device + ": this backend opens no HTTP devices");
  }
  // An RFID badge reader. Not every backend has them: this default refuses with kNotFound.
  virtual Expected<std::unique_ptr<BadgeReader>> open_badge_reader(const BadgeReaderConfig& config);

 protected:
  Backend() = default;
};

inline Expected<std::unique_ptr<BadgeReader>> Backend::open_badge_reader(const BadgeReaderConfig& config) {
  return make_error(ErrorCode::kNotFound, config.reader + ": this backend has no RFID badge readers");
}

}  // namespace hubrt::hal
